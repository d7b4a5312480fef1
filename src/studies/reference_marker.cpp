#include "studies/reference_marker.h"

#include <Eigen/LU>
#include <opencv2/aruco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/reconstruction/undistort.h"

namespace imagepro::studies {

namespace {

constexpr int kCells = 6;  // a 4x4 code plus a one-cell black border each side

const cv::Ptr<cv::aruco::Dictionary>& dictionary() {
  static const cv::Ptr<cv::aruco::Dictionary> dict =
      cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50);
  return dict;
}

// The plane of the marker seen through the camera: image point -> marker plane point.
class MarkerPlane {
 public:
  MarkerPlane(const CameraModel& cam, const MarkerGeometry& marker, const Pose& pose)
      : cam_(cam), marker_(marker) {
    cv::aruco::drawMarker(dictionary(), marker.id, kCells, cells_, 1);
    const Eigen::Matrix3d R = rotationMatrix(pose);
    const Eigen::Vector3d T = translation(pose);
    facing_ = R.col(2).dot(T) > 0.0;
    Eigen::Matrix3d M;
    M << R.col(0), R.col(1), T;
    toPlane_ = M.inverse();
  }

  enum Level : std::uint8_t { kOutside = 0, kWhite = 1, kBlack = 2 };

  Level levelAt(double u, double v) const {
    if (!facing_) return kOutside;
    const Eigen::Vector2d ideal = cam_.distortion.isZero() ? Eigen::Vector2d(u, v) : undistortExact(cam_, {u, v});
    const Eigen::Vector3d p = toPlane_ * backProjectIdeal(cam_, ideal);
    if (!(p.z() > 0.0)) return kOutside;
    const double x = p.x() / p.z(), y = p.y() / p.z();
    const double halfCard = 0.5 * marker_.card_mm, halfSquare = 0.5 * marker_.square_mm;
    if (std::abs(x) > halfCard || std::abs(y) > halfCard) return kOutside;
    if (std::abs(x) > halfSquare || std::abs(y) > halfSquare) return kWhite;
    const double cell = marker_.square_mm / kCells;
    const int col = std::clamp(static_cast<int>(std::floor((x + halfSquare) / cell)), 0, kCells - 1);
    const int row = std::clamp(static_cast<int>(std::floor((y + halfSquare) / cell)), 0, kCells - 1);
    return cells_.at<std::uint8_t>(row, col) != 0 ? kWhite : kBlack;
  }

  // The image rectangle that can see the card.
  cv::Rect imageBox(const Pose& pose) const {
    const Eigen::Matrix3d R = rotationMatrix(pose);
    const Eigen::Vector3d T = translation(pose);
    const double h = 0.5 * marker_.card_mm;
    double u0 = INFINITY, u1 = -INFINITY, v0 = INFINITY, v1 = -INFINITY;
    constexpr int kPerSide = 16;
    for (int k = 0; k <= kPerSide; ++k) {
      const double t = -h + 2.0 * h * k / kPerSide;
      for (const Eigen::Vector2d& q : {Eigen::Vector2d(t, -h), Eigen::Vector2d(t, h), Eigen::Vector2d(-h, t),
                                       Eigen::Vector2d(h, t)}) {
        const Eigen::Vector3d P = R * Eigen::Vector3d(q.x(), q.y(), 0.0) + T;
        if (P.z() <= 1e-6) return {0, 0, cam_.width, cam_.height};
        const Eigen::Vector2d px = distortPixel(cam_, projectIdeal(cam_, P));
        u0 = std::min(u0, px.x());
        u1 = std::max(u1, px.x());
        v0 = std::min(v0, px.y());
        v1 = std::max(v1, px.y());
      }
    }
    const cv::Rect box(static_cast<int>(std::floor(u0)) - 2, static_cast<int>(std::floor(v0)) - 2,
                       static_cast<int>(std::ceil(u1 - u0)) + 5, static_cast<int>(std::ceil(v1 - v0)) + 5);
    return box & cv::Rect(0, 0, cam_.width, cam_.height);
  }

 private:
  const CameraModel& cam_;
  const MarkerGeometry& marker_;
  cv::Mat cells_;
  Eigen::Matrix3d toPlane_;
  bool facing_ = true;
};

}  // namespace

void paintMarkerCard(const CameraModel& cam, const MarkerGeometry& marker, const VirtualSceneOptions& scene,
                     const Pose& pose, cv::Mat& frame) {
  if (frame.empty() || frame.type() != CV_8UC1) return;
  const MarkerPlane plane(cam, marker, pose);
  const cv::Rect box = plane.imageBox(pose) & cv::Rect(0, 0, frame.cols, frame.rows);
  if (box.empty()) return;
  const int white = std::clamp(scene.white_level, 0, 255), black = std::clamp(scene.black_level, 0, 255);
  // Pixel-centre levels, then every pixel whose 3x3 neighbourhood is not uniform averaged
  // over n x n samples (samples off the card keep the scene's level there).
  cv::Mat levels(box.size(), CV_8UC1);
  for (int y = 0; y < box.height; ++y)
    for (int x = 0; x < box.width; ++x) levels.at<std::uint8_t>(y, x) = plane.levelAt(box.x + x, box.y + y);
  const int n = std::max(1, scene.supersampling);
  const cv::Mat scene0 = frame(box).clone();
  for (int y = 0; y < box.height; ++y) {
    auto* out = frame.ptr<std::uint8_t>(box.y + y) + box.x;
    for (int x = 0; x < box.width; ++x) {
      const std::uint8_t c = levels.at<std::uint8_t>(y, x);
      bool edge = false;
      for (int dy = -1; dy <= 1 && !edge; ++dy)
        for (int dx = -1; dx <= 1 && !edge; ++dx) {
          const int yy = std::clamp(y + dy, 0, box.height - 1), xx = std::clamp(x + dx, 0, box.width - 1);
          edge = levels.at<std::uint8_t>(yy, xx) != c;
        }
      const int outside = c == MarkerPlane::kOutside ? scene0.at<std::uint8_t>(y, x) : scene.background_level;
      auto value = [&](MarkerPlane::Level l) { return l == MarkerPlane::kOutside ? outside : (l == MarkerPlane::kWhite ? white : black); };
      if (!edge) {
        if (c != MarkerPlane::kOutside) out[x] = static_cast<std::uint8_t>(value(static_cast<MarkerPlane::Level>(c)));
        continue;
      }
      int sum = 0;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          sum += value(plane.levelAt(box.x + x + (i + 0.5) / n - 0.5, box.y + y + (j + 0.5) / n - 0.5));
      out[x] = static_cast<std::uint8_t>(std::lround(static_cast<double>(sum) / (n * n)));
    }
  }
}

void applySceneEffects(const VirtualSceneOptions& scene, std::uint64_t seed, cv::Mat& frame) {
  if (frame.empty() || frame.type() != CV_8UC1) return;
  cv::Mat grey;
  frame.convertTo(grey, CV_32F);
  if (scene.illumination_gradient != 0.0) {
    const double span = std::max(grey.cols - 1, 1);
    for (int v = 0; v < grey.rows; ++v) {
      auto* row = grey.ptr<float>(v);
      for (int u = 0; u < grey.cols; ++u)
        row[u] *= static_cast<float>(1.0 + scene.illumination_gradient * (u / span - 0.5));
    }
  }
  if (scene.blur_sigma_px > 0.0)
    cv::GaussianBlur(grey, grey, cv::Size(0, 0), scene.blur_sigma_px, scene.blur_sigma_px, cv::BORDER_REPLICATE);
  if (scene.noise_sigma > 0.0) {
    cv::Mat noise(grey.size(), CV_32F);
    cv::RNG rng(0x9e3779b97f4a7c15ULL ^ (seed * 0x2545f4914f6cdd1dULL + scene.seed));
    rng.fill(noise, cv::RNG::NORMAL, 0.0, scene.noise_sigma);
    grey += noise;
  }
  grey.convertTo(frame, CV_8U);
}

Status estimateMarkerPose(const CameraModel& cam, const MarkerGeometry& marker, const cv::Mat& grey, Pose& out) {
  if (grey.empty() || grey.type() != CV_8UC1) return Status::EmptyFrame;
  static const cv::Ptr<cv::aruco::DetectorParameters> params = [] {
    cv::Ptr<cv::aruco::DetectorParameters> p = cv::aruco::DetectorParameters::create();
    p->cornerRefinementMethod = cv::aruco::CORNER_REFINE_SUBPIX;
    return p;
  }();
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(grey, dictionary(), corners, ids, params);
  int found = -1;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] != marker.id) continue;
    if (found >= 0) return Status::AmbiguousTarget;
    found = static_cast<int>(i);
  }
  if (found < 0) return Status::NoTarget;
  // Corners as found: top-left, top-right, bottom-right, bottom-left of the printed marker,
  // corrected for the lens distortion.
  std::vector<cv::Point2d> image(4);
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d p = undistortExact(cam, {corners[found][k].x, corners[found][k].y});
    image[k] = cv::Point2d(p.x(), p.y());
  }
  // IPPE's square has +Y up the marker and +Z towards the viewer.
  const double h = 0.5 * marker.square_mm;
  const std::vector<cv::Point3d> object{{-h, h, 0}, {h, h, 0}, {h, -h, 0}, {-h, -h, 0}};
  const cv::Matx33d K(cam.fu(), 0, cam.u0(), 0, cam.fv(), cam.v0(), 0, 0, 1);
  cv::Vec3d rvec, tvec;
  if (!cv::solvePnP(object, image, K, cv::noArray(), rvec, tvec, false, cv::SOLVEPNP_IPPE_SQUARE))
    return Status::Diverged;
  cv::Matx33d Rcv;
  cv::Rodrigues(rvec, Rcv);
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R(r, c) = Rcv(r, c);
  // Flip IPPE's Y and Z to the target frame's (+Y down the marker, +Z away from the camera).
  R.col(1) = -R.col(1);
  R.col(2) = -R.col(2);
  const Eigen::Vector3d T(tvec[0], tvec[1], tvec[2]);
  if (!R.allFinite() || !T.allFinite()) return Status::Diverged;
  out = poseFromRt(R, T);
  return Status::Ok;
}

}  // namespace imagepro::studies
