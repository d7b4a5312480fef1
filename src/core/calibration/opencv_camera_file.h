#pragma once
// OpenCV's camera file, as its calibration sample and ROS's tools read it: cv::FileStorage
// YAML or JSON with `camera_matrix` (3x3), `distortion_coefficients` (k1, k2, p1, p2[, k3,
// ...]), `image_width` and `image_height`. Written from a calibration (intrinsics.h) or
// any camera of the settings, and read so a camera calibrated elsewhere can be used here:
// its distortion is brought into this project's model (eq. 4.7) by the least-squares fit
// of intrinsics.h, its d0 for the settings' x pixel size.
#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include "core/common/geometry.h"

namespace imagepro {

struct IntrinsicsResult;

struct OpenCvCamera {
  int width = 0, height = 0;
  cv::Matx33d camera_matrix = cv::Matx33d::eye();
  std::vector<double> distortion;  // OpenCV's order
};

// The file's text: JSON when `json`, else YAML.
std::string openCvCameraText(const OpenCvCamera& camera, bool json);
// Written atomically; JSON for a path ending in .json, YAML otherwise. False with `error`.
bool writeOpenCvCamera(const std::string& path, const OpenCvCamera& camera, std::string& error);
// False with `error` naming the file and what is missing or wrong.
bool readOpenCvCamera(const std::string& path, OpenCvCamera& camera, std::string& error);

// A full intrinsic calibration's camera as OpenCV found it (its distortion as fitted, not
// through this project's model).
OpenCvCamera openCvCameraOf(const IntrinsicsResult& result);
// This project's camera in OpenCV's terms (its distortion fitted, exact for square pixels).
OpenCvCamera openCvCameraOf(const CameraModel& camera);
// OpenCV's camera into `camera`: size, principal point, d0 = fx * sx, sy = d0 / fy, the
// distortion fitted (`fit_rms_px`: what the fit leaves of OpenCV's field).
void applyOpenCvCamera(const OpenCvCamera& opencv, CameraModel& camera, double* fit_rms_px = nullptr);

}  // namespace imagepro
