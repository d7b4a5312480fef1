#include "core/source/virtual_renderer.h"
#include "core/source/scene_shapes.h"
#include "support/plain_scene.h"

#include <gtest/gtest.h>

#include "core/settings/settings.h"

#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace imagepro {
namespace {

// Forward model, independent of the renderer's inverse mapping: a target-plane point
// projected by the pose and the pinhole camera, then distorted by eq. 4.7.
Eigen::Vector2d imageOf(const CameraModel& cam, const Pose& pose, double x, double y) {
  const Eigen::Vector3d P = rotationMatrix(pose) * Eigen::Vector3d(x, y, 0) + translation(pose);
  return distortPixel(cam, projectIdeal(cam, P));
}

// The image of a circle of the target plane as a fine polygon.
std::vector<cv::Point2d> circleImage(const CameraModel& cam, const Pose& pose, double cx, double r, int n = 2000) {
  std::vector<cv::Point2d> poly;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * M_PI * k / n;
    const Eigen::Vector2d p = imageOf(cam, pose, cx + r * std::cos(a), r * std::sin(a));
    poly.emplace_back(p.x(), p.y());
  }
  return poly;
}

bool inside(const std::vector<cv::Point2d>& poly, double u, double v) {
  // Even-odd ray casting.
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const auto& a = poly[i];
    const auto& b = poly[j];
    if ((a.y > v) != (b.y > v) && u < (b.x - a.x) * (v - a.y) / (b.y - a.y) + a.x) in = !in;
  }
  return in;
}

// Area and centroid of a simple polygon (shoelace).
void polygonMoments(const std::vector<cv::Point2d>& poly, double& area, Eigen::Vector2d& centroid) {
  double a = 0, cx = 0, cy = 0;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const double cross = poly[j].x * poly[i].y - poly[i].x * poly[j].y;
    a += cross;
    cx += (poly[j].x + poly[i].x) * cross;
    cy += (poly[j].y + poly[i].y) * cross;
  }
  area = 0.5 * a;
  centroid = Eigen::Vector2d(cx / (6.0 * area), cy / (6.0 * area));
  area = std::abs(area);
}

VirtualSceneOptions binaryScene() {
  VirtualSceneOptions s;
  s.mode = RenderMode::Binary;
  return s;
}

// Grey scene whose levels measure coverage: white 255, everything else 0.
VirtualSceneOptions coverageScene(int supersampling) {
  VirtualSceneOptions s = test::plainScene();
  s.mode = RenderMode::Grey;
  s.white_level = 255;
  s.black_level = 0;
  s.background_level = 0;
  s.supersampling = supersampling;
  return s;
}

CameraModel distortedCamera() {
  CameraModel cam;
  cam.principal_point_px = {310.2, 245.7};  // off the image centre on purpose
  cam.distortion = kThesisCameraDistortion;
  return cam;
}

// Every pixel centre classified by the forward model must match the binary render.
void expectMatchesForwardModel(const CameraModel& cam, const TargetGeometry& target, const Pose& pose) {
  cv::Mat img;
  renderTarget(cam, target, binaryScene(), pose, img);
  ASSERT_EQ(img.type(), CV_8UC1);
  ASSERT_EQ(img.cols, cam.width);
  ASSERT_EQ(img.rows, cam.height);
  const auto disk = circleImage(cam, pose, 0, target.radius_mm);
  const auto spot0 = circleImage(cam, pose, 0, target.spot_radius_mm);
  const auto spot1 = circleImage(cam, pose, target.spot_offset_mm, target.spot_radius_mm);
  cv::Rect box = cv::boundingRect(std::vector<cv::Point2f>(disk.begin(), disk.end()));
  box = cv::Rect(box.x - 2, box.y - 2, box.width + 4, box.height + 4);
  int white = 0, mismatches = 0;
  for (int v = 0; v < img.rows; ++v) {
    for (int u = 0; u < img.cols; ++u) {
      bool expected = false;
      if (box.contains(cv::Point(u, v)))
        expected = inside(disk, u, v) && !inside(spot0, u, v) && !inside(spot1, u, v);
      const bool got = img.at<std::uint8_t>(v, u) == 255;
      white += got;
      mismatches += expected != got;
    }
  }
  EXPECT_GT(white, 500);
  // Only a pixel centre within ~1e-4 px of an outline could disagree.
  EXPECT_LE(mismatches, 2) << "pose rx " << pose.rx_deg << " ry " << pose.ry_deg;
}

TEST(VirtualRenderer, BinaryMatchesForwardProjectionWithoutDistortion) {
  const CameraModel cam;
  const TargetGeometry target;
  expectMatchesForwardModel(cam, target, Pose{0, 0, 0, 0, 0, 800});
  expectMatchesForwardModel(cam, target, Pose{35, -20, 15, 40, -30, 700});
  expectMatchesForwardModel(cam, target, Pose{-60, 10, -120, -80, 50, 900});
}

TEST(VirtualRenderer, BinaryMatchesForwardProjectionWithDistortion) {
  CameraModel cam = distortedCamera();
  const TargetGeometry target;
  expectMatchesForwardModel(cam, target, Pose{0, 0, 0, 0, 0, 800});
  expectMatchesForwardModel(cam, target, Pose{30, 25, 40, 200, 150, 900});
  // Exaggerated distortion, as in the thesis's figures 4.3-4.5.
  cam.distortion = {-1.0e-6, -2.0e-12, 2.0e-5, -1.5e-5};
  expectMatchesForwardModel(cam, target, Pose{-25, 40, 80, -220, -140, 950});
}

TEST(VirtualRenderer, OnlyBlackAndWhiteInBinaryMode) {
  VirtualSceneOptions scene = binaryScene();
  scene.clutter = 10;
  scene.noise_sigma = 10;  // grey-mode effects do not apply
  scene.blur_sigma_px = 2;
  cv::Mat img;
  renderTarget(distortedCamera(), TargetGeometry{}, scene, Pose{20, 10, 0, 30, 20, 700}, img);
  int white = 0;
  for (auto it = img.begin<std::uint8_t>(); it != img.end<std::uint8_t>(); ++it) {
    ASSERT_TRUE(*it == 0 || *it == 255);
    white += *it == 255;
  }
  EXPECT_GT(white, 1000);
}

// Moments of the white disk against the analytic conic: the image of the circle
// x^2 + y^2 = R^2 through H = K [r1 r2 T] is C = H^-T diag(1, 1, -R^2) H^-1.
struct ConicEllipse {
  Eigen::Vector2d centre;
  Eigen::Matrix2d covariance;  // of the filled ellipse: (A/k)^-1 / 4
  double area;
};

ConicEllipse projectedCircle(const CameraModel& cam, const Pose& pose, double radius) {
  Eigen::Matrix3d K;
  K << cam.fu(), 0, cam.u0(), 0, cam.fv(), cam.v0(), 0, 0, 1;
  const Eigen::Matrix3d R = rotationMatrix(pose);
  Eigen::Matrix3d M;
  M << R.col(0), R.col(1), translation(pose);
  const Eigen::Matrix3d Hinv = (K * M).inverse();
  const Eigen::Matrix3d Q = Eigen::Vector3d(1, 1, -radius * radius).asDiagonal();
  const Eigen::Matrix3d C = Hinv.transpose() * Q * Hinv;
  const Eigen::Matrix2d A = C.topLeftCorner<2, 2>();
  const Eigen::Vector2d b = C.topRightCorner<2, 1>();
  ConicEllipse e;
  e.centre = -A.inverse() * b;
  const double k = b.dot(A.inverse() * b) - C(2, 2);
  const Eigen::Matrix2d shape = A / k;  // (x - c)^T shape (x - c) <= 1
  e.area = M_PI / std::sqrt(shape.determinant());
  e.covariance = shape.inverse() / 4.0;
  return e;
}

void expectMomentsMatch(const cv::Mat& img, const ConicEllipse& e, double area_tol, double centre_tol,
                        double cov_tol) {
  const cv::Moments m = cv::moments(img);
  const double area = m.m00 / 255.0;
  EXPECT_NEAR(area / e.area, 1.0, area_tol);
  EXPECT_NEAR(m.m10 / m.m00, e.centre.x(), centre_tol);
  EXPECT_NEAR(m.m01 / m.m00, e.centre.y(), centre_tol);
  const double scale = e.covariance.norm();
  EXPECT_NEAR(m.mu20 / m.m00, e.covariance(0, 0), cov_tol * scale);
  EXPECT_NEAR(m.mu11 / m.m00, e.covariance(0, 1), cov_tol * scale);
  EXPECT_NEAR(m.mu02 / m.m00, e.covariance(1, 1), cov_tol * scale);
}

TEST(VirtualRenderer, DiskMomentsMatchProjectedConic) {
  const CameraModel cam;
  TargetGeometry disk_only;
  disk_only.spot_radius_mm = 0.0;
  for (const Pose& pose : {Pose{0, 0, 0, 0, 0, 800}, Pose{40, -25, 30, 50, -20, 650}, Pose{-55, 35, -10, -90, 60, 1000},
                           Pose{70, 0, 0, 0, 0, 500}}) {
    SCOPED_TRACE(pose.rx_deg);
    const ConicEllipse e = projectedCircle(cam, pose, disk_only.radius_mm);
    cv::Mat grey;
    renderTarget(cam, disk_only, coverageScene(8), pose, grey);
    expectMomentsMatch(grey, e, 1e-3, 0.005, 2e-3);
    cv::Mat binary;
    renderTarget(cam, disk_only, binaryScene(), pose, binary);
    expectMomentsMatch(binary, e, 1e-2, 0.1, 1e-2);
  }
}

TEST(VirtualRenderer, OffsetSpotIsRightOfCentreAndRzTurnsIt) {
  const CameraModel cam;
  const TargetGeometry target;
  const double z = 800;
  const double spot_px = cam.fu() * target.spot_offset_mm / z;  // 25 px
  cv::Mat img;
  renderTarget(cam, target, binaryScene(), Pose{0, 0, 0, 0, 0, z}, img);
  const int cu = static_cast<int>(std::lround(cam.u0() + 0.5));
  const int cv_ = static_cast<int>(std::lround(cam.v0() + 0.5));
  auto at = [&](double u, double v) { return img.at<std::uint8_t>(static_cast<int>(std::lround(v)), static_cast<int>(std::lround(u))); };
  EXPECT_EQ(at(cam.u0() + spot_px, cam.v0()), 0);   // offset spot, right of centre
  EXPECT_EQ(at(cam.u0() - spot_px, cam.v0()), 255); // nothing on the left
  EXPECT_EQ(at(cam.u0(), cam.v0() + spot_px), 255);
  EXPECT_EQ(img.at<std::uint8_t>(cv_, cu), 0);       // centre spot

  // Rz = 90: +X turns onto +Y, which is down in the image.
  renderTarget(cam, target, binaryScene(), Pose{0, 0, 90, 0, 0, z}, img);
  EXPECT_EQ(at(cam.u0(), cam.v0() + spot_px), 0);
  EXPECT_EQ(at(cam.u0() + spot_px, cam.v0()), 255);
  EXPECT_EQ(at(cam.u0(), cam.v0() - spot_px), 255);
}

TEST(VirtualRenderer, DistortionMovesOffCentreTargetAsEquation47Predicts) {
  CameraModel ideal_cam = distortedCamera();
  ideal_cam.distortion = {};
  const CameraModel cam = distortedCamera();
  TargetGeometry disk_only;
  disk_only.spot_radius_mm = 0.0;
  const Pose pose{10, -15, 0, 250, 180, 900};
  cv::Mat ideal, distorted;
  renderTarget(ideal_cam, disk_only, coverageScene(8), pose, ideal);
  renderTarget(cam, disk_only, coverageScene(8), pose, distorted);
  const cv::Moments mi = cv::moments(ideal);
  const cv::Moments md = cv::moments(distorted);
  const Eigen::Vector2d ci(mi.m10 / mi.m00, mi.m01 / mi.m00);
  const Eigen::Vector2d cd(md.m10 / md.m00, md.m01 / md.m00);
  // Exact: the centroid of the forward-distorted outline.
  double area;
  Eigen::Vector2d expected;
  polygonMoments(circleImage(cam, pose, 0, disk_only.radius_mm), area, expected);
  EXPECT_NEAR(cd.x(), expected.x(), 0.01);
  EXPECT_NEAR(cd.y(), expected.y(), 0.01);
  EXPECT_NEAR(md.m00 / 255.0 / area, 1.0, 1e-3);
}

TEST(VirtualRenderer, SmallOffCentreDiskMovesByDeltaOfEquation47) {
  // A small disk moves as a whole by delta (eq. 4.7, relative to the principal point)
  // at its centre; the curvature of delta over its 11 px radius adds < 0.03 px.
  CameraModel ideal_cam = distortedCamera();
  ideal_cam.distortion = {};
  const CameraModel cam = distortedCamera();
  TargetGeometry small;
  small.radius_mm = 12.0;
  small.spot_radius_mm = 0.0;
  for (const Pose& pose : {Pose{0, 0, 0, 250, 180, 900}, Pose{0, 0, 0, -300, 200, 900}, Pose{0, 0, 0, -320, -230, 900}}) {
    cv::Mat ideal, distorted;
    renderTarget(ideal_cam, small, coverageScene(8), pose, ideal);
    renderTarget(cam, small, coverageScene(8), pose, distorted);
    const cv::Moments mi = cv::moments(ideal);
    const cv::Moments md = cv::moments(distorted);
    const Eigen::Vector2d ci(mi.m10 / mi.m00, mi.m01 / mi.m00);
    const Eigen::Vector2d cd(md.m10 / md.m00, md.m01 / md.m00);
    const Eigen::Vector2d delta = distortionDelta(cam.distortion, ci - Eigen::Vector2d(cam.u0(), cam.v0()));
    EXPECT_GT(delta.norm(), 2.0);
    EXPECT_NEAR((cd - ci).x(), delta.x(), 0.03) << pose.tx_mm;
    EXPECT_NEAR((cd - ci).y(), delta.y(), 0.03) << pose.tx_mm;
  }
}

TEST(VirtualRenderer, GreyEdgesAreAntiAliasedAndFlatAreasExact) {
  const CameraModel cam;
  VirtualSceneOptions scene = test::plainScene();  // grey, 230 / 20 / 110
  cv::Mat img;
  renderTarget(cam, TargetGeometry{}, scene, Pose{20, -10, 5, 0, 0, 800}, img);
  std::vector<int> histogram(256, 0);
  for (auto it = img.begin<std::uint8_t>(); it != img.end<std::uint8_t>(); ++it) ++histogram[*it];
  int intermediate = 0;
  for (int g = 0; g < 256; ++g)
    if (g != 20 && g != 110 && g != 230) intermediate += histogram[g];
  EXPECT_GT(intermediate, 200);  // the outline of disk, spots and card
  EXPECT_GT(histogram[230], 4000);
  EXPECT_GT(histogram[20], 4000);
  EXPECT_GT(histogram[110], 100000);
  EXPECT_EQ(img.at<std::uint8_t>(239, 330), 230);  // disk, between the two spots
  EXPECT_EQ(img.at<std::uint8_t>(0, 0), 110);
}

// The area of the disk (centre c, radius r) over the pixel [x0, x0 + 1] x [y0, y0 + 1]: its
// columns' covered heights, integrated by the midpoint rule.
double diskAreaInPixel(const Eigen::Vector2d& c, double r, double x0, double y0) {
  constexpr int kSteps = 2000;
  double area = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double x = x0 + (i + 0.5) / kSteps, dx = x - c.x();
    if (std::abs(dx) >= r) continue;
    const double h = std::sqrt(r * r - dx * dx);
    area += std::max(0.0, std::min(y0 + 1.0, c.y() + h) - std::max(y0, c.y() - h));
  }
  return area / kSteps;
}

// The anti-aliasing is the ground truth of every grey-level study: each rim pixel's level
// must be its exact coverage, to well under what the sub-pixel rim resolves. A disk seen
// head-on without distortion is a circle in the image, whose coverage of each pixel is known.
TEST(VirtualRenderer, DefaultAntiAliasingGivesEachRimPixelItsCoverage) {
  const CameraModel cam;
  TargetGeometry disk_only;
  disk_only.spot_radius_mm = 0.0;
  const Pose pose{0, 0, 0, 3.3, -2.1, 400};
  const double r = cam.fu() * disk_only.radius_mm / pose.tz_mm;  // 100 px
  const Eigen::Vector2d c = projectIdeal(cam, Eigen::Vector3d(pose.tx_mm, pose.ty_mm, pose.tz_mm));
  auto rmsError = [&](int supersampling) {
    cv::Mat img;
    renderTarget(cam, disk_only, coverageScene(supersampling), pose, img);
    double sum2 = 0.0;
    int n = 0;
    for (int v = 0; v < img.rows; ++v)
      for (int u = 0; u < img.cols; ++u) {
        if (std::abs((Eigen::Vector2d(u, v) - c).norm() - r) > 1.0) continue;  // not on the rim
        const double exact = diskAreaInPixel(c, r, u - 0.5, v - 0.5);  // pixel centres at integers
        if (exact <= 0.0 || exact >= 1.0) continue;
        const double e = img.at<std::uint8_t>(v, u) / 255.0 - exact;
        sum2 += e * e;
        ++n;
      }
    EXPECT_GT(n, 700);  // every pixel the rim crosses
    return std::sqrt(sum2 / n);
  };
  const double byDefault = rmsError(VirtualSceneOptions{}.supersampling);
  // Measured: 0.031 of the contrast at 4 x 4 samples (coverage in steps of 1/16, of 1/4 where
  // the rim runs along a row or column), 0.011 at 8 x 8, 0.004 at 16 x 16.
  EXPECT_LT(byDefault, 0.015);
  EXPECT_LT(byDefault, 0.5 * rmsError(4));
}

TEST(VirtualRenderer, IlluminationGradientScalesBrightnessAcrossTheWidth) {
  const CameraModel cam;
  VirtualSceneOptions scene = test::plainScene();
  scene.illumination_gradient = 0.4;
  cv::Mat img;
  renderTarget(cam, TargetGeometry{}, scene, Pose{0, 0, 0, 0, 0, 800}, img);
  for (int u : {0, 100, 319, 500, 639}) {
    const double factor = 1.0 + 0.4 * (u / 639.0 - 0.5);
    EXPECT_NEAR(img.at<std::uint8_t>(5, u), 110 * factor, 0.5) << u;
  }
  // The disk, right of the offset spot (u ~ 360).
  EXPECT_NEAR(img.at<std::uint8_t>(239, 360), 230 * (1.0 + 0.4 * (360 / 639.0 - 0.5)), 0.5);
}

TEST(VirtualRenderer, BlurIsAGaussianOfTheSharpImage) {
  const CameraModel cam;
  VirtualSceneOptions scene = test::plainScene();
  const Pose pose{15, 10, 0, 0, 0, 800};
  cv::Mat sharp, blurred;
  renderTarget(cam, TargetGeometry{}, scene, pose, sharp);
  scene.blur_sigma_px = 1.5;
  renderTarget(cam, TargetGeometry{}, scene, pose, blurred);
  cv::Mat expected;
  sharp.convertTo(expected, CV_32F);
  cv::GaussianBlur(expected, expected, cv::Size(0, 0), 1.5, 1.5, cv::BORDER_REPLICATE);
  cv::Mat got;
  blurred.convertTo(got, CV_32F);
  double max_diff;
  cv::minMaxLoc(cv::abs(got - expected), nullptr, &max_diff);
  EXPECT_LE(max_diff, 1.0);
  EXPECT_GT(cv::norm(sharp, blurred, cv::NORM_L1), 1000.0);
}

TEST(VirtualRenderer, NoiseHasTheGivenSigmaAndIsReproducible) {
  const CameraModel cam;
  VirtualSceneOptions scene = test::plainScene();
  const Pose pose{0, 0, 0, 0, 0, 800};
  cv::Mat clean, a, b, c, d;
  renderTarget(cam, TargetGeometry{}, scene, pose, clean);
  scene.noise_sigma = 6.0;
  renderTarget(cam, TargetGeometry{}, scene, pose, a, 7);
  renderTarget(cam, TargetGeometry{}, scene, pose, b, 7);
  renderTarget(cam, TargetGeometry{}, scene, pose, c, 8);
  scene.seed = 2;
  renderTarget(cam, TargetGeometry{}, scene, pose, d, 7);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a, c, cv::NORM_L1), 1e5);
  EXPECT_GT(cv::norm(a, d, cv::NORM_L1), 1e5);
  cv::Mat diff;
  cv::subtract(a, clean, diff, cv::noArray(), CV_32F);
  cv::Scalar mean, stddev;
  cv::meanStdDev(diff, mean, stddev);
  EXPECT_NEAR(mean[0], 0.0, 0.05);
  EXPECT_NEAR(stddev[0], std::sqrt(6.0 * 6.0 + 1.0 / 12.0), 0.1);  // plus rounding to integers
}

// The same scene and seed render the same frame; another seed another one.
void expectTheSeedDecides(const CameraModel& cam, VirtualSceneOptions scene, const Pose& pose) {
  cv::Mat a, b, other;
  renderTarget(cam, TargetGeometry{}, scene, pose, a);
  renderTarget(cam, TargetGeometry{}, scene, pose, b);
  scene.seed += 98;
  renderTarget(cam, TargetGeometry{}, scene, pose, other);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a, other, cv::NORM_L1), 1e5);
}

TEST(VirtualRenderer, ClutterIsReproducibleAndNeverOverlapsTheCard) {
  const CameraModel cam;
  VirtualSceneOptions scene = test::plainScene();
  const Pose pose{25, -15, 10, 40, 30, 600};
  cv::Mat plain, a;
  renderTarget(cam, TargetGeometry{}, scene, pose, plain);
  scene.clutter = 40;
  renderTarget(cam, TargetGeometry{}, scene, pose, a);
  expectTheSeedDecides(cam, scene, pose);

  // The card and what is on it (every pixel that is not background without clutter,
  // shrunk by the anti-aliased rim) is untouched.
  cv::Mat card = plain != 110;
  cv::erode(card, card, cv::Mat(), cv::Point(-1, -1), 2);
  ASSERT_GT(cv::countNonZero(card), 15000);
  cv::Mat changed = (a != plain) & card;
  EXPECT_EQ(cv::countNonZero(changed), 0);
  // Clutter is there, in the clutter colour, outside the card.
  cv::Mat clutter = (a == 230) & (plain == 110);
  EXPECT_GT(cv::countNonZero(clutter), 5000);
}

// The Virtual source's default backdrop is a lit room (a scene made directly is plain): many
// levels around the card, the card itself as on the plain background times the room's light
// (scene_shapes.h), the same room for the same seed.
TEST(VirtualRenderer, RoomBackdropSurroundsTheCardAndLightsItUnevenly) {
  const CameraModel cam;
  ASSERT_EQ(Settings{}.virtual_scene.backdrop, Backdrop::Room);
  ASSERT_EQ(VirtualSceneOptions{}.backdrop, Backdrop::Plain);
  VirtualSceneOptions scene = Settings{}.virtual_scene;
  const Pose pose{25, -15, 10, 40, 30, 600};
  cv::Mat plain, a;
  renderTarget(cam, TargetGeometry{}, test::plainScene(), pose, plain);
  renderTarget(cam, TargetGeometry{}, scene, pose, a);
  expectTheSeedDecides(cam, scene, pose);

  cv::Mat light;
  makeRoomLight(cam.width, cam.height, light);
  double lo = 0, hi = 0;
  cv::minMaxLoc(light, &lo, &hi);
  EXPECT_LT(lo, 0.8);
  EXPECT_GT(hi, 1.01);  // brighter than the centre on the window's side
  // On the card: the plain render's level times the light, to the rounding of each.
  cv::Mat card = plain != 110;
  cv::erode(card, card, cv::Mat(), cv::Point(-1, -1), 2);
  ASSERT_GT(cv::countNonZero(card), 15000);
  cv::Mat lit, got, diff;
  plain.convertTo(lit, CV_32F);
  cv::multiply(lit, light, lit);
  a.convertTo(got, CV_32F);
  cv::absdiff(lit, got, diff);
  double worst = 0;
  cv::minMaxLoc(diff, nullptr, &worst, nullptr, nullptr, card);
  EXPECT_LE(worst, 1.0);  // both renders rounded to whole levels
  // Around it: a room of many levels, not the flat grey.
  cv::Mat around = plain == 110;
  cv::erode(around, around, cv::Mat(), cv::Point(-1, -1), 2);
  int hist[256] = {};
  int flat = 0, counted = 0;
  for (int v = 0; v < a.rows; ++v)
    for (int u = 0; u < a.cols; ++u)
      if (around.at<std::uint8_t>(v, u)) {
        ++hist[a.at<std::uint8_t>(v, u)];
        flat += a.at<std::uint8_t>(v, u) == 110;
        ++counted;
      }
  EXPECT_GT(std::count_if(std::begin(hist), std::end(hist), [&](int n) { return n > counted / 200; }), 12);
  EXPECT_LT(flat, counted / 10);
}

TEST(VirtualRenderer, InvisibleTargetsGiveAnEmptyScene) {
  const CameraModel cam;
  const TargetGeometry target;
  const VirtualSceneOptions scene = binaryScene();
  cv::Mat img;
  for (const Pose& pose : {Pose{0, 90, 0, 0, 0, 800},     // edge-on
                           Pose{90, 0, 0, 0, 0, 800},     // edge-on about X
                           Pose{0, 0, 0, 0, 0, -800},     // behind the camera
                           Pose{0, 180, 0, 0, 0, 800},    // facing away: the back of the card
                           Pose{0, 0, 0, 0, 0, 0}}) {     // camera in the plane
    renderTarget(cam, target, scene, pose, img);
    EXPECT_EQ(cv::countNonZero(img), 0) << pose.rx_deg << " " << pose.ry_deg << " " << pose.tz_mm;
  }
  // Nearly edge-on and straddling the camera plane: only part of it is in front.
  renderTarget(cam, target, scene, Pose{0, 89.99, 0, 0, 0, 800}, img);
  renderTarget(cam, target, scene, Pose{80, 0, 0, 0, 0, 20}, img);
  renderTarget(distortedCamera(), target, test::plainScene(), Pose{-85, 30, 0, 10, 0, 5}, img);
  SUCCEED();
}

TEST(VirtualRenderer, TargetInView) {
  const CameraModel cam;
  const TargetGeometry target;
  EXPECT_TRUE(targetInView(cam, target, Pose{0, 0, 0, 0, 0, 800}));
  EXPECT_TRUE(targetInView(cam, target, Pose{50, 0, 30, 0, 0, 800}));
  // The disk's right edge at u = 319.5 + 800 * (tx + 50) / 800: inside up to tx = 270.
  EXPECT_TRUE(targetInView(cam, target, Pose{0, 0, 0, 269, 0, 800}));
  EXPECT_FALSE(targetInView(cam, target, Pose{0, 0, 0, 271, 0, 800}));
  EXPECT_FALSE(targetInView(cam, target, Pose{0, 0, 0, 2000, 0, 800}));
  EXPECT_FALSE(targetInView(cam, target, Pose{0, 0, 0, 0, 0, -800}));
  EXPECT_FALSE(targetInView(cam, target, Pose{0, 90, 0, 0, 0, 800}));
  EXPECT_FALSE(targetInView(cam, target, Pose{0, 180, 0, 0, 0, 800}));
  EXPECT_FALSE(targetInView(cam, target, Pose{0, 0, 0, 0, 0, 60}));  // too close: overfills the image
}

TEST(VirtualRenderer, EmptyCameraGivesEmptyImage) {
  CameraModel cam;
  cam.width = 0;
  cv::Mat img;
  renderTarget(cam, TargetGeometry{}, binaryScene(), Pose{}, img);
  EXPECT_TRUE(img.empty());
}

TEST(VirtualRenderer, PatternHasGridSpotsAwayFromTheCard) {
  const CameraModel cam;
  const TargetGeometry target;
  PatternGeometry pattern;  // 25 mm spacing, 4 mm spots
  pattern.card_size_mm = 140;  // half 70: the spot at 75 mm keeps 1 mm clear of the card
  VirtualSceneOptions scene = binaryScene();
  const Pose pose{0, 0, 0, 0, 0, 1000};  // 0.8 px per mm
  auto pixel = [&](const cv::Mat& img, double x, double y) {
    const Eigen::Vector2d p = imageOf(cam, pose, x, y);
    return img.at<std::uint8_t>(static_cast<int>(std::lround(p.y())), static_cast<int>(std::lround(p.x())));
  };
  cv::Mat img;
  renderPattern(cam, target, pattern, scene, pose, img);
  EXPECT_EQ(pixel(img, 75, 0), 0);      // grid spot
  EXPECT_EQ(pixel(img, -75, 50), 0);
  EXPECT_EQ(pixel(img, 100, 125), 0);
  EXPECT_EQ(pixel(img, 87.5, 0), 255);  // sheet between spots
  EXPECT_EQ(pixel(img, 80, 0), 255);    // just beyond the spot's 4 mm radius
  EXPECT_EQ(pixel(img, 68, 0), 0);      // card
  EXPECT_EQ(pixel(img, 35, 0), 255);    // target disk
  EXPECT_EQ(pixel(img, 25, 0), 0);      // offset spot
  // The target and its card look exactly as renderTarget draws them.
  VirtualSceneOptions card_scene = scene;
  card_scene.card_size_mm = pattern.card_size_mm;
  cv::Mat target_only;
  renderTarget(cam, target, card_scene, pose, target_only);
  const Eigen::Vector2d c0 = imageOf(cam, pose, -65, -65);
  const Eigen::Vector2d c1 = imageOf(cam, pose, 65, 65);
  const cv::Rect card(cv::Point(static_cast<int>(c0.x()) + 1, static_cast<int>(c0.y()) + 1),
                      cv::Point(static_cast<int>(c1.x()), static_cast<int>(c1.y())));
  EXPECT_EQ(cv::norm(img(card), target_only(card), cv::NORM_INF), 0.0);

  // A wider card: the spots at 75 mm would touch it (73 + 4 > 75) and are left out.
  pattern.card_size_mm = 146;
  renderPattern(cam, target, pattern, scene, pose, img);
  EXPECT_EQ(pixel(img, 75, 0), 255);
  EXPECT_EQ(pixel(img, 75, 75), 255);
  EXPECT_EQ(pixel(img, 100, 0), 0);
  EXPECT_EQ(pixel(img, 75, 100), 0);
}

}  // namespace
}  // namespace imagepro
