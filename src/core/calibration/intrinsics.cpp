#include "core/calibration/intrinsics.h"

#include <Eigen/Dense>
#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace imagepro {
namespace {

constexpr int kRimPoints = 64;     // the dot's rim as a polygon (centroid error ~ 1e-3 of its size)
constexpr int kMinViewDots = 6;    // fewer dots say too little about a view's homography
constexpr double kOutlierFactor = 4.0;  // a view this many times the median RMS (and above 1 px) is out
constexpr double kOutlierFloorPx = 1.0;
constexpr int kFieldSamplesX = 32, kFieldSamplesY = 24;

// The undistorted pixels the two models are compared at: a grid over the whole image.
std::vector<Eigen::Vector2d> fieldSamples(int width, int height) {
  std::vector<Eigen::Vector2d> s;
  for (int j = 0; j < kFieldSamplesY; ++j)
    for (int i = 0; i < kFieldSamplesX; ++i)
      s.emplace_back((width - 1.0) * i / (kFieldSamplesX - 1), (height - 1.0) * j / (kFieldSamplesY - 1));
  return s;
}

// Least squares A x = b with every column scaled to unit norm first (the parameters span
// twelve orders of magnitude); the RMS of the residual over the 2D samples.
Eigen::Vector4d solveScaled(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, double* rms) {
  Eigen::Vector4d scale;
  for (int k = 0; k < 4; ++k) scale[k] = A.col(k).norm() > 0 ? 1.0 / A.col(k).norm() : 1.0;
  const Eigen::MatrixXd As = A * scale.asDiagonal();
  const Eigen::Vector4d y = As.colPivHouseholderQr().solve(b);
  const Eigen::Vector4d x = y.cwiseProduct(scale);
  if (rms) *rms = std::sqrt((A * x - b).squaredNorm() / (0.5 * static_cast<double>(b.size())));
  return x;
}

std::vector<cv::Point3f> objectPointsOf(const std::vector<FoundDot>& dots) {
  std::vector<cv::Point3f> out;
  for (const FoundDot& d : dots)
    out.emplace_back(static_cast<float>(d.object_mm.x()), static_cast<float>(d.object_mm.y()), 0.0f);
  return out;
}

}  // namespace

cv::Matx33d cameraMatrix(const CameraModel& camera) {
  return {camera.fu(), 0.0, camera.u0(), 0.0, camera.fv(), camera.v0(), 0.0, 0.0, 1.0};
}

Eigen::Vector2d dotCentroidOffsetPx(const cv::Matx33d& K, const std::vector<double>& dist, const cv::Vec3d& rvec,
                                    const cv::Vec3d& tvec, const Eigen::Vector2d& object_mm, double diameter_mm) {
  std::vector<cv::Point3d> pts;
  pts.emplace_back(object_mm.x(), object_mm.y(), 0.0);
  for (int k = 0; k < kRimPoints; ++k) {
    const double a = 2.0 * std::numbers::pi * k / kRimPoints;
    pts.emplace_back(object_mm.x() + 0.5 * diameter_mm * std::cos(a), object_mm.y() + 0.5 * diameter_mm * std::sin(a),
                     0.0);
  }
  std::vector<cv::Point2d> img;
  cv::projectPoints(pts, rvec, tvec, K, dist, img);
  // Area centroid of the projected rim (shoelace), about the projected centre for precision.
  double area = 0, sx = 0, sy = 0;
  for (int k = 0; k < kRimPoints; ++k) {
    const cv::Point2d p = img[1 + k] - img[0], q = img[1 + (k + 1) % kRimPoints] - img[0];
    const double c = p.x * q.y - q.x * p.y;
    area += c;
    sx += (p.x + q.x) * c;
    sy += (p.y + q.y) * c;
  }
  if (std::abs(area) < 1e-12) return Eigen::Vector2d::Zero();
  return {sx / (3.0 * area), sy / (3.0 * area)};
}

Distortion distortionFromOpenCv(const cv::Matx33d& K, const std::vector<double>& dist, int width, int height,
                                double* rms_px) {
  const double fx = K(0, 0), fy = K(1, 1), cx = K(0, 2), cy = K(1, 2);
  const std::vector<Eigen::Vector2d> s = fieldSamples(width, height);
  std::vector<cv::Point3d> rays;
  for (const Eigen::Vector2d& u : s) rays.emplace_back((u.x() - cx) / fx, (u.y() - cy) / fy, 1.0);
  std::vector<cv::Point2d> seen;
  cv::projectPoints(rays, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, dist, seen);
  const int n = static_cast<int>(s.size());
  Eigen::MatrixXd A(2 * n, 4);
  Eigen::VectorXd b(2 * n);
  for (int i = 0; i < n; ++i) {
    const double u = s[i].x() - cx, v = s[i].y() - cy, r2 = u * u + v * v;
    A.row(2 * i) << u * r2, u * r2 * r2, 2 * u * v, r2 + 2 * u * u;
    A.row(2 * i + 1) << v * r2, v * r2 * r2, r2 + 2 * v * v, 2 * u * v;
    b[2 * i] = seen[i].x - s[i].x();
    b[2 * i + 1] = seen[i].y - s[i].y();
  }
  const Eigen::Vector4d x = solveScaled(A, b, rms_px);
  return {x[0], x[1], x[2], x[3]};
}

std::array<double, 5> openCvFromDistortion(const CameraModel& camera, double* rms_px) {
  const double fx = camera.fu(), fy = camera.fv(), cx = camera.u0(), cy = camera.v0();
  const std::vector<Eigen::Vector2d> s = fieldSamples(camera.width, camera.height);
  const int n = static_cast<int>(s.size());
  Eigen::MatrixXd A(2 * n, 4);
  Eigen::VectorXd b(2 * n);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d rel(s[i].x() - cx, s[i].y() - cy);
    const double x = rel.x() / fx, y = rel.y() / fy, r2 = x * x + y * y;
    A.row(2 * i) << fx * x * r2, fx * x * r2 * r2, fx * 2 * x * y, fx * (r2 + 2 * x * x);
    A.row(2 * i + 1) << fy * y * r2, fy * y * r2 * r2, fy * (r2 + 2 * y * y), fy * 2 * x * y;
    const Eigen::Vector2d d = distortionDelta(camera.distortion, rel);
    b[2 * i] = d.x();
    b[2 * i + 1] = d.y();
  }
  const Eigen::Vector4d x = solveScaled(A, b, rms_px);
  return {x[0], x[1], x[2], x[3], 0.0};
}

void applyIntrinsics(const IntrinsicsResult& r, CameraModel& camera) {
  camera.width = r.width;
  camera.height = r.height;
  camera.principal_point_px = {r.cx, r.cy};
  camera.image_plane_distance_mm = r.fx * camera.pixel_size_mm[0];
  camera.pixel_size_mm[1] = camera.image_plane_distance_mm / r.fy;
  camera.distortion = r.distortion;
}

Status calibrateFoundDots(std::vector<IntrinsicsView> views, cv::Size imageSize, const DotGridSpec& spec,
                          const IntrinsicsOptions& options, IntrinsicsResult& result) {
  result = {};
  result.width = imageSize.width;
  result.height = imageSize.height;
  for (IntrinsicsView& v : views) {
    v.dots = static_cast<int>(v.found.size());
    if (ok(v.status) && v.dots < kMinViewDots) v.status = Status::GridNotFound;
    v.centre_offset_px.assign(v.found.size(), Eigen::Vector2d::Zero());
  }
  result.views = std::move(views);
  if (!dotGridSpecError(spec).empty()) return result.status = Status::InvalidPattern;
  const double diameter = dotDiameterMm(spec);

  cv::Matx33d K = cv::Matx33d::eye();
  std::vector<double> dist(5, 0.0);
  cv::Mat stdI, stdE, perView;
  std::vector<cv::Mat> rvecs, tvecs;
  std::vector<int> used;
  auto solve = [&](bool guess) -> bool {
    used.clear();
    std::vector<std::vector<cv::Point3f>> obj;
    std::vector<std::vector<cv::Point2f>> img;
    for (int i = 0; i < static_cast<int>(result.views.size()); ++i) {
      const IntrinsicsView& v = result.views[i];
      if (!ok(v.status)) continue;
      used.push_back(i);
      obj.push_back(objectPointsOf(v.found));
      std::vector<cv::Point2f> p;
      for (size_t k = 0; k < v.found.size(); ++k) {
        const Eigen::Vector2d c = v.found[k].image_px - v.centre_offset_px[k];
        p.emplace_back(static_cast<float>(c.x()), static_cast<float>(c.y()));
      }
      img.push_back(std::move(p));
    }
    if (static_cast<int>(used.size()) < kMinIntrinsicViews) return false;
    int flags = options.fit_k3 ? 0 : cv::CALIB_FIX_K3;
    if (guess) flags |= cv::CALIB_USE_INTRINSIC_GUESS;
    cv::Mat Km(K), Dm(dist);
    try {
      result.rms_px = cv::calibrateCamera(obj, img, imageSize, Km, Dm, rvecs, tvecs, stdI, stdE, perView, flags,
                                          cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100,
                                                           1e-12));
    } catch (const cv::Exception&) {
      return false;
    }
    K = cv::Matx33d(reinterpret_cast<const double*>(Km.data));
    for (int k = 0; k < 5; ++k) dist[k] = Dm.at<double>(k);
    return true;
  };
  auto usable = [&] {
    return static_cast<int>(std::count_if(result.views.begin(), result.views.end(),
                                          [](const IntrinsicsView& v) { return ok(v.status); }));
  };
  if (usable() < kMinIntrinsicViews) return result.status = Status::TooFewViews;
  if (!solve(false)) return result.status = Status::DegenerateFit;

  // Step 4: a misnamed grid shows as a view far worse than the rest.
  std::vector<double> errs;
  for (size_t u = 0; u < used.size(); ++u) errs.push_back(perView.at<double>(static_cast<int>(u)));
  std::vector<double> sorted = errs;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double limit = std::max(kOutlierFloorPx, kOutlierFactor * sorted[sorted.size() / 2]);
  bool dropped = false;
  for (size_t u = 0; u < used.size(); ++u)
    if (errs[u] > limit) {
      result.views[used[u]].status = Status::PoseInconsistent;
      result.views[used[u]].rms_px = errs[u];
      dropped = true;
    }
  if (dropped) {
    if (usable() < kMinIntrinsicViews) return result.status = Status::TooFewViews;
    if (!solve(true)) return result.status = Status::DegenerateFit;
  }

  // Step 3: each dot's centroid offset at the current poses and lens, then solve again.
  for (int pass = 0; pass < options.centre_correction_passes; ++pass) {
    for (size_t u = 0; u < used.size(); ++u) {
      IntrinsicsView& v = result.views[used[u]];
      const cv::Vec3d rv(rvecs[u].ptr<double>()), tv(tvecs[u].ptr<double>());
      for (size_t k = 0; k < v.found.size(); ++k)
        v.centre_offset_px[k] = dotCentroidOffsetPx(K, dist, rv, tv, v.found[k].object_mm, diameter);
    }
    if (!solve(true)) return result.status = Status::DegenerateFit;
  }

  result.fx = K(0, 0);
  result.fy = K(1, 1);
  result.cx = K(0, 2);
  result.cy = K(1, 2);
  for (int k = 0; k < 5; ++k) result.opencv_dist[k] = dist[k];
  const auto sd = [&](int k) { return stdI.total() > static_cast<size_t>(k) ? stdI.at<double>(k) : 0.0; };
  result.deviation = {sd(0), sd(1), sd(2), sd(3), sd(4), sd(5), sd(6), sd(7), sd(8)};
  result.views_used = static_cast<int>(used.size());
  for (size_t u = 0; u < used.size(); ++u) {
    IntrinsicsView& v = result.views[used[u]];
    v.rms_px = perView.at<double>(static_cast<int>(u));
    v.rvec = cv::Vec3d(rvecs[u].ptr<double>());
    v.tvec = cv::Vec3d(tvecs[u].ptr<double>());
    cv::Matx33d R;
    cv::Rodrigues(v.rvec, R);
    const double nz = std::clamp(std::abs(R(2, 2)), 0.0, 1.0);
    v.tilt_deg = std::acos(nz) * 180.0 / std::numbers::pi;
    const Eigen::Vector2d axis(R(0, 2), R(1, 2));
    v.tilt_axis = axis.norm() > 1e-12 ? Eigen::Vector2d(axis.normalized()) : Eigen::Vector2d::Zero();
  }
  const bool plausible = std::isfinite(result.fx) && std::isfinite(result.fy) && result.fx > 0 && result.fy > 0 &&
                         result.cx > -0.5 * result.width && result.cx < 1.5 * result.width &&
                         result.cy > -0.5 * result.height && result.cy < 1.5 * result.height &&
                         std::all_of(dist.begin(), dist.end(), [](double d) { return std::isfinite(d); });
  if (!plausible) return result.status = Status::DegenerateFit;
  result.distortion = distortionFromOpenCv(K, dist, result.width, result.height, &result.model_fit_rms_px);
  return result.status = Status::Ok;
}

Status calibrateIntrinsics(std::span<const cv::Mat> images, const DotGridSpec& spec, const IntrinsicsOptions& options,
                           IntrinsicsResult& result, const IntrinsicsProgress& progress) {
  result = {};
  if (!dotGridSpecError(spec).empty()) return result.status = Status::InvalidPattern;
  std::vector<IntrinsicsView> views(images.size());
  cv::Size size;
  for (size_t i = 0; i < images.size(); ++i) {
    if (progress && !progress(static_cast<int>(i), static_cast<int>(images.size())))
      return result.status = Status::Stopped;
    const cv::Mat& im = images[i];
    if (im.empty() || im.type() != CV_8UC1) {
      views[i].status = Status::EmptyFrame;
      continue;
    }
    if (size.area() == 0) size = im.size();
    if (im.size() != size) {
      views[i].status = Status::FrameSizeMismatch;
      continue;
    }
    GridDetection g;
    views[i].status = findDotGrid(im, spec, g);
    views[i].partial = g.partial;
    views[i].found = std::move(g.dots);
  }
  if (progress && !progress(static_cast<int>(images.size()), static_cast<int>(images.size())))
    return result.status = Status::Stopped;
  return calibrateFoundDots(std::move(views), size, spec, options, result);
}

}  // namespace imagepro
