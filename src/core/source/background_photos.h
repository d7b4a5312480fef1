#pragma once
// Photographs behind real-scene frames: a folder of JPEG/PNG files, by
// default the ~100 sample photographs of Debian's opencv-doc package (offices, a
// building, a desk, chessboards, ellipses, dot grids), read as 8-bit grey and cut to
// the camera's size.
#include <opencv2/core.hpp>

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace imagepro {

// $IMAGEPRO_BACKGROUNDS when set, else the folder chosen when the project was built
// (CMake cache variable IMAGEPRO_BACKGROUNDS_DIR, Debian's opencv-doc photographs).
std::string defaultBackgroundsDir();

// The JPEG and PNG files of `dir` (not its sub-folders), sorted by name; empty when
// the folder is missing or holds none.
std::vector<std::string> listBackgrounds(const std::string& dir);

// Scales `photo` (CV_8UC1) to cover `size`, `zoom` (>= 1) times more, and cuts out the
// window at (fx, fy) in [0, 1] of the room left over (0.5, 0.5: the middle).
cv::Mat fitBackground(const cv::Mat& photo, cv::Size size, double zoom, double fx, double fy);

// Reads photographs once each, as grey, and keeps them (thread-safe).
class PhotoCache {
 public:
  // False with `error` naming the file when it cannot be read as an image.
  bool load(const std::string& path, cv::Mat& grey, std::string& error) const;

 private:
  mutable std::mutex mutex_;
  mutable std::map<std::string, cv::Mat> photos_;
};

}  // namespace imagepro
