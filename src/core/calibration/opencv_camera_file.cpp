#include "core/calibration/opencv_camera_file.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/calibration/intrinsics.h"
#include "core/common/atomic_file.h"

namespace imagepro {
namespace {

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

std::string openCvCameraText(const OpenCvCamera& camera, bool json) {
  cv::FileStorage fs(json ? ".json" : ".yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY |
                                                   (json ? cv::FileStorage::FORMAT_JSON : cv::FileStorage::FORMAT_YAML));
  fs << "image_width" << camera.width;
  fs << "image_height" << camera.height;
  fs << "camera_matrix" << cv::Mat(camera.camera_matrix);
  fs << "distortion_coefficients" << cv::Mat(camera.distortion).reshape(1, 1);
  return fs.releaseAndGetString();
}

bool writeOpenCvCamera(const std::string& path, const OpenCvCamera& camera, std::string& error) {
  return writeFileAtomically(path, openCvCameraText(camera, endsWith(path, ".json")), error);
}

bool readOpenCvCamera(const std::string& path, OpenCvCamera& camera, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = path + ": cannot be read";
    return false;
  }
  std::stringstream text;
  text << in.rdbuf();
  try {
    cv::FileStorage fs(text.str(), cv::FileStorage::READ | cv::FileStorage::MEMORY);
    if (!fs.isOpened()) {
      error = path + ": not an OpenCV FileStorage file (YAML, JSON or XML)";
      return false;
    }
    cv::Mat K, D;
    fs["camera_matrix"] >> K;
    fs["distortion_coefficients"] >> D;
    OpenCvCamera c;
    fs["image_width"] >> c.width;
    fs["image_height"] >> c.height;
    if (K.rows != 3 || K.cols != 3) {
      error = path + ": camera_matrix is missing or not 3x3";
      return false;
    }
    K.convertTo(K, CV_64F);
    c.camera_matrix = cv::Matx33d(reinterpret_cast<const double*>(K.data));
    if (!D.empty()) {
      D.convertTo(D, CV_64F);
      D = D.reshape(1, 1);
      c.distortion.assign(D.ptr<double>(), D.ptr<double>() + D.cols);
    }
    const size_t n = c.distortion.size();
    if (n != 0 && n != 4 && n != 5 && n != 8 && n != 12 && n != 14) {
      error = path + ": distortion_coefficients has " + std::to_string(n) + " values (OpenCV takes 4, 5, 8, 12 or 14)";
      return false;
    }
    if (c.width <= 0 || c.height <= 0) {
      error = path + ": image_width and image_height must be given and above 0";
      return false;
    }
    const double fx = c.camera_matrix(0, 0), fy = c.camera_matrix(1, 1);
    bool finite = std::isfinite(fx) && std::isfinite(fy);
    for (const double d : c.distortion) finite = finite && std::isfinite(d);
    if (!finite || !(fx > 0) || !(fy > 0)) {
      error = path + ": camera_matrix needs positive focal lengths and finite values";
      return false;
    }
    camera = c;
    return true;
  } catch (const cv::Exception& e) {
    error = path + ": " + e.err;
    return false;
  }
}

OpenCvCamera openCvCameraOf(const IntrinsicsResult& r) {
  OpenCvCamera oc;
  oc.width = r.width;
  oc.height = r.height;
  oc.camera_matrix = cv::Matx33d(r.fx, 0, r.cx, 0, r.fy, r.cy, 0, 0, 1);
  oc.distortion.assign(r.opencv_dist.begin(), r.opencv_dist.end());
  return oc;
}

OpenCvCamera openCvCameraOf(const CameraModel& camera) {
  OpenCvCamera c;
  c.width = camera.width;
  c.height = camera.height;
  c.camera_matrix = cameraMatrix(camera);
  const std::array<double, 5> d = openCvFromDistortion(camera);
  c.distortion.assign(d.begin(), d.end());
  return c;
}

void applyOpenCvCamera(const OpenCvCamera& opencv, CameraModel& camera, double* fit_rms_px) {
  IntrinsicsResult r;
  r.width = opencv.width;
  r.height = opencv.height;
  r.fx = opencv.camera_matrix(0, 0);
  r.fy = opencv.camera_matrix(1, 1);
  r.cx = opencv.camera_matrix(0, 2);
  r.cy = opencv.camera_matrix(1, 2);
  r.distortion = distortionFromOpenCv(opencv.camera_matrix, opencv.distortion, opencv.width, opencv.height,
                                      fit_rms_px);
  applyIntrinsics(r, camera);
}

}  // namespace imagepro
