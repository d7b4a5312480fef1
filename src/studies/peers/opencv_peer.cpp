#include "studies/peers/opencv_peer.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <Eigen/Core>
#include <opencv2/core/eigen.hpp>

#include <cmath>

namespace imagepro::studies {

namespace {

constexpr int kRimSamples = 16;

cv::Point2f centroid(const std::vector<cv::Point>& contour) {
  const cv::Moments m = cv::moments(contour);
  if (std::abs(m.m00) < 1e-9) return contour.empty() ? cv::Point2f() : cv::Point2f(contour[0]);
  return {static_cast<float>(m.m10 / m.m00), static_cast<float>(m.m01 / m.m00)};
}

}  // namespace

Status opencvPeerPose(const cv::Mat& grey, const CameraModel& camera, const TargetGeometry& target,
                      OpenCvPeerWorkspace& ws, Pose& out) {
  if (grey.empty()) return Status::EmptyFrame;
  cv::threshold(grey, ws.binary, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
  cv::findContours(ws.binary, ws.contours, ws.hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_NONE);

  // The target: an outer contour that is a good ellipse with exactly two holes.
  int best = -1;
  double best_area = 0.0;
  cv::RotatedRect best_ellipse;
  for (int i = 0; i < static_cast<int>(ws.contours.size()); ++i) {
    if (ws.hierarchy[i][3] >= 0 || ws.contours[i].size() < 20) continue;
    int holes = 0;
    for (int c = ws.hierarchy[i][2]; c >= 0; c = ws.hierarchy[c][0]) ++holes;
    if (holes != 2) continue;
    const cv::RotatedRect e = cv::fitEllipseDirect(ws.contours[i]);
    const double area = M_PI * e.size.width * e.size.height / 4.0;
    const double contour_area = cv::contourArea(ws.contours[i]);
    if (!(area > 0) || std::abs(contour_area - area) > 0.05 * area) continue;
    if (area > best_area) {
      best = i;
      best_area = area;
      best_ellipse = e;
    }
  }
  if (best < 0) return Status::NoTarget;

  const int hole_a = ws.hierarchy[best][2];
  const int hole_b = ws.hierarchy[hole_a][0];
  cv::Point2f spot_a = centroid(ws.contours[hole_a]);
  cv::Point2f spot_b = centroid(ws.contours[hole_b]);
  const cv::Point2f centre = best_ellipse.center;
  if (cv::norm(spot_b - centre) < cv::norm(spot_a - centre)) std::swap(spot_a, spot_b);
  // spot_a: centre spot, spot_b: offset spot.

  // Affine map of the unit circle onto the ellipse, and the rim angle of the offset spot.
  const double th = best_ellipse.angle * M_PI / 180.0;
  const double ax = best_ellipse.size.width / 2.0, by = best_ellipse.size.height / 2.0;
  cv::Matx22d A(std::cos(th) * ax, -std::sin(th) * by, std::sin(th) * ax, std::cos(th) * by);
  const cv::Vec2d d = A.inv() * cv::Vec2d(spot_b.x - spot_a.x, spot_b.y - spot_a.y);
  const double phi0 = std::atan2(d[1], d[0]);
  const bool mirrored = A(0, 0) * A(1, 1) - A(0, 1) * A(1, 0) < 0;

  ws.object_points.clear();
  ws.image_points.clear();
  for (int k = 0; k < kRimSamples; ++k) {
    const double phi = 2.0 * M_PI * k / kRimSamples;
    const double s = mirrored ? -1.0 : 1.0;
    const cv::Vec2d p = A * cv::Vec2d(std::cos(phi0 + s * phi), std::sin(phi0 + s * phi));
    ws.image_points.emplace_back(static_cast<float>(centre.x + p[0]), static_cast<float>(centre.y + p[1]));
    ws.object_points.emplace_back(static_cast<float>(target.radius_mm * std::cos(phi)),
                                  static_cast<float>(target.radius_mm * std::sin(phi)), 0.0f);
  }
  ws.image_points.push_back(spot_a);
  ws.object_points.emplace_back(0.0f, 0.0f, 0.0f);
  ws.image_points.push_back(spot_b);
  ws.object_points.emplace_back(static_cast<float>(target.spot_offset_mm), 0.0f, 0.0f);

  const cv::Matx33d K(camera.fu(), 0, camera.u0(), 0, camera.fv(), camera.v0(), 0, 0, 1);
  cv::Vec3d rvec, tvec;
  if (!cv::solvePnP(ws.object_points, ws.image_points, K, cv::noArray(), rvec, tvec, false, cv::SOLVEPNP_IPPE))
    return Status::SingularConic;
  cv::Matx33d Rcv;
  cv::Rodrigues(rvec, Rcv);
  Eigen::Matrix3d R;
  cv::cv2eigen(Rcv, R);
  out = poseFromRt(R, Eigen::Vector3d(tvec[0], tvec[1], tvec[2]));
  return Status::Ok;
}

}  // namespace imagepro::studies
