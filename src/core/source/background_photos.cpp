#include "core/source/background_photos.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#ifndef IMAGEPRO_BACKGROUNDS_DIR
#define IMAGEPRO_BACKGROUNDS_DIR "/usr/share/doc/opencv-doc/examples/data"
#endif

namespace imagepro {

namespace fs = std::filesystem;

std::string defaultBackgroundsDir() {
  const char* env = std::getenv("IMAGEPRO_BACKGROUNDS");
  return env && *env ? std::string(env) : std::string(IMAGEPRO_BACKGROUNDS_DIR);
}

std::vector<std::string> listBackgrounds(const std::string& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    std::string ext = it->path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (ext == ".jpg" || ext == ".jpeg" || ext == ".png") out.push_back(it->path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

cv::Mat fitBackground(const cv::Mat& photo, cv::Size size, double zoom, double fx, double fy) {
  CV_Assert(!photo.empty() && size.width > 0 && size.height > 0);
  const double cover = std::max(static_cast<double>(size.width) / photo.cols, static_cast<double>(size.height) / photo.rows);
  const double scale = cover * std::max(zoom, 1.0);
  const cv::Size scaled(std::max(size.width, static_cast<int>(std::ceil(photo.cols * scale))),
                        std::max(size.height, static_cast<int>(std::ceil(photo.rows * scale))));
  cv::Mat resized;
  cv::resize(photo, resized, scaled, 0, 0, scale < 1.0 ? cv::INTER_AREA : cv::INTER_LINEAR);
  const int x = static_cast<int>(std::lround(std::clamp(fx, 0.0, 1.0) * (scaled.width - size.width)));
  const int y = static_cast<int>(std::lround(std::clamp(fy, 0.0, 1.0) * (scaled.height - size.height)));
  return resized(cv::Rect(x, y, size.width, size.height)).clone();
}

bool PhotoCache::load(const std::string& path, cv::Mat& grey, std::string& error) const {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = photos_.find(path);
    if (it != photos_.end()) {
      grey = it->second;
      return true;
    }
  }
  cv::Mat read;
  try {
    read = cv::imread(path, cv::IMREAD_GRAYSCALE);
  } catch (const cv::Exception& e) {
    error = path + ": cannot be read (" + e.err + ")";
    return false;
  }
  if (read.empty()) {
    error = path + ": not a readable image";
    return false;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  photos_[path] = read;
  grey = read;
  return true;
}

}  // namespace imagepro
