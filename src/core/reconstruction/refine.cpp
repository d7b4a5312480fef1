#include "core/reconstruction/refine.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "core/reconstruction/pose.h"
#include "core/reconstruction/reconstruct.h"

namespace imagepro {

namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// How the spots are weighed against the rim. A spot's centroid is one measurement of one
// point; the rim's N edge points together fix the rim's image, its centre to about
// sigma * sqrt(2 / N) per coordinate for an edge point's error sigma. Measured on rendered
// frames at their true pose (noise 0-3, blur 0-1 px, 0-15 deg of tilt), a spot's centroid
// errs about 3 times as much as that (median 0.017 px against an edge point's RMS 0.048 px
// over about 160 points). So each spot coordinate gets the weight N / (2 * 3^2) of one
// edge point: together the spots count about as much as the rim's position, whatever N.
// Ratios 2, 3 and 4.5 were tried in the accuracy study (docs/reconstruction.md).
constexpr double kSpotToRimCentreError = 3.0;

constexpr int kMaxIterations = 8;
// A step this small changes nothing that can be measured (6e-5 deg, 1e-5 of the distance):
// the pose is not moved by it and no further pass is made.
constexpr double kSmallTurnRad = 1e-6;
constexpr double kSmallShiftFraction = 1e-5;
constexpr double kNegligibleGain = 1e-9;
// A refinement corrects the analytic pose; a larger move means it went to another solution.
constexpr double kMaxTurnDeg = 10.0;
constexpr double kMaxShiftFraction = 0.1;

struct Evaluation {
  double cost = 0.0;
  double rimSumOfSquares = 0.0;
  int rimPoints = 0;
  std::array<double, 2> spotErrors{};
  Matrix6d JtJ = Matrix6d::Zero();
  Vector6d Jtr = Vector6d::Zero();
};

struct Problem {
  const CameraModel& cam;
  const TargetGeometry& target;
  std::span<const Eigen::Vector2d> contour;
  std::array<Eigen::Vector2d, 2> spots;
  double spotWeight;
};

void accumulate(Evaluation& e, const Vector6d& j, double r, double weight) {
  e.JtJ.noalias() += weight * j * j.transpose();
  e.Jtr += weight * r * j;
  e.cost += weight * r * r;
}

// Residuals and their normal equations at (R, T); parameters (d1, d2, d3, tx, ty, tz) of
// R exp([d]x), T + t. False when the target plane's homography is singular (the plane
// through the camera centre) or a spot lies behind the camera.
bool evaluate(const Problem& p, const Eigen::Matrix3d& R, const Eigen::Vector3d& T, Evaluation& e) {
  e = Evaluation{};
  const CameraModel& cam = p.cam;
  const double fu = cam.fu(), fv = cam.fv(), u0 = cam.u0(), v0 = cam.v0();
  Eigen::Matrix3d K;
  K << fu, 0.0, u0, 0.0, fv, v0, 0.0, 0.0, 1.0;
  Eigen::Matrix3d H;  // target plane (x, y, 1) -> image (homogeneous)
  H << K * R.col(0), K * R.col(1), K * T;
  const double det = H.determinant();
  if (!(std::abs(det) > 1e-12 * H.col(0).norm() * H.col(1).norm() * H.col(2).norm())) return false;
  const Eigen::Matrix3d G = H.inverse();  // image -> target plane
  if (!G.allFinite()) return false;

  // Rim. With q = G (u, v, 1) the point on the plane (homogeneous) and S = diag(1, 1, -R^2),
  // f = q'Sq is the conic's value, grad f = 2 (m0, m1) with m = G'Sq, and the Sampson
  // distance is f / |grad f|. A change dH = K D of H = K [r1 r2 T] moves q by -G K D q and m
  // by G'(S dq - D'K'm). As G K r1 = e1, G K r2 = e2 and G K T = e3, the turns d1, d2 move q
  // along a3 = G K r3 and the shift t_k along column k of G K; the turn d3 about the normal
  // moves the rim along itself and changes nothing. Everything that does not depend on the
  // point is taken out of the loop: per point about 60 operations.
  const double R2 = p.target.radius_mm * p.target.radius_mm;
  const Eigen::Matrix3d M = G * K;
  const Eigen::Vector3d a3 = M * R.col(2), r3 = R.col(2);
  const Eigen::Vector3d g0 = G.col(0), g1 = G.col(1);
  auto S = [R2](const Eigen::Vector3d& x) { return Eigen::Vector3d(x.x(), x.y(), -R2 * x.z()); };
  const Eigen::Vector2d A(g0.dot(S(a3)), g1.dot(S(a3)));  // G' S a3, first two components
  Eigen::Matrix<double, 2, 3> B;                          // G' S M, first two rows
  for (int k = 0; k < 3; ++k) B.col(k) = Eigen::Vector2d(g0.dot(S(M.col(k))), g1.dot(S(M.col(k))));
  double JtJ[5][5] = {}, Jtr[5] = {};  // d1, d2, tx, ty, tz; upper triangle
  for (const Eigen::Vector2d& pt : p.contour) {
    const Eigen::Vector3d q = g0 * pt.x() + g1 * pt.y() + G.col(2);
    const Eigen::Vector3d s = S(q);
    const double f = q.dot(s);
    const Eigen::Vector3d m = G.transpose() * s;
    const double mm = std::sqrt(m.x() * m.x() + m.y() * m.y());
    if (!(mm > 0.0) || !std::isfinite(f)) continue;
    const double im = 1.0 / mm, ig = 0.5 * im;  // ig = 1 / |grad f|
    const double d = f * ig;
    const Eigen::Vector3d n(fu * m.x(), fv * m.y(), u0 * m.x() + v0 * m.y() + m.z());  // K'm
    const double r3n = r3.dot(n);
    const double sa3 = s.dot(a3);
    const Eigen::Vector3d sM = M.transpose() * s;
    // (df, dm0, dm1) per parameter, then dd = (df - d * dg) / |grad f| with dg = 2 m.dm / |m|.
    double j[5];
    const double mx = 2.0 * d * m.x() * im, my = 2.0 * d * m.y() * im;
    auto put = [&](int k, double df, double dm0, double dm1) { j[k] = (df - mx * dm0 - my * dm1) * ig; };
    // d1: dq = -q1 a3, D'n = (0, r3.n, 0); d2: dq = q0 a3, D'n = (-r3.n, 0, 0);
    // t_k: dq = -q2 (G K)_k, D'n = (0, 0, n_k).
    put(0, -2.0 * q.y() * sa3, -q.y() * A.x() - g0.y() * r3n, -q.y() * A.y() - g1.y() * r3n);
    put(1, 2.0 * q.x() * sa3, q.x() * A.x() + g0.x() * r3n, q.x() * A.y() + g1.x() * r3n);
    for (int k = 0; k < 3; ++k)
      put(2 + k, -2.0 * q.z() * sM(k), -q.z() * B(0, k) - g0.z() * n(k), -q.z() * B(1, k) - g1.z() * n(k));
    for (int a = 0; a < 5; ++a) {
      Jtr[a] += d * j[a];
      for (int b = a; b < 5; ++b) JtJ[a][b] += j[a] * j[b];
    }
    e.cost += d * d;
    e.rimSumOfSquares += d * d;
    ++e.rimPoints;
  }
  constexpr std::array<int, 5> kRimParameter{0, 1, 3, 4, 5};
  for (int a = 0; a < 5; ++a) {
    e.Jtr(kRimParameter[a]) = Jtr[a];
    for (int b = a; b < 5; ++b)
      e.JtJ(kRimParameter[a], kRimParameter[b]) = e.JtJ(kRimParameter[b], kRimParameter[a]) = JtJ[a][b];
  }

  // Spots: the image of (x, 0, 0) plus its perspective centroid offset, which depends on
  // the pose only weakly (a second-order term, left out of the Jacobian).
  for (int i = 0; i < 2; ++i) {
    const double x = i == 0 ? 0.0 : p.target.spot_offset_mm;
    const Eigen::Vector3d P = x * R.col(0) + T;
    if (!(P.z() > 0.0)) return false;
    Eigen::Vector2d predicted = projectIdeal(cam, P);
    Eigen::Vector2d bias;
    if (p.target.spot_radius_mm > 0.0 && spotCentroidOffset(cam, R, T, x, 0.0, p.target.spot_radius_mm, bias) &&
        bias.allFinite())
      predicted += bias;
    const Eigen::Vector2d r = predicted - p.spots[i];
    e.spotErrors[i] = r.norm();
    // dP: R(d x (x, 0, 0)) = x (d3 r2 - d2 r3), and t.
    Eigen::Matrix<double, 3, 6> dP = Eigen::Matrix<double, 3, 6>::Zero();
    dP.col(1) = -x * R.col(2);
    dP.col(2) = x * R.col(1);
    dP.rightCols<3>().setIdentity();
    Eigen::Matrix<double, 2, 3> dProj;
    const double iz = 1.0 / P.z();
    dProj << fu * iz, 0.0, -fu * P.x() * iz * iz, 0.0, fv * iz, -fv * P.y() * iz * iz;
    const Eigen::Matrix<double, 2, 6> J = dProj * dP;
    accumulate(e, J.row(0).transpose(), r.x(), p.spotWeight);
    accumulate(e, J.row(1).transpose(), r.y(), p.spotWeight);
  }
  return std::isfinite(e.cost) && e.JtJ.allFinite() && e.Jtr.allFinite();
}

Eigen::Matrix3d turned(const Eigen::Matrix3d& R, const Eigen::Vector3d& d) {
  const double angle = d.norm();
  return angle > 0.0 ? Eigen::Matrix3d(R * Eigen::AngleAxisd(angle, d / angle).toRotationMatrix()) : R;
}

}  // namespace

Status refinePose(const CameraModel& cam, const TargetGeometry& target, std::span<const Eigen::Vector2d> contour,
                  const Eigen::Vector2d& centreSpotPx, const Eigen::Vector2d& offsetSpotPx, const Pose& start,
                  PoseRefinement& out) {
  out = PoseRefinement{};
  out.pose = start;
  if (contour.size() < 5) return Status::TooFewPoints;
  if (!centreSpotPx.allFinite() || !offsetSpotPx.allFinite()) return Status::SpotsNotFound;
  const Eigen::Matrix3d R0 = rotationMatrix(start);
  const Eigen::Vector3d T0 = translation(start);
  if (!R0.allFinite() || !T0.allFinite() || !(T0.norm() > 0.0)) return Status::SingularConic;

  const double weight =
      static_cast<double>(contour.size()) / (2.0 * kSpotToRimCentreError * kSpotToRimCentreError);
  const Problem problem{cam, target, contour, {centreSpotPx, offsetSpotPx}, weight};
  Eigen::Matrix3d R = R0;
  Eigen::Vector3d T = T0;
  Evaluation current, candidate;
  if (!evaluate(problem, R, T, current) || current.rimPoints < 5) return Status::SingularConic;
  out.start_cost = current.cost;

  // Levenberg-Marquardt: the damping scales the diagonal, so the rotation's radians and
  // the translation's millimetres need no common unit.
  double lambda = 1e-6;
  for (int it = 0; it < kMaxIterations; ++it) {
    Matrix6d A = current.JtJ;
    for (int k = 0; k < 6; ++k) A(k, k) += lambda * current.JtJ(k, k) + 1e-12;
    const Eigen::LDLT<Matrix6d> ldlt(A);
    if (ldlt.info() != Eigen::Success || !(ldlt.isPositive())) return Status::SingularConic;
    const Vector6d step = -ldlt.solve(current.Jtr);
    if (!step.allFinite()) return Status::SingularConic;
    if (step.head<3>().norm() < kSmallTurnRad && step.tail<3>().norm() < kSmallShiftFraction * T.norm()) break;
    // What the step would gain by the linear model (cost = sum w r^2, gradient 2 J'r): a
    // billionth of the cost moves nothing measurable, and near the sum's rounding a trial
    // could not tell better from worse.
    const double gain = -(2.0 * step.dot(current.Jtr) + step.dot(current.JtJ * step));
    if (!(gain > kNegligibleGain * current.cost)) break;
    const Eigen::Matrix3d Rn = turned(R, step.head<3>());
    const Eigen::Vector3d Tn = T + step.tail<3>();
    if (evaluate(problem, Rn, Tn, candidate) && candidate.rimPoints >= 5 && candidate.cost < current.cost) {
      R = Rn;
      T = Tn;
      std::swap(current, candidate);
      ++out.iterations;
      lambda = std::max(0.1 * lambda, 1e-9);
    } else {
      lambda *= 10.0;
    }
  }
  if (rotationAngleBetweenDeg(R0, R) > kMaxTurnDeg || (T - T0).norm() > kMaxShiftFraction * T0.norm())
    return Status::Diverged;
  out.pose = poseFromRt(R, T);
  out.cost = current.cost;
  out.rim_error_px = std::sqrt(current.rimSumOfSquares / current.rimPoints);
  out.spot_errors_px = current.spotErrors;
  return Status::Ok;
}

Status refineReconstructedPose(const ReconstructionConfig& config, ReconstructionResult& out) {
  PoseRefinement refined;
  const Status s = refinePose(config.camera, config.target, out.contour_ideal, out.centre_spot_ideal,
                              out.offset_spot_ideal, out.pose, refined);
  if (!ok(s)) return s;
  const double spotError = std::max(refined.spot_errors_px[0], refined.spot_errors_px[1]);
  if (!passesSelfCheck(config.options, spotError, refined.rim_error_px)) return Status::PoseInconsistent;
  out.pose = refined.pose;
  out.spot_error_px = spotError;
  out.rim_error_px = refined.rim_error_px;
  return Status::Ok;
}

}  // namespace imagepro
