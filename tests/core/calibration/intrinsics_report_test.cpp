// The quality report (core/calibration/intrinsics_report.h) and OpenCV's camera file
// (core/calibration/opencv_camera_file.h) on exactly known views.
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "calibration_scenes.h"
#include "core/calibration/intrinsics.h"
#include "core/calibration/intrinsics_report.h"
#include "core/calibration/opencv_camera_file.h"
#include "support/test_dirs.h"

namespace imagepro {
namespace {

// A view of a symmetric 9 x 6 grid, 25 mm, projected exactly (centroids offset as a
// camera sees them) by `K`, `dist` at the pose (rvec, tvec) of its first dot.
IntrinsicsView exactView(const cv::Matx33d& K, const std::vector<double>& dist, const cv::Vec3d& rvec,
                         const cv::Vec3d& tvec) {
  IntrinsicsView v;
  v.status = Status::Ok;
  std::vector<cv::Point3d> obj;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 9; ++j) obj.emplace_back(25.0 * j, 25.0 * i, 0.0);
  std::vector<cv::Point2d> img;
  cv::projectPoints(obj, rvec, tvec, K, dist, img);
  for (size_t k = 0; k < obj.size(); ++k) {
    FoundDot d;
    d.column = static_cast<int>(k % 9);
    d.row = static_cast<int>(k / 9);
    d.object_mm = {obj[k].x, obj[k].y};
    d.image_px = Eigen::Vector2d(img[k].x, img[k].y) + dotCentroidOffsetPx(K, dist, rvec, tvec, d.object_mm, 12.5);
    v.found.push_back(d);
  }
  return v;
}

DotGridSpec symmetric() {
  DotGridSpec s;
  s.kind = DotGridKind::SymmetricCircles;
  s.columns = 9;
  s.rows = 6;
  s.spacing_mm = 25.0;
  s.dot_diameter_mm = 12.5;
  return s;
}

const cv::Matx33d kK(810.0, 0, 322.0, 0, 805.0, 241.0, 0, 0, 1);
const std::vector<double> kDist{-0.25, 0.08, 0.001, -0.0005, 0.0};

TEST(IntrinsicsReport, ExactDotsGiveTheCameraBackAndTheWarningsFollowTheViews) {
  // Three views tilted about x only, the grid in the middle: the focal length is found but
  // the report names the narrow coverage and the single tilt axis.
  std::vector<IntrinsicsView> views;
  for (const double a : {0.0, 0.5, -0.5})
    views.push_back(exactView(kK, kDist, cv::Vec3d(a, 0, 0), cv::Vec3d(-100, -60, 600)));
  IntrinsicsResult r;
  ASSERT_EQ(calibrateFoundDots(views, cv::Size(640, 480), symmetric(), {}, r), Status::Ok);
  EXPECT_NEAR(r.fx, 810.0, 0.5);
  EXPECT_NEAR(r.fy, 805.0, 0.5);
  EXPECT_LT(r.rms_px, 0.01);  // the centroid offsets corrected
  const CoverageMap map = coverageMap(r);
  const auto names = [&] {
    std::string s;
    for (const CalibrationWarning& w : intrinsicsWarnings(r, map)) s += w.name + " ";
    return s;
  }();
  EXPECT_NE(names.find("OneTiltAxis"), std::string::npos) << names;
  EXPECT_NE(names.find("FewViews"), std::string::npos) << names;
  EXPECT_NE(names.find("PoorBorderCoverage"), std::string::npos) << names;
  EXPECT_EQ(coverageText(map).size(), static_cast<size_t>(kCoverageRows * (2 * kCoverageColumns)));
  EXPECT_EQ(coverageImage(r, map).size(), cv::Size(640, 480));

  // Views turned both ways and moved over the image: no warning about angles or views.
  views.clear();
  for (const auto& [rv, tv] : {std::pair{cv::Vec3d(0.6, 0, 0), cv::Vec3d(-240, -140, 560)},
                               {cv::Vec3d(0, 0.6, 0), cv::Vec3d(-20, -140, 560)},
                               {cv::Vec3d(-0.5, 0.3, 0), cv::Vec3d(-240, 10, 600)},
                               {cv::Vec3d(0.3, -0.5, 0), cv::Vec3d(-20, 10, 600)},
                               {cv::Vec3d(0, 0, 0.1), cv::Vec3d(-100, -60, 500)}})
    views.push_back(exactView(kK, kDist, rv, tv));
  ASSERT_EQ(calibrateFoundDots(views, cv::Size(640, 480), symmetric(), {}, r), Status::Ok);
  for (const CalibrationWarning& w : intrinsicsWarnings(r, coverageMap(r))) {
    EXPECT_NE(w.name, "OneTiltAxis");
    EXPECT_NE(w.name, "FewViews");
    EXPECT_NE(w.name, "NarrowViewAngles");
  }
  EXPECT_NEAR(r.cx, 322.0, 0.1);
  EXPECT_NEAR(r.opencv_dist[0], -0.25, 0.005);

  // The result as OpenCV's camera: OpenCV's own coefficients, not refitted.
  const OpenCvCamera oc = openCvCameraOf(r);
  EXPECT_EQ(oc.width, 640);
  EXPECT_EQ(oc.height, 480);
  EXPECT_EQ(oc.camera_matrix, cv::Matx33d(r.fx, 0, r.cx, 0, r.fy, r.cy, 0, 0, 1));
  EXPECT_EQ(oc.distortion, std::vector<double>(r.opencv_dist.begin(), r.opencv_dist.end()));
}

TEST(Intrinsics, ProgressIsReportedPerImageAndStopsTheRun) {
  const cv::Mat blank(480, 640, CV_8UC1, cv::Scalar(200));
  const std::vector<cv::Mat> images(3, blank);
  std::vector<std::pair<int, int>> calls;
  IntrinsicsResult r;
  EXPECT_EQ(calibrateIntrinsics(images, symmetric(), {}, r,
                                [&](int searched, int total) {
                                  calls.emplace_back(searched, total);
                                  return true;
                                }),
            Status::TooFewViews);
  EXPECT_EQ(calls, (std::vector<std::pair<int, int>>{{0, 3}, {1, 3}, {2, 3}, {3, 3}}));
  for (const IntrinsicsView& v : r.views) EXPECT_EQ(v.status, Status::GridNotFound);
  // false stops it before the next image.
  calls.clear();
  EXPECT_EQ(calibrateIntrinsics(images, symmetric(), {}, r,
                                [&](int searched, int total) {
                                  calls.emplace_back(searched, total);
                                  return searched < 1;
                                }),
            Status::Stopped);
  EXPECT_EQ(calls.size(), 2u);
  EXPECT_EQ(r.status, Status::Stopped);
}

TEST(IntrinsicsReport, AMisnamedViewIsLeftOut) {
  std::vector<IntrinsicsView> views;
  for (const auto& rv : {cv::Vec3d(0.5, 0, 0), cv::Vec3d(0, 0.5, 0), cv::Vec3d(-0.4, 0.3, 0), cv::Vec3d(0.3, -0.4, 0)})
    views.push_back(exactView(kK, kDist, rv, cv::Vec3d(-100, -60, 600)));
  std::swap(views[2].found[3].image_px, views[2].found[40].image_px);
  IntrinsicsResult r;
  ASSERT_EQ(calibrateFoundDots(views, cv::Size(640, 480), symmetric(), {}, r), Status::Ok);
  EXPECT_EQ(r.views[2].status, Status::PoseInconsistent);
  EXPECT_EQ(r.views_used, 3);
  views.resize(2);
  EXPECT_EQ(calibrateFoundDots(views, cv::Size(640, 480), symmetric(), {}, r), Status::TooFewViews);
}

// OpenCV's camera file: written, read back through cv::FileStorage, the same camera; and a
// camera of this project through it and back.
TEST(OpenCvCameraFile, RoundTrips) {
  const auto dir = test::freshDir("opencv_camera_file");
  OpenCvCamera c;
  c.width = 640;
  c.height = 480;
  c.camera_matrix = kK;
  c.distortion = kDist;
  std::string error;
  for (const char* name : {"camera.yaml", "camera.json"}) {
    const std::string path = (dir / name).string();
    ASSERT_TRUE(writeOpenCvCamera(path, c, error)) << error;
    cv::FileStorage fs(path, cv::FileStorage::READ);  // as OpenCV's own tools read it
    cv::Mat K, D;
    fs["camera_matrix"] >> K;
    fs["distortion_coefficients"] >> D;
    EXPECT_EQ(static_cast<int>(fs["image_width"]), 640);
    EXPECT_EQ(K.at<double>(0, 0), 810.0);
    EXPECT_EQ(D.total(), 5u);
    OpenCvCamera back;
    ASSERT_TRUE(readOpenCvCamera(path, back, error)) << error;
    EXPECT_EQ(back.camera_matrix, c.camera_matrix);
    EXPECT_EQ(back.distortion, c.distortion);
  }
  CameraModel cam;
  cam.distortion = kThesisCameraDistortion;
  cam.principal_point_px = {330.0, 250.0};
  CameraModel back;
  double fit = 1.0;
  applyOpenCvCamera(openCvCameraOf(cam), back, &fit);
  EXPECT_LT(fit, 1e-6);
  EXPECT_NEAR(back.image_plane_distance_mm, cam.image_plane_distance_mm, 1e-9);
  EXPECT_NEAR(back.principal_point_px[0], 330.0, 1e-9);
  EXPECT_NEAR(back.distortion.k1, cam.distortion.k1, 1e-6 * std::abs(cam.distortion.k1));
  EXPECT_NEAR(back.distortion.p2, cam.distortion.p2, 1e-6 * std::abs(cam.distortion.p2));
  OpenCvCamera missing;
  EXPECT_FALSE(readOpenCvCamera((dir / "none.yaml").string(), missing, error));
  std::ofstream(dir / "garbage.yaml") << "not: [a camera";
  EXPECT_FALSE(readOpenCvCamera((dir / "garbage.yaml").string(), missing, error));
}

}  // namespace
}  // namespace imagepro
