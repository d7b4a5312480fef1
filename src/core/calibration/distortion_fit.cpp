#include "core/calibration/distortion_fit.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/reconstruction/undistort.h"

namespace imagepro {
namespace {

Eigen::Vector4d asVector(const Distortion& d) { return {d.k1, d.k2, d.p1, d.p2}; }

// The image corners relative to the principal point: where each parameter acts most.
std::array<Eigen::Vector2d, 4> corners(const CameraModel& camera) {
  const double l = -0.5 - camera.u0(), r = camera.width - 0.5 - camera.u0();
  const double t = -0.5 - camera.v0(), b = camera.height - 0.5 - camera.v0();
  return {Eigen::Vector2d(l, t), Eigen::Vector2d(r, t), Eigen::Vector2d(l, b), Eigen::Vector2d(r, b)};
}

}  // namespace

Eigen::Matrix<double, 2, 4> distortionDesignRows(const Eigen::Vector2d& q) {
  const double u = q.x(), v = q.y();
  const double r2 = u * u + v * v;
  Eigen::Matrix<double, 2, 4> rows;
  rows << u * r2, u * r2 * r2, 2.0 * u * v, r2 + 2.0 * u * u,  //
      v * r2, v * r2 * r2, r2 + 2.0 * v * v, 2.0 * u * v;
  return rows;
}

Status fitDistortion(std::span<const DistortionSample> samples, Distortion& out) {
  if (static_cast<int>(samples.size()) < kMinDistortionSamples) return Status::TooFewMatches;
  const Eigen::Index n = static_cast<Eigen::Index>(samples.size());
  Eigen::MatrixXd A(2 * n, 4);
  Eigen::VectorXd b(2 * n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const DistortionSample& s = samples[static_cast<size_t>(i)];
    if (!s.undistorted.allFinite() || !s.delta.allFinite()) return Status::DegenerateFit;
    A.middleRows<2>(2 * i) = distortionDesignRows(s.undistorted);
    b.segment<2>(2 * i) = s.delta;
  }
  const Eigen::Vector4d scale = A.colwise().norm().transpose();
  if (!(scale.minCoeff() > 0.0)) return Status::DegenerateFit;
  const Eigen::MatrixXd As = A * scale.cwiseInverse().asDiagonal();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(As);
  qr.setThreshold(1e-10);
  if (qr.rank() < 4) return Status::DegenerateFit;
  const Eigen::Vector4d x = qr.solve(b).cwiseQuotient(scale);
  if (!x.allFinite()) return Status::DegenerateFit;
  out = {x[0], x[1], x[2], x[3]};
  return Status::Ok;
}

Pose correctedPose(const Pose& pose, const PoseCorrection& c) {
  const Eigen::Vector3d w = c.head<3>();
  const double angle = w.norm();
  const Eigen::Matrix3d dR =
      angle > 0.0 ? Eigen::AngleAxisd(angle, w / angle).toRotationMatrix() : Eigen::Matrix3d::Identity();
  return poseFromRt(dR * rotationMatrix(pose), dR * translation(pose) + c.tail<3>());
}

Eigen::Matrix<double, 2, 6> poseJacobian(const CameraModel& camera, const Eigen::Vector3d& P) {
  const double iz = 1.0 / P.z();
  Eigen::Matrix<double, 2, 3> dq;  // d(ideal pixel)/dP
  dq << camera.fu() * iz, 0.0, -camera.fu() * P.x() * iz * iz,  //
      0.0, camera.fv() * iz, -camera.fv() * P.y() * iz * iz;
  Eigen::Matrix<double, 3, 6> dP;  // dP/d(w, t) at zero: w x P + t
  Eigen::Matrix3d skew;
  skew << 0.0, -P.z(), P.y(), P.z(), 0.0, -P.x(), -P.y(), P.x(), 0.0;
  dP << -skew, Eigen::Matrix3d::Identity();
  const Eigen::Vector2d rel = projectIdeal(camera, P) - Eigen::Vector2d(camera.u0(), camera.v0());
  const Eigen::Matrix2d seen = Eigen::Matrix2d::Identity() + distortionWithJacobian(camera.distortion, rel).J;
  return seen * dq * dP;
}

Status fitDistortionAndPoses(std::span<const DistortionSample> samples, Distortion& out,
                             std::vector<PoseCorrection>& corrections) {
  if (static_cast<int>(samples.size()) < kMinDistortionSamples) return Status::TooFewMatches;
  // One block of six columns per image that has samples.
  int images = 0;
  for (const DistortionSample& s : samples) images = std::max(images, s.image + 1);
  std::vector<int> block(static_cast<size_t>(images), -1);
  int blocks = 0;
  for (const DistortionSample& s : samples)
    if (s.image >= 0 && block[s.image] < 0) block[s.image] = blocks++;
  const Eigen::Index n = static_cast<Eigen::Index>(samples.size());
  const Eigen::Index cols = 4 + 6 * blocks;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, cols);
  Eigen::VectorXd b(2 * n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const DistortionSample& s = samples[static_cast<size_t>(i)];
    if (!s.undistorted.allFinite() || !s.delta.allFinite() || !s.pose_jacobian.allFinite())
      return Status::DegenerateFit;
    A.block<2, 4>(2 * i, 0) = distortionDesignRows(s.undistorted);
    if (s.image >= 0) A.block<2, 6>(2 * i, 4 + 6 * block[s.image]) = s.pose_jacobian;
    b.segment<2>(2 * i) = s.delta;
  }
  const Eigen::VectorXd scale = A.colwise().norm().transpose();
  if (!(scale.minCoeff() > 0.0)) return Status::DegenerateFit;
  const Eigen::MatrixXd As = A * scale.cwiseInverse().asDiagonal();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(As);
  qr.setThreshold(1e-10);
  if (qr.rank() < cols) return Status::DegenerateFit;
  const Eigen::VectorXd x = qr.solve(b).cwiseQuotient(scale);
  if (!x.allFinite()) return Status::DegenerateFit;
  out = {x[0], x[1], x[2], x[3]};
  corrections.assign(static_cast<size_t>(images), PoseCorrection::Zero());
  for (int im = 0; im < images; ++im)
    if (block[im] >= 0) corrections[im] = x.segment<6>(4 + 6 * block[im]);
  return Status::Ok;
}

double rmsResidualPx(const Distortion& d, std::span<const DistortionSample> samples,
                     std::span<const PoseCorrection> corrections) {
  if (samples.empty()) return 0.0;
  double sum = 0.0;
  for (const DistortionSample& s : samples) {
    Eigen::Vector2d model = distortionDelta(d, s.undistorted);
    if (s.image >= 0 && s.image < static_cast<int>(corrections.size())) model += s.pose_jacobian * corrections[s.image];
    sum += (s.delta - model).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(samples.size()));
}

double relativeParameterChange(const CameraModel& camera, const Distortion& previous, const Distortion& next) {
  Eigen::Vector4d effect = Eigen::Vector4d::Zero();  // px per unit of each parameter
  for (const Eigen::Vector2d& c : corners(camera))
    effect = effect.cwiseMax(distortionDesignRows(c).colwise().norm().transpose());
  const Eigen::Vector4d a = asVector(previous), b = asVector(next);
  double worst = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double reference = std::max(std::abs(b[k]) * effect[k], kNegligibleEffectPx);
    worst = std::max(worst, std::abs(b[k] - a[k]) * effect[k] / reference);
  }
  return worst;
}

DisplacementField displacementField(const CameraModel& camera, const Distortion& d) {
  const Eigen::Vector2d pp(camera.u0(), camera.v0());
  return [d, pp](const Eigen::Vector2d& q) { return distortionDelta(d, q - pp); };
}

FieldComparison compareDisplacementFields(const CameraModel& camera, const DisplacementField& a,
                                          const DisplacementField& b) {
  FieldComparison c;
  double sum = 0.0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const Eigen::Vector2d q(x, y);
      const double e = (a(q) - b(q)).norm();
      sum += e * e;
      c.max_px = std::max(c.max_px, e);
    }
  const double n = static_cast<double>(camera.width) * camera.height;
  c.rms_px = n > 0 ? std::sqrt(sum / n) : 0.0;
  return c;
}

FieldComparison compareDistortionFields(const CameraModel& camera, const Distortion& a, const Distortion& b) {
  const Distortion diff{a.k1 - b.k1, a.k2 - b.k2, a.p1 - b.p1, a.p2 - b.p2};  // eq. 4.7 is linear in them
  const DisplacementField zero = [](const Eigen::Vector2d&) { return Eigen::Vector2d(0.0, 0.0); };
  return compareDisplacementFields(camera, displacementField(camera, diff), zero);
}

bool distortionPlausible(const CameraModel& camera, const Distortion& d) {
  if (!asVector(d).allFinite()) return false;
  const double limit = 0.25 * std::hypot(camera.width, camera.height);
  const double h = 0.5;  // px, central differences
  // Pixel centres every 16 px, and the last row and column.
  auto steps = [](int n) {
    std::vector<double> s;
    for (int i = 0; i < n; i += 16) s.push_back(i);
    if (n > 0 && s.back() != n - 1) s.push_back(n - 1);
    return s;
  };
  const std::vector<double> xs = steps(camera.width), ys = steps(camera.height);
  for (const double y : ys)
    for (const double x : xs) {
      const Eigen::Vector2d q(x - camera.u0(), y - camera.v0());
      if (!(distortionDelta(d, q).norm() < limit)) return false;
      const Eigen::Vector2d du = (distortionDelta(d, q + Eigen::Vector2d(h, 0)) -
                                  distortionDelta(d, q - Eigen::Vector2d(h, 0))) / (2 * h);
      const Eigen::Vector2d dv = (distortionDelta(d, q + Eigen::Vector2d(0, h)) -
                                  distortionDelta(d, q - Eigen::Vector2d(0, h))) / (2 * h);
      const double det = (1.0 + du.x()) * (1.0 + dv.y()) - du.y() * dv.x();
      if (!(det > 0.5)) return false;
    }
  return true;
}

}  // namespace imagepro
