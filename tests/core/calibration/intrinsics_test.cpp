// Full intrinsic calibration (core/calibration/intrinsics.h) on printable pages of each dot
// grid, photographed by a camera of known intrinsics and lens from tilts up to 60 deg.
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "calibration_scenes.h"
#include "core/calibration/grid_finder.h"
#include "core/calibration/intrinsics.h"
#include "intrinsic_scenes.h"

namespace imagepro {
namespace {

using testing::GridView;
using testing::PhotoConditions;
using testing::RenderedGrid;

using testing::gridSpec;
DotGridSpec asymmetricSpec() { return gridSpec(DotGridKind::AsymmetricCircles, 4, 11, 15.0, 7.5); }
DotGridSpec symmetricSpec() { return gridSpec(DotGridKind::SymmetricCircles, 9, 6, 25.0, 12.5); }
DotGridSpec thesisSpec() {
  DotGridSpec s = gridSpec(DotGridKind::Thesis, 13, 8, 20.0, 6.0);
  s.card_size_mm = 50.0;
  s.target = {20.0, 3.0, 10.0};
  return s;
}

// The estimated lens's displacement field against the truth's, at every 4th pixel of the
// image taken as undistorted, each about its own principal point.
double fieldRmsPx(const CameraModel& truth, const IntrinsicsResult& r) {
  std::vector<cv::Point3d> rays;
  std::vector<Eigen::Vector2d> at;
  for (int v = 0; v < truth.height; v += 4)
    for (int u = 0; u < truth.width; u += 4) {
      at.emplace_back(u, v);
      rays.emplace_back((u - r.cx) / r.fx, (v - r.cy) / r.fy, 1.0);
    }
  std::vector<cv::Point2d> est;
  const cv::Matx33d K(r.fx, 0, r.cx, 0, r.fy, r.cy, 0, 0, 1);
  cv::projectPoints(rays, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K,
                    std::vector<double>(r.opencv_dist.begin(), r.opencv_dist.end()), est);
  double sum = 0;
  for (size_t i = 0; i < at.size(); ++i) {
    const Eigen::Vector2d truthDelta = distortPixel(truth, at[i]) - at[i];
    const Eigen::Vector2d estDelta(est[i].x - at[i].x(), est[i].y - at[i].y());
    sum += (estDelta - truthDelta).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(at.size()));
}

struct Case {
  const char* name;
  DotGridSpec spec;
  Distortion lens;
  bool uneven;
  double distance_mm;
};

IntrinsicsResult calibrateCase(const Case& c, const IntrinsicsOptions& options, RenderedGrid& rendered) {
  const CameraModel truth = testing::intrinsicTruthCamera(c.lens);
  PhotoConditions light;
  if (c.uneven) {
    light.gradient = 0.55;
    light.spot = 0.6;
  }
  std::string error;
  EXPECT_TRUE(testing::renderGridViews(c.spec, Paper::A4, truth, testing::intrinsicViews(c.distance_mm), light, rendered, error)) << error;
  IntrinsicsResult r;
  calibrateIntrinsics(rendered.images, c.spec, options, r);
  return r;
}

class IntrinsicsRoundTrip : public ::testing::TestWithParam<Case> {};

TEST_P(IntrinsicsRoundTrip, RecoversTheCamera) {
  const Case& c = GetParam();
  RenderedGrid rendered;
  const IntrinsicsResult r = calibrateCase(c, IntrinsicsOptions{}, rendered);
  ASSERT_EQ(r.status, Status::Ok);
  const CameraModel truth = testing::intrinsicTruthCamera(c.lens);
  int found = 0;
  for (const IntrinsicsView& v : r.views) {
    found += ok(v.status);
    EXPECT_EQ(v.status, Status::Ok) << "tilt " << v.tilt_deg;
  }
  const double field = fieldRmsPx(truth, r);
  std::printf("%s: %d of %zu views, rms %.4f px, fx %+.4f %% fy %+.4f %% cx %+.3f cy %+.3f px, k1 %.4e (%.4e) "
              "k2 %.4e (%.4e), field %.4f px, our model's fit %.4f px\n",
              c.name, found, r.views.size(), r.rms_px, 100 * (r.fx / truth.fu() - 1), 100 * (r.fy / truth.fv() - 1),
              r.cx - truth.u0(), r.cy - truth.v0(), r.distortion.k1, c.lens.k1, r.distortion.k2, c.lens.k2, field,
              r.model_fit_rms_px);
  // Measured (docs/calibration.md): focal lengths within 0.05 %, principal point within
  // 0.3 px, fields 0.006-0.015 px RMS in even light and up to 0.08 px under the uneven
  // light, reprojection 0.007-0.015 px.
  EXPECT_NEAR(r.fx / truth.fu(), 1.0, 1e-3);
  EXPECT_NEAR(r.fy / truth.fv(), 1.0, 1e-3);
  EXPECT_NEAR(r.cx, truth.u0(), 0.5);
  EXPECT_NEAR(r.cy, truth.v0(), 0.5);
  EXPECT_NEAR(r.distortion.k1, c.lens.k1, 0.04 * std::abs(c.lens.k1));
  EXPECT_LT(field, c.uneven ? 0.1 : 0.03);
  EXPECT_LT(r.rms_px, 0.03);
  EXPECT_LT(r.model_fit_rms_px, 0.01);
  // The 60 deg view is among them.
  double steepest = 0;
  for (const IntrinsicsView& v : r.views) steepest = std::max(steepest, v.tilt_deg);
  EXPECT_GT(steepest, 55.0);
}

INSTANTIATE_TEST_SUITE_P(
    Grids, IntrinsicsRoundTrip,
    ::testing::Values(Case{"asymmetric, thesis lens", asymmetricSpec(), kThesisCameraDistortion, false, 420.0},
                      // The grid of the photographs: 4 x 5 dots of 20 mm, s = 30 mm, filling the image.
                      Case{"asymmetric 4 x 5, 20 mm dots, webcam lens, uneven light",
                           gridSpec(DotGridKind::AsymmetricCircles, 4, 5, 30.0, 20.0), testing::kWebcamLens, true, 400.0},
                      Case{"asymmetric, webcam lens, uneven light", asymmetricSpec(), testing::kWebcamLens, true, 420.0},
                      Case{"symmetric, webcam lens, uneven light", symmetricSpec(), testing::kWebcamLens, true, 500.0},
                      Case{"symmetric, thesis lens", symmetricSpec(), kThesisCameraDistortion, false, 500.0},
                      Case{"thesis pattern, webcam lens, uneven light", thesisSpec(), testing::kWebcamLens, true, 450.0}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::to_string(info.index); });

}  // namespace
}  // namespace imagepro

namespace imagepro {
namespace {

TEST(DotGrid, OpenCvConventions) {
  DotGridSpec s = asymmetricSpec();
  EXPECT_EQ(dotGridPointMm(s, 0, 0), Eigen::Vector2d(0, 0));
  EXPECT_EQ(dotGridPointMm(s, 1, 0), Eigen::Vector2d(30, 0));   // (2j + i mod 2) s
  EXPECT_EQ(dotGridPointMm(s, 0, 1), Eigen::Vector2d(15, 15));
  EXPECT_EQ(dotGridPointMm(s, 2, 3), Eigen::Vector2d(75, 45));
  s = symmetricSpec();
  EXPECT_EQ(dotGridPointMm(s, 2, 3), Eigen::Vector2d(50, 75));
  EXPECT_EQ(parseDotGridKind("asymmetric-circles"), DotGridKind::AsymmetricCircles);
  EXPECT_FALSE(parseDotGridKind("chessboard").has_value());
}

TEST(DotGrid, BadDescriptionsAreNamed) {
  DotGridSpec s = symmetricSpec();
  s.rows = 0;
  EXPECT_NE(dotGridSpecError(s).find("rows"), std::string::npos);
  s = symmetricSpec();
  s.spacing_mm = -5;
  EXPECT_NE(dotGridSpecError(s).find("spacing"), std::string::npos);
  s = symmetricSpec();
  s.dot_diameter_mm = 30;  // wider than the spacing
  EXPECT_FALSE(dotGridSpecError(s).empty());
  IntrinsicsResult r;
  std::vector<cv::Mat> none;
  s.rows = 0;
  EXPECT_EQ(calibrateIntrinsics(none, s, {}, r), Status::InvalidPattern);
}

// The images rendered for OpenCV's grids are OpenCV's: its own finder with its own blob
// detector takes them with the same pattern size, and names the dots as ours do.
TEST(DotGrid, OpenCvFindsTheRenderedGrids) {
  for (const DotGridSpec& s : {asymmetricSpec(), symmetricSpec()}) {
    RenderedGrid rendered;
    std::string error;
    const std::vector<GridView> all = testing::intrinsicViews(450.0);
    const std::vector<GridView> views(all.begin(), all.begin() + 3);
    ASSERT_TRUE(testing::renderGridViews(s, Paper::A4, testing::intrinsicTruthCamera(kThesisCameraDistortion), views,
                                         PhotoConditions{}, rendered, error));
    for (const cv::Mat& im : rendered.images) {
      std::vector<cv::Point2f> centres;
      const int flag = s.kind == DotGridKind::AsymmetricCircles ? cv::CALIB_CB_ASYMMETRIC_GRID : cv::CALIB_CB_SYMMETRIC_GRID;
      ASSERT_TRUE(cv::findCirclesGrid(im, cv::Size(s.columns, s.rows), centres, flag)) << dotGridKindName(s.kind);
      GridDetection g;
      ASSERT_EQ(findDotGrid(im, s, g), Status::Ok) << dotGridKindName(s.kind) << " " << g.candidates;
      ASSERT_EQ(g.dots.size(), centres.size());
      // The same dot first, or the symmetric grid's other way round.
      const double same = std::hypot(g.dots[0].image_px.x() - centres[0].x, g.dots[0].image_px.y() - centres[0].y);
      const double flipped = std::hypot(g.dots[0].image_px.x() - centres.back().x, g.dots[0].image_px.y() - centres.back().y);
      EXPECT_LT(s.kind == DotGridKind::AsymmetricCircles ? same : std::min(same, flipped), 1.0);
    }
  }
}

// Part of the thesis pattern out of view: the lattice names what is seen; too few views
// and an empty image are named.
TEST(DotGrid, PartialThesisGridAndErrors) {
  const DotGridSpec s = thesisSpec();
  RenderedGrid rendered;
  std::string error;
  // Close enough that the sheet overflows the image.
  const std::vector<GridView> views{{10, 20, 5, 0, 0, 280}, {-20, 0, 0, 30, 20, 300}};
  ASSERT_TRUE(testing::renderGridViews(s, Paper::A4, testing::intrinsicTruthCamera(testing::kWebcamLens), views,
                                       PhotoConditions{}, rendered, error));
  for (const cv::Mat& im : rendered.images) {
    GridDetection g;
    ASSERT_EQ(findDotGrid(im, s, g), Status::Ok);
    EXPECT_TRUE(g.partial);
    EXPECT_GT(g.dots.size(), 40u);
    // Neighbours on the lattice are neighbours in the image.
    for (const FoundDot& a : g.dots)
      for (const FoundDot& b : g.dots)
        if (std::abs(a.column - b.column) + std::abs(a.row - b.row) == 1) {
          EXPECT_LT((a.image_px - b.image_px).norm(), 120.0);
        }
  }
  IntrinsicsResult r;
  EXPECT_EQ(calibrateIntrinsics(rendered.images, s, {}, r), Status::TooFewViews);
  GridDetection g;
  EXPECT_EQ(findDotGrid(cv::Mat(480, 640, CV_8UC1, cv::Scalar(200)), s, g), Status::GridNotFound);
  EXPECT_EQ(findDotGrid(cv::Mat(), s, g), Status::EmptyFrame);
}

}  // namespace
}  // namespace imagepro

namespace imagepro {
namespace {

// Side by side with OpenCV on the same images (docs/calibration.md): cv::findCirclesGrid
// with its default blob detector, then cv::calibrateCamera (k3 fixed, as ours). Ours must
// find the grid in at least as many images.
TEST(IntrinsicsVersusOpenCv, SameImages) {
  for (const Case& c : {Case{"asymmetric, webcam lens, uneven light", asymmetricSpec(), testing::kWebcamLens, true, 420.0},
                        Case{"symmetric, webcam lens, uneven light", symmetricSpec(), testing::kWebcamLens, true, 500.0}}) {
    RenderedGrid rendered;
    const IntrinsicsResult ours = calibrateCase(c, IntrinsicsOptions{}, rendered);
    ASSERT_EQ(ours.status, Status::Ok);
    const CameraModel truth = testing::intrinsicTruthCamera(c.lens);
    std::vector<std::vector<cv::Point3f>> obj;
    std::vector<std::vector<cv::Point2f>> img;
    for (const cv::Mat& im : rendered.images) {
      std::vector<cv::Point2f> centres;
      const int flag =
          c.spec.kind == DotGridKind::AsymmetricCircles ? cv::CALIB_CB_ASYMMETRIC_GRID : cv::CALIB_CB_SYMMETRIC_GRID;
      if (!cv::findCirclesGrid(im, cv::Size(c.spec.columns, c.spec.rows), centres, flag)) continue;
      std::vector<cv::Point3f> o;
      for (int i = 0; i < c.spec.rows; ++i)
        for (int j = 0; j < c.spec.columns; ++j) {
          const Eigen::Vector2d p = dotGridPointMm(c.spec, j, i);
          o.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), 0.0f);
        }
      obj.push_back(o);
      img.push_back(centres);
    }
    EXPECT_GE(ours.views_used, static_cast<int>(obj.size()));
    std::printf("%s: ours %d of %zu views, fx %+.3f %% cx %+.2f cy %+.2f px, field %.4f px\n", c.name,
                ours.views_used, rendered.images.size(), 100 * (ours.fx / truth.fu() - 1), ours.cx - truth.u0(),
                ours.cy - truth.v0(), fieldRmsPx(truth, ours));
    if (obj.size() < 3) {
      std::printf("%s: OpenCV %zu of %zu views: too few to calibrate\n", c.name, obj.size(), rendered.images.size());
      continue;
    }
    cv::Mat K, D;
    std::vector<cv::Mat> rv, tv;
    const double rms = cv::calibrateCamera(obj, img, cv::Size(truth.width, truth.height), K, D, rv, tv, cv::CALIB_FIX_K3);
    IntrinsicsResult theirs;
    theirs.fx = K.at<double>(0, 0);
    theirs.fy = K.at<double>(1, 1);
    theirs.cx = K.at<double>(0, 2);
    theirs.cy = K.at<double>(1, 2);
    for (int k = 0; k < 5; ++k) theirs.opencv_dist[k] = D.at<double>(k);
    std::printf("%s: OpenCV %zu of %zu views, fx %+.3f %% cx %+.2f cy %+.2f px, field %.4f px, rms %.4f px\n", c.name,
                obj.size(), rendered.images.size(), 100 * (theirs.fx / truth.fu() - 1), theirs.cx - truth.u0(),
                theirs.cy - truth.v0(), fieldRmsPx(truth, theirs), rms);
  }
}

}  // namespace
}  // namespace imagepro
