#pragma once
// A printed sheet "photographed": a sheet image (the page drawn at some pixels per mm)
// seen by a camera with its lens at a pose, by cv::remap (every camera sample's ray,
// undistorted by inverting eq. 4.7, is met with the sheet's plane), supersampled, then
// optionally lit unevenly, blurred and noisy. No code of the Virtual source's renderer.
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>

#include "core/common/geometry.h"

namespace imagepro::testing {

// Where the pattern's plane lies on a sheet image: the sheet pixel of the pattern's origin
// and the scale; +X right, +Y down on the sheet.
struct SheetFrame {
  double origin_x_px = 0.0, origin_y_px = 0.0;
  double px_per_mm = 4.0;
};

struct PhotoConditions {
  int supersampling = 3;     // camera image drawn this much finer, then averaged
  double blur_sigma_px = 0.7;
  double noise_sigma = 2.0;
  unsigned char beyond = 110;  // grey level beyond the sheet
  // Uneven light: brightness times 1 - gradient * u / width, and a spotlight of gain
  // 1 + spot at (spot_x, spot_y) (image fractions), Gaussian of spot_width image widths.
  double gradient = 0.0;
  double spot = 0.0, spot_x = 0.3, spot_y = 0.3, spot_width = 0.3;
  unsigned seed = 1;
};

inline cv::Mat photograph(const cv::Mat& sheet, const SheetFrame& frame, const CameraModel& camera, const Pose& pose,
                          const PhotoConditions& c) {
  const int ss = c.supersampling;
  const int w = camera.width * ss, h = camera.height * ss;
  cv::Mat mapX(h, w, CV_32FC1), mapY(h, w, CV_32FC1);
  const Eigen::Matrix3d R = rotationMatrix(pose);
  const Eigen::Vector3d T = translation(pose), n = R.col(2);
  const Eigen::Vector2d pp(camera.u0(), camera.v0());
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const Eigen::Vector2d seen((i + 0.5) / ss - 0.5, (j + 0.5) / ss - 0.5);
      // Invert eq. 4.7 (seen = ideal + delta(ideal)) by fixed-point iteration.
      Eigen::Vector2d ideal = seen;
      for (int k = 0; k < 30; ++k) {
        const Eigen::Vector2d next = seen - distortionDelta(camera.distortion, ideal - pp);
        const bool settled = (next - ideal).squaredNorm() < 1e-14;
        ideal = next;
        if (settled) break;
      }
      const Eigen::Vector3d ray = backProjectIdeal(camera, ideal);
      const double along = n.dot(ray);
      const Eigen::Vector3d onPlane = R.transpose() * (n.dot(T) / along * ray - T);
      const bool front = along != 0.0 && n.dot(T) / along > 0.0;
      mapX.at<float>(j, i) = front ? static_cast<float>(frame.origin_x_px + onPlane.x() * frame.px_per_mm) : -1e6f;
      mapY.at<float>(j, i) = front ? static_cast<float>(frame.origin_y_px + onPlane.y() * frame.px_per_mm) : -1e6f;
    }
  cv::Mat fine;
  cv::remap(sheet, fine, mapX, mapY, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(c.beyond));
  cv::Mat fineF, image;
  fine.convertTo(fineF, CV_32F);
  cv::resize(fineF, image, cv::Size(camera.width, camera.height), 0, 0, cv::INTER_AREA);
  if (c.gradient != 0.0 || c.spot != 0.0)
    for (int v = 0; v < image.rows; ++v)
      for (int u = 0; u < image.cols; ++u) {
        const double x = static_cast<double>(u) / image.cols, y = static_cast<double>(v) / image.cols;
        const double dx = x - c.spot_x, dy = y - c.spot_y * image.rows / image.cols;
        const double gain = (1.0 - c.gradient * x) *
                            (1.0 + c.spot * std::exp(-(dx * dx + dy * dy) / (2.0 * c.spot_width * c.spot_width)));
        image.at<float>(v, u) *= static_cast<float>(gain);
      }
  if (c.blur_sigma_px > 0) cv::GaussianBlur(image, image, cv::Size(), c.blur_sigma_px);
  cv::Mat noise(image.size(), CV_32F);
  cv::RNG rng(c.seed);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, c.noise_sigma);
  cv::Mat out;
  cv::Mat(image + noise).convertTo(out, CV_8U);
  return out;
}

}  // namespace imagepro::testing
