#pragma once
// Shared helpers of the ellipse tests: the pipeline up to the connected paths, the
// exact image of the target's disk for a pose, and points sampled on an ellipse.
#include <Eigen/Dense>
#include <opencv2/core.hpp>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/common/geometry.h"
#include "core/connectivity/connectivity.h"
#include "core/edges/edges.h"
#include "core/ellipse/detect.h"
#include "core/segmentation/histogram.h"
#include "core/segmentation/threshold.h"

namespace imagepro::test {

// Threshold (AT-Mod unless the image is already binary), Laplace edges, CN1 paths.
struct PathPipeline {
  cv::Mat binary;
  EdgeList edges;
  EdgeWorkspace edge_ws;
  ConnectivityWorkspace connect_ws;
  Paths paths;

  Status run(const cv::Mat& grey, int manual_threshold = -1) {
    int t = manual_threshold;
    if (t < 0) {
      Histogram h;
      computeHistogram(grey, h);
      if (const Status st = computeThreshold(ThresholdOptions{}, h, t); !ok(st)) return st;
    }
    binarize(grey, t, binary);
    if (const Status st = detectEdges(EdgeMethod::Laplace, binary, edges, edge_ws); !ok(st)) return st;
    return connectPaths(ConnectivityMethod::CN1, edges, binary.size(), paths, connect_ws);
  }
};

// The exact image of the disk x^2 + y^2 = R^2 of the target plane (no distortion).
inline Ellipse diskImage(const CameraModel& cam, const TargetGeometry& target, const Pose& pose) {
  Eigen::Matrix3d K;
  K << cam.fu(), 0, cam.u0(), 0, cam.fv(), cam.v0(), 0, 0, 1;
  const Eigen::Matrix3d R = rotationMatrix(pose);
  Eigen::Matrix3d H;
  H << R.col(0), R.col(1), translation(pose);
  H = K * H;
  const Eigen::Matrix3d Hi = H.inverse();
  const Eigen::Matrix3d Q = Eigen::Vector3d(1, 1, -target.radius_mm * target.radius_mm).asDiagonal();
  const Eigen::Matrix3d M = Hi.transpose() * Q * Hi;
  Conic c;
  c << M(0, 0), 2 * M(0, 1), M(1, 1), 2 * M(0, 2), 2 * M(1, 2), M(2, 2);
  Ellipse e;
  ellipseFromConic(c / c.norm(), e);
  return e;
}

// n points at equal parameter steps over [from, to) degrees, plus Gaussian noise.
inline std::vector<Eigen::Vector2d> sampleEllipse(const Ellipse& e, int n, double from_deg = 0.0,
                                                  double to_deg = 360.0, double noise = 0.0, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const double t = e.angle_deg * std::numbers::pi / 180.0;
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < n; ++i) {
    const double s = (from_deg + (to_deg - from_deg) * i / n) * std::numbers::pi / 180.0;
    const double x = e.a * std::cos(s), y = e.b * std::sin(s);
    Eigen::Vector2d p(e.cx + x * std::cos(t) - y * std::sin(t), e.cy + x * std::sin(t) + y * std::cos(t));
    if (noise > 0.0) p += noise * Eigen::Vector2d(gauss(rng), gauss(rng));
    pts.push_back(p);
  }
  return pts;
}

// Angle difference modulo 180 degrees.
inline double angleDiffDeg(double a, double b) {
  double d = std::fmod(a - b, 180.0);
  if (d > 90.0) d -= 180.0;
  if (d < -90.0) d += 180.0;
  return d;
}

}  // namespace imagepro::test
