#include "core/reconstruction/pose.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace imagepro {

namespace {

// A target seen more obliquely than this is reported as NormalFacingAway: its image is a
// sliver whose conic no longer determines the plane.
constexpr double kMaxViewAngleDeg = 88.0;
// The offset spot must lie within this factor of rf from the centre once on the plane.
constexpr double kMinOffsetRatio = 0.5;
constexpr double kMaxOffsetRatio = 1.5;

Eigen::Matrix3d conicToMatrix(const Conic& c) {
  Eigen::Matrix3d M;
  M << c[0], 0.5 * c[1], 0.5 * c[3],  //
      0.5 * c[1], c[2], 0.5 * c[4],   //
      0.5 * c[3], 0.5 * c[4], c[5];
  return M;
}

Eigen::Matrix3d pinholeMatrix(const CameraModel& cam) {
  Eigen::Matrix3d K;
  K << cam.fu(), 0.0, cam.u0(), 0.0, cam.fv(), cam.v0(), 0.0, 0.0, 1.0;
  return K;
}

double conicValue(const Eigen::Matrix3d& M, const Eigen::Vector2d& p) {
  const Eigen::Vector3d x(p.x(), p.y(), 1.0);
  return x.dot(M * x);
}

// Image conic of the circle (x0, y0, radius) of the target plane under P = R p + T.
Eigen::Matrix3d imageConicOfCircle(const CameraModel& cam, const Eigen::Matrix3d& R,
                                   const Eigen::Vector3d& T, double x0, double y0,
                                   double radius) {
  Eigen::Matrix3d H;  // target plane (x, y, 1) -> image pixels (homogeneous)
  H.col(0) = R.col(0);
  H.col(1) = R.col(1);
  H.col(2) = T;
  H = pinholeMatrix(cam) * H;
  Eigen::Matrix3d S;
  S << 1.0, 0.0, -x0, 0.0, 1.0, -y0, -x0, -y0, x0 * x0 + y0 * y0 - radius * radius;
  const Eigen::Matrix3d Hinv = H.inverse();
  return Hinv.transpose() * S * Hinv;
}

// Rotation whose third column is n (the first any unit vector normal to it).
Eigen::Matrix3d frameAboutNormal(const Eigen::Vector3d& n) {
  Eigen::Matrix3d R;
  R.col(2) = n;
  R.col(0) = n.unitOrthogonal();
  R.col(1) = n.cross(R.col(0));
  return R;
}

double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// Radians per pixel by which the rim's normal turns when the ellipse's axes move a
// hundredth of a pixel apart or together (the larger of the two: head-on the normal goes
// with the square root of the axes' difference, so growing it turns the normal most).
double rimNormalSensitivity(const CameraModel& cam, const Conic& conic, double radius_mm,
                            const Eigen::Vector3d& normal) {
  constexpr double kShiftPx = 0.01;
  Ellipse e;
  if (!ellipseFromConic(conic, e)) return NAN;
  double largest = NAN;
  for (const double sign : {1.0, -1.0}) {
    Ellipse moved = e;
    moved.a += sign * 0.5 * kShiftPx;
    moved.b -= sign * 0.5 * kShiftPx;
    if (!(moved.a > moved.b)) continue;  // already nearer a circle than the shift
    std::array<CircleCandidate, 2> cands;
    if (!ok(circleCandidates(cam, conicFromEllipse(moved), radius_mm, cands))) continue;
    const double turn =
        std::min(angleBetween(cands[0].normal, normal), angleBetween(cands[1].normal, normal));
    largest = std::isnan(largest) ? turn : std::max(largest, turn);
  }
  return largest / kShiftPx;
}

// The centre spot's image is taken to err 1.3 times as much as the rim's axes: of the
// factors tried in the accuracy study (0.7, 1, 1.3, 1.6), 1.3 bettered the rim alone in both
// the median and the 95th percentile within 15 deg of head-on on seeds 1-3
// (docs/reconstruction.md).
constexpr double kSpotToRimErrorRatio = 1.3;

// The rim's normal averaged with the centre spot's polar line, each weighed by the inverse
// square of its expected error: its sensitivity to a pixel times that pixel error. Any
// failure keeps the rim's normal.
Eigen::Vector3d weighedNormal(const CameraModel& cam, const TargetGeometry& target,
                              const Conic& conic, const CircleCandidate& rim,
                              const Eigen::Vector2d& centreSpotPx) {
  // The centre spot's centroid is off the image of the disk's centre by perspective; the
  // offset depends on the normal and the centre only, not on Rz.
  Eigen::Vector2d centreImage = centreSpotPx;
  Eigen::Vector2d offset;
  if (target.spot_radius_mm > 0.0 &&
      spotCentroidOffset(cam, frameAboutNormal(rim.normal), rim.centre, 0.0, 0.0,
                         target.spot_radius_mm, offset))
    centreImage -= offset;

  constexpr double kShiftPx = 0.01;
  Eigen::Vector3d polar, alongU, alongV;
  if (!ok(normalFromPolarLine(cam, conic, centreImage, polar)) ||
      !ok(normalFromPolarLine(cam, conic, centreImage + Eigen::Vector2d(kShiftPx, 0.0), alongU)) ||
      !ok(normalFromPolarLine(cam, conic, centreImage + Eigen::Vector2d(0.0, kShiftPx), alongV)))
    return rim.normal;
  if (!(polar.dot(rim.normal) > 0.0)) return rim.normal;
  const double polarSensitivity = std::hypot(angleBetween(alongU, polar), angleBetween(alongV, polar)) /
                                  (std::sqrt(2.0) * kShiftPx);
  const double rimSensitivity = rimNormalSensitivity(cam, conic, target.radius_mm, rim.normal);
  if (!(polarSensitivity > 0.0) || !(rimSensitivity > 0.0) || !std::isfinite(polarSensitivity) ||
      !std::isfinite(rimSensitivity))
    return rim.normal;
  const double rimWeight = 1.0 / (rimSensitivity * rimSensitivity);
  const double polarError = kSpotToRimErrorRatio * polarSensitivity;
  const double polarWeight = 1.0 / (polarError * polarError);
  const Eigen::Vector3d n = rimWeight * rim.normal + polarWeight * polar;
  return n.allFinite() && n.norm() > 0.0 ? Eigen::Vector3d(n.normalized()) : rim.normal;
}

}  // namespace

bool spotCentroidOffset(const CameraModel& cam, const Eigen::Matrix3d& R, const Eigen::Vector3d& T,
                        double x_mm, double y_mm, double radius_mm, Eigen::Vector2d& offset) {
  Eigen::Vector2d conicCentre;
  if (!conicMatrixCentre(imageConicOfCircle(cam, R, T, x_mm, y_mm, radius_mm), conicCentre))
    return false;
  offset = conicCentre - projectIdeal(cam, R * Eigen::Vector3d(x_mm, y_mm, 0.0) + T);
  return true;
}

bool conicMatrixCentre(const Eigen::Matrix3d& M, Eigen::Vector2d& centre) {
  const Eigen::Matrix2d A = M.topLeftCorner<2, 2>();
  const double det = A.determinant();
  if (!(std::abs(det) > 1e-300) || !std::isfinite(det)) return false;
  centre = -A.inverse() * M.topRightCorner<2, 1>();
  return centre.allFinite();
}

Eigen::Matrix3d imageConicOfTargetCircle(const CameraModel& cam, const Pose& pose, double x_mm,
                                         double y_mm, double radius_mm) {
  return imageConicOfCircle(cam, rotationMatrix(pose), translation(pose), x_mm, y_mm, radius_mm);
}

Status circleCandidates(const CameraModel& cam, const Conic& undistortedConic, double radius_mm,
                        std::array<CircleCandidate, 2>& out) {
  if (!undistortedConic.allFinite() || !(radius_mm > 0.0) || !(undistortedConic.norm() > 0.0))
    return Status::SingularConic;
  const Eigen::Matrix3d C = conicToMatrix(undistortedConic);
  // An ellipse in the image: the quadratic part is definite (b^2 - 4ac < 0), with a margin
  // relative to its size so that a near-parabola is not taken for an ellipse.
  const double a = C(0, 0), b2 = C(0, 1), c = C(1, 1);
  if (!(a * c - b2 * b2 > 1e-12 * (a * a + c * c + 2.0 * b2 * b2))) return Status::NotAnEllipse;

  const Eigen::Matrix3d K = pinholeMatrix(cam);
  Eigen::Matrix3d Q = K.transpose() * C * K;
  const double scale = Q.norm();
  if (!(scale > 0.0) || !std::isfinite(scale)) return Status::SingularConic;
  Q /= scale;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(Q);
  if (eig.info() != Eigen::Success) return Status::SingularConic;
  Eigen::Vector3d lambda = eig.eigenvalues();  // ascending
  Eigen::Matrix3d V = eig.eigenvectors();
  const int positives = (lambda.array() > 0.0).count();
  if (positives == 1) {  // signature (-, -, +): flip to (+, +, -)
    lambda = -lambda.reverse().eval();
    V = V.rowwise().reverse().eval();
  } else if (positives != 2) {
    return Status::SingularConic;  // definite: no real points, or degenerate
  }
  // Now lambda(0) < 0 < lambda(1) <= lambda(2).
  const double l3 = lambda(0), l2 = lambda(1), l1 = lambda(2);
  constexpr double kTiny = 1e-12;
  if (!(l2 > kTiny) || !(-l3 > kTiny)) return Status::SingularConic;
  const Eigen::Vector3d e1 = V.col(2), e3 = V.col(0);
  const double k = std::sqrt(l1 - l3);
  const double sa = std::sqrt(std::max(0.0, l1 - l2));
  const double sb = std::sqrt(l2 - l3);
  const double d = radius_mm * l2 / std::sqrt(-l1 * l3);
  for (int i = 0; i < 2; ++i) {
    const double s = i == 0 ? 1.0 : -1.0;
    CircleCandidate& cand = out[i];
    cand.normal = (s * sa * e1 + sb * e3) / k;
    cand.centre = d / (l2 * k) * (s * sa * l3 * e1 + sb * l1 * e3);
    if (cand.centre.z() < 0.0) {  // the mirror image through the camera centre
      cand.centre = -cand.centre;
      cand.normal = -cand.normal;
    }
    cand.normal.normalize();
    if (!cand.centre.allFinite() || !cand.normal.allFinite()) return Status::SingularConic;
  }
  return Status::Ok;
}

namespace {

// The pose of one circle candidate: its normal (weighed with the centre spot's polar line
// when asked), its centre, and +X through the offset spot's ray cut with its plane.
Status poseOfCandidate(const CameraModel& cam, const TargetGeometry& target, const Conic& undistortedConic,
                       const CircleCandidate& candidate, const Eigen::Vector2d& centreSpotPx,
                       const Eigen::Vector2d& offsetSpotPx, bool weighCentreSpot, Pose& out) {
  const Eigen::Vector3d n = weighCentreSpot
                                ? weighedNormal(cam, target, undistortedConic, candidate, centreSpotPx)
                                : candidate.normal;
  const Eigen::Vector3d& T = candidate.centre;
  if (n.dot(T.normalized()) < std::cos(kMaxViewAngleDeg * M_PI / 180.0))
    return Status::NormalFacingAway;
  const double planeDistance = n.dot(T);

  // +X: from the centre towards the offset spot's ray cut with the plane.
  auto xAxisThrough = [&](const Eigen::Vector2d& px, Eigen::Vector3d& xAxis) {
    const Eigen::Vector3d ray = backProjectIdeal(cam, px);
    const double along = n.dot(ray);
    if (!(along > 1e-9 * ray.norm())) return Status::NormalFacingAway;
    const Eigen::Vector3d onPlane = ray * (planeDistance / along);
    const Eigen::Vector3d inPlane = onPlane - T;
    const double offset = inPlane.norm();
    if (!(offset >= kMinOffsetRatio * target.spot_offset_mm &&
          offset <= kMaxOffsetRatio * target.spot_offset_mm))
      return Status::SpotsNotFound;
    xAxis = inPlane / offset;
    return Status::Ok;
  };
  auto rotationFrom = [&](const Eigen::Vector3d& xAxis) {
    Eigen::Matrix3d R;
    R.col(2) = n;
    R.col(0) = (xAxis - n * n.dot(xAxis)).normalized();
    R.col(1) = R.col(2).cross(R.col(0));
    return R;
  };

  Eigen::Vector3d xAxis;
  if (const Status s = xAxisThrough(offsetSpotPx, xAxis); !ok(s)) return s;
  Eigen::Matrix3d R = rotationFrom(xAxis);

  // Remove the perspective offset between the offset spot's image centroid and the image
  // of its centre, computed from the pose so far, then take the axis again. The offset
  // depends on the axis only weakly, so a second pass leaves a residual far below 1e-6 deg.
  for (int pass = 0; pass < 2 && target.spot_radius_mm > 0.0; ++pass) {
    Eigen::Vector2d bias;
    if (!spotCentroidOffset(cam, R, T, target.spot_offset_mm, 0.0, target.spot_radius_mm, bias)) break;
    if (!bias.allFinite() || bias.norm() > 0.5 * target.spot_radius_mm * cam.fu() / T.z()) break;
    if (const Status s = xAxisThrough(offsetSpotPx - bias, xAxis); !ok(s)) return s;
    R = rotationFrom(xAxis);
  }
  if (!R.allFinite() || !T.allFinite()) return Status::SingularConic;
  out = poseFromRt(R, T);
  return Status::Ok;
}

}  // namespace

std::array<double, 2> spotReprojectionErrors(const CameraModel& cam, const TargetGeometry& target, const Pose& pose,
                                             const Eigen::Vector2d& centreSpotPx, const Eigen::Vector2d& offsetSpotPx) {
  const Eigen::Matrix3d R = rotationMatrix(pose);
  const Eigen::Vector3d T = translation(pose);
  std::array<double, 2> errors{};
  const std::array<std::pair<double, Eigen::Vector2d>, 2> spots{{{0.0, centreSpotPx}, {target.spot_offset_mm, offsetSpotPx}}};
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& [x_mm, observed] = spots[i];
    Eigen::Vector2d predicted = projectIdeal(cam, R * Eigen::Vector3d(x_mm, 0.0, 0.0) + T);
    Eigen::Vector2d bias;
    if (target.spot_radius_mm > 0.0 && spotCentroidOffset(cam, R, T, x_mm, 0.0, target.spot_radius_mm, bias) &&
        bias.allFinite())
      predicted += bias;
    errors[i] = (predicted - observed).norm();
  }
  return errors;
}

Status poseFromEllipse(const CameraModel& cam, const TargetGeometry& target, const Conic& undistortedConic,
                       const Eigen::Vector2d& centreSpotPx, const Eigen::Vector2d& offsetSpotPx, Pose& out,
                       bool weighCentreSpot, PoseCandidates* candidates) {
  if (!undistortedConic.allFinite()) return Status::SingularConic;
  if (!centreSpotPx.allFinite() || !offsetSpotPx.allFinite()) return Status::SpotsNotFound;
  std::array<CircleCandidate, 2> cands;
  if (const Status s = circleCandidates(cam, undistortedConic, target.radius_mm, cands); !ok(s))
    return s;

  // The centre spot must lie inside the rim's ellipse: the conic has there the sign it has
  // at the ellipse's own centre.
  const Eigen::Matrix3d C = conicToMatrix(undistortedConic);
  Eigen::Vector2d ellipseCentre;
  if (!conicMatrixCentre(C, ellipseCentre)) return Status::SingularConic;
  if (!(conicValue(C, centreSpotPx) * conicValue(C, ellipseCentre) > 0.0))
    return Status::CentreSpotOutsideEllipse;

  // The candidate whose circle centre projects nearer the centre spot first.
  const double e0 = (projectIdeal(cam, cands[0].centre) - centreSpotPx).squaredNorm();
  const double e1 = (projectIdeal(cam, cands[1].centre) - centreSpotPx).squaredNorm();
  if (e1 < e0) std::swap(cands[0], cands[1]);
  PoseCandidates both;
  for (int k = 0; k < 2; ++k) {
    both.status[k] = poseOfCandidate(cam, target, undistortedConic, cands[k], centreSpotPx, offsetSpotPx,
                                     weighCentreSpot, both.pose[k]);
    if (ok(both.status[k]))
      both.spot_errors_px[k] = spotReprojectionErrors(cam, target, both.pose[k], centreSpotPx, offsetSpotPx);
  }
  both.normals_apart_deg = angleBetween(cands[0].normal, cands[1].normal) * 180.0 / M_PI;
  if (candidates) *candidates = both;
  if (!ok(both.status[0])) return both.status[0];
  out = both.pose[0];
  return Status::Ok;
}

Status normalFromPolarLine(const CameraModel& cam, const Conic& undistortedConic,
                           const Eigen::Vector2d& centreSpotPx, Eigen::Vector3d& normal) {
  if (!undistortedConic.allFinite() || !centreSpotPx.allFinite()) return Status::SingularConic;
  const Eigen::Matrix3d C = conicToMatrix(undistortedConic);
  const Eigen::Vector3d line = C * Eigen::Vector3d(centreSpotPx.x(), centreSpotPx.y(), 1.0);
  Eigen::Vector3d n = pinholeMatrix(cam).transpose() * line;
  const double len = n.norm();
  if (!(len > 0.0) || !std::isfinite(len)) return Status::SingularConic;
  n /= len;
  if (n.dot(backProjectIdeal(cam, centreSpotPx)) < 0.0) n = -n;
  normal = n;
  return Status::Ok;
}

}  // namespace imagepro
