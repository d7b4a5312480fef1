#include "core/calibration/calibration_check.h"

#include <gtest/gtest.h>

#include <map>

#include "calibration_scenes.h"
#include "core/pipeline/engine.h"

namespace imagepro {
namespace {

using testing::calibrationViews;
using testing::realisticScene;
using testing::renderViews;

// The pose the pipeline reconstructs for the pattern's target, as the live check gets it.
Pose pipelinePose(const Settings& settings, const cv::Mat& image) {
  Engine engine(settings);
  Frame frame;
  frame.image = image;
  FrameResult result;
  engine.process(frame, result);
  EXPECT_EQ(result.status, Status::Ok);
  return result.pose.value_or(Pose{});
}

// On rendered patterns of known pose, the check's ideal positions are the truth's projected
// spots, and the spots found lie on them (no lens) or displaced by the lens's distortion.
TEST(CalibrationCheck, IdealPositionsFollowTheTruthAndFoundSpotsLieNearThem) {
  Settings settings;
  settings.pipeline.tracking.mode = TrackingMode::Off;
  for (const Distortion& lens : {Distortion{}, kThesisCameraDistortion}) {
    settings.camera().distortion = lens;
    settings.pipeline.reconstruction.distortion_correction = lens.k1 != 0.0;
    const auto views = calibrationViews();
    const auto images = renderViews(settings, lens, views, realisticScene());
    for (size_t v = 0; v < views.size(); ++v) {
      SCOPED_TRACE(::testing::Message() << "view " << v << " k1 " << lens.k1);
      std::vector<PatternSpot> pattern;
      patternSpots(settings.pattern, settings.target, pattern);
      std::vector<IdealSpot> truth;
      projectPatternSpots(settings.camera(), settings.pattern, pattern, views[v], truth);

      CalibrationCheckWorkspace ws;
      CalibrationCheck check;
      ASSERT_EQ(checkCalibrationView(settings, images[v], pipelinePose(settings, images[v]), ws, check), Status::Ok);
      ASSERT_GT(check.ideal.size(), 300u);
      ASSERT_EQ(check.ideal.size(), ws.ideal.size());
      // The reconstructed pose puts every ideal position within a pixel of the truth's.
      std::map<std::pair<int, int>, Eigen::Vector2d> truth_at;
      for (const IdealSpot& s : truth) truth_at[{s.column, s.row}] = s.ideal;
      double worst = 0.0;
      for (const IdealSpot& s : ws.ideal) {
        const auto it = truth_at.find({s.column, s.row});
        if (it == truth_at.end()) continue;  // at the image's edge for one pose and not the other
        worst = std::max(worst, (s.ideal - it->second).norm());
      }
      EXPECT_LT(worst, 1.0);
      // Most spots are matched, none ambiguous, each found spot where the lens puts its ideal position.
      EXPECT_GT(check.stats.matched, static_cast<int>(0.8 * check.ideal.size()));
      EXPECT_EQ(check.stats.ambiguous, 0);
      ASSERT_EQ(check.matches.size(), static_cast<size_t>(check.stats.matched));
      for (const auto& [i, o] : check.matches) {
        const Eigen::Vector2d expected = distortPixel(settings.camera(), check.ideal[i]);
        EXPECT_LT((check.seen[o] - expected).norm(), 1.0) << check.ideal[i].transpose();
      }
    }
  }
}

TEST(CalibrationCheck, NamedErrorsForFramesItCannotCheck) {
  Settings settings;
  CalibrationCheckWorkspace ws;
  CalibrationCheck check;
  EXPECT_EQ(checkCalibrationView(settings, cv::Mat(), Pose{}, ws, check), Status::EmptyFrame);
  EXPECT_EQ(checkCalibrationView(settings, cv::Mat(100, 100, CV_8UC1, cv::Scalar(128)), Pose{}, ws, check),
            Status::FrameSizeMismatch);
  // A flat frame has no threshold: the ideal positions are there, no spots.
  const cv::Mat flat(settings.camera().height, settings.camera().width, CV_8UC1, cv::Scalar(128));
  EXPECT_NE(checkCalibrationView(settings, flat, Pose{0, 0, 0, 0, 0, 800}, ws, check), Status::Ok);
  EXPECT_EQ(check.status, Status::ThresholdUndefined);
  EXPECT_FALSE(check.ideal.empty());
  EXPECT_TRUE(check.seen.empty());
  EXPECT_TRUE(check.matches.empty());
}

}  // namespace
}  // namespace imagepro
