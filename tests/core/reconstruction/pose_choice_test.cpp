// The choice between the rim's two circles and the self-check of the pose
// (reconstruct.h, ReconstructionOptions): a far, blurred, noisy target is either solved
// right or called AmbiguousPose with the right pose among its candidates, never a flipped
// ok; a tracked stream's last pose decides; a moved spot is refused as PoseInconsistent.
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <random>

#include "core/reconstruction/reconstruct.h"
#include "core/source/virtual_renderer.h"
#include "test_scenes.h"
#include "support/plain_scene.h"

namespace imagepro {
namespace {

using testing::makePose;
using testing::rotationErrorDeg;
using testing::seenRimEllipse;

struct PoseChoiceTest : ::testing::Test {
  Settings settings = test::plainSettings();
  ReconstructionWorkspace ws;
  ReconstructionResult result;
  cv::Mat image;

  void SetUp() override {
    settings.virtual_scene.blur_sigma_px = 1.2;
    settings.virtual_scene.noise_sigma = 4.0;
  }
  Status run(const Pose& pose, std::uint64_t seed, const Pose* expected = nullptr) {
    renderTarget(settings.camera(), settings.target, settings.virtual_scene, pose, image, seed);
    return reconstructTarget(reconstructionConfig(settings), image, seenRimEllipse(settings.camera(), settings.target, pose),
                             128, ws, result, expected);
  }
  // Far targets (2.2-2.4 m, rim radius about 17 px) tilted 15-50 deg: where the spots' few
  // pixels tell the two circles apart least surely.
  std::vector<Pose> farPoses() {
    std::vector<Pose> poses;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> z(2200, 2400), tilt(15, 50), rz(-180, 180), u(150, 490), v(120, 360);
    for (int i = 0; i < 40; ++i) poses.push_back(makePose(settings.camera(), z(rng), tilt(rng), rz(rng), rz(rng), u(rng), v(rng)));
    return poses;
  }
};

TEST_F(PoseChoiceTest, FarTargetsAreSolvedRightOrCalledAmbiguousNeverFlipped) {
  int solved = 0, ambiguous = 0;
  std::uint64_t seed = 0;
  for (const Pose& truth : farPoses()) {
    const Status s = run(truth, ++seed);
    if (s == Status::Ok) {
      ++solved;
      EXPECT_LT(rotationErrorDeg(truth, result.pose), 5.0) << "an ok pose must not be flipped";
    } else if (s == Status::AmbiguousPose) {
      ++ambiguous;
      const double nearest = std::min(rotationErrorDeg(truth, result.candidates.pose[0]),
                                      rotationErrorDeg(truth, result.candidates.pose[1]));
      EXPECT_LT(nearest, 5.0) << "one of the candidates is the target's pose";
    }
  }
  std::printf("far targets: %d solved, %d ambiguous of 40\n", solved, ambiguous);
  EXPECT_GE(solved, 36);  // 40 measured (38 before halfway poses)
}

// Under wide blur the spots' centroids scatter more, and the margin the better circle must
// win by grows with the rim's measured blur spread: a frame whose spots would decide under
// the sharp image's margin is left undecided when its rim is blurred (AmbiguousPose, or the
// pose halfway between two close candidates). (At 2 px of blur one
// of these 60 frames came out flipped: docs/reconstruction.md, The margin follows the blur.)
TEST_F(PoseChoiceTest, TheMarginGrowsWithTheBlur) {
  settings.virtual_scene.blur_sigma_px = 1.8;  // the real-scene stills reach 1.6
  const ReconstructionOptions& o = settings.pipeline.reconstruction;
  // Far targets within 12 deg of head-on: the two circles put the spots a tenth of a pixel
  // or so apart, where the margin decides.
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> z(1800, 2400), tilt(5, 12), rz(-180, 180), u(150, 490), v(120, 360);
  int heldBack = 0, solved = 0;
  std::uint64_t seed = 200;
  for (int i = 0; i < 60; ++i) {
    const Pose truth = makePose(settings.camera(), z(rng), tilt(rng), rz(rng), rz(rng), u(rng), v(rng));
    const Status s = run(truth, ++seed);
    const PoseCandidates& c = result.candidates;
    if ((s != Status::Ok && s != Status::AmbiguousPose) || !ok(c.status[1])) continue;
    EXPECT_GT(result.blur_spread_px, 1.3);  // the measure reads wide blur low (RimEdgeTest.MeasuresTheBlur)
    const auto ss = [](const std::array<double, 2>& e) { return e[0] * e[0] + e[1] * e[1]; };
    const double best = std::min(ss(c.spot_errors_px[0]), ss(c.spot_errors_px[1]));
    const double gap = std::max(ss(c.spot_errors_px[0]), ss(c.spot_errors_px[1])) - best;
    const double byRatio = (o.ambiguity_ratio * o.ambiguity_ratio - 1.0) * best;
    const double sharpMargin = o.ambiguity_margin_px, blurMargin = o.ambiguity_margin_px * result.blur_spread_px;
    if (gap > std::max(sharpMargin * sharpMargin, byRatio) && gap <= std::max(blurMargin * blurMargin, byRatio)) {
      EXPECT_TRUE(s == Status::AmbiguousPose || result.halfway_pose) << "a gap only the sharp margin would pass";
      ++heldBack;
    }
    if (s == Status::Ok) {
      ++solved;
      EXPECT_LT(rotationErrorDeg(truth, result.pose), 5.0) << "an ok pose must not be flipped";
    }
  }
  std::printf("blur 1.8 px: %d solved, %d held back by the wider margin\n", solved, heldBack);
  EXPECT_GE(heldBack, 2);  // 4 measured
  EXPECT_GE(solved, 40);   // 52 measured
}

// Nothing in the spots to go by (every pair of distinct circles called ambiguous): the
// last pose of a tracked stream, a few degrees off, picks the right one every time.
TEST_F(PoseChoiceTest, TheLastPoseDecidesWhenTheSpotsCannot) {
  settings.pipeline.reconstruction.ambiguity_ratio = 1e6;
  std::uint64_t seed = 100;
  int decided = 0;
  for (const Pose& truth : farPoses()) {
    if (run(truth, ++seed) != Status::AmbiguousPose) continue;
    Pose last = truth;
    last.rx_deg += 3.0;
    last.rz_deg -= 2.0;
    ASSERT_EQ(run(truth, seed, &last), Status::Ok);
    EXPECT_LT(rotationErrorDeg(truth, result.pose), 5.0);
    ++decided;
  }
  EXPECT_GE(decided, 30);
}

// The two candidates' normals a degree apart: the pose halfway between them is as good as
// either, no doubt is reported (a target seen head-on is not ambiguous).
TEST_F(PoseChoiceTest, NearlyEqualCandidatesAreNotAmbiguous) {
  settings.pipeline.reconstruction.ambiguity_ratio = 1e6;
  settings.virtual_scene.blur_sigma_px = 0.0;
  settings.virtual_scene.noise_sigma = 0.0;
  const Pose truth = makePose(settings.camera(), 600, 0.5, 20, 30, 320, 240);
  ASSERT_EQ(run(truth, 1), Status::Ok);
  EXPECT_LT(rotationErrorDeg(truth, result.pose), 1.0);
}

// Far targets seen 2.5-4.5 deg off their line of sight: the rim's two circles lie 5-9 deg
// apart, either side of it. When the spots cannot tell them apart (here: never), the pose
// halfway between them is ok, within ambiguity_tolerance_deg of either, and here of the truth; with
// ambiguity_tolerance_deg 0 the same frames are AmbiguousPose.
TEST_F(PoseChoiceTest, CloseCandidatesTheSpotsCannotTellApartGiveThePoseHalfway) {
  ReconstructionOptions& o = settings.pipeline.reconstruction;
  o.ambiguity_ratio = 1e6;
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> z(1800, 2400), tilt(2.5, 4.5), rz(-180, 180);
  int halfway = 0;
  std::uint64_t seed = 300;
  for (int i = 0; i < 12; ++i) {
    const Pose truth = makePose(settings.camera(), z(rng), tilt(rng), rz(rng), rz(rng), 320, 240);
    o.ambiguity_tolerance_deg = 5.0;
    ASSERT_EQ(run(truth, ++seed), Status::Ok) << "frame " << i;
    const PoseCandidates& c = result.candidates;
    ASSERT_TRUE(ok(c.status[1]));
    const double apart = rotationErrorDeg(c.pose[0], c.pose[1]);
    if (apart <= 1.0) continue;  // noise can put the circles nearly together
    ++halfway;
    EXPECT_TRUE(result.halfway_pose);
    EXPECT_NEAR(rotationErrorDeg(result.pose, c.pose[0]), apart / 2, 1e-6);
    EXPECT_NEAR(rotationErrorDeg(result.pose, c.pose[1]), apart / 2, 1e-6);
    EXPECT_LT(rotationErrorDeg(truth, result.pose), o.ambiguity_tolerance_deg);
    EXPECT_LT(result.spot_error_px, o.max_spot_error_px);
    o.ambiguity_tolerance_deg = 0.0;
    EXPECT_EQ(run(truth, seed), Status::AmbiguousPose) << "frame " << i;
    EXPECT_FALSE(result.halfway_pose);
  }
  EXPECT_GE(halfway, 10);
}

// A centre spot moved on the disk by a fifth of its radius: the pose it gives cannot put
// the spots and the rim where they are, and the self-check says so.
TEST_F(PoseChoiceTest, AMovedSpotIsRefusedAsInconsistent) {
  settings.virtual_scene.blur_sigma_px = 0.0;
  settings.virtual_scene.noise_sigma = 0.0;
  const Pose truth = makePose(settings.camera(), 700, 30, 40, 60, 320, 240);
  ASSERT_EQ(run(truth, 1), Status::Ok);
  EXPECT_LT(result.spot_error_px, 0.2);
  EXPECT_LT(result.rim_error_px, 0.2);
  const Ellipse rim = seenRimEllipse(settings.camera(), settings.target, truth);
  const cv::Point2d centre = {result.spots.centre_spot.x(), result.spots.centre_spot.y()};
  const double spot_px = settings.target.spot_radius_mm / settings.target.radius_mm * rim.b;
  // Paint the spot over with the disk's white and draw it again 0.2 R further along -X.
  cv::circle(image, centre, static_cast<int>(spot_px + 3), cv::Scalar(settings.virtual_scene.white_level), cv::FILLED);
  const cv::Point2d offset = {result.spots.offset_spot.x() - centre.x, result.spots.offset_spot.y() - centre.y};
  const cv::Point2d moved = centre - offset * (0.2 * settings.target.radius_mm / settings.target.spot_offset_mm);
  cv::circle(image, moved, static_cast<int>(spot_px), cv::Scalar(settings.virtual_scene.black_level), cv::FILLED,
             cv::LINE_AA);
  const Status s = reconstructTarget(reconstructionConfig(settings), image, rim, 128, ws, result);
  EXPECT_EQ(s, Status::PoseInconsistent) << result.spot_error_px << " px spots";
  EXPECT_GT(result.spot_error_px, settings.pipeline.reconstruction.max_spot_error_px);
}

// Either error alone may be large on a right pose (a rim combed by interlacing: up to 0.97
// px with spots within 0.33 px on PendulumStudy.InterlacedFrames' small swing); both beyond
// 0.5 of their limits are a pose that fits neither (on the webcam stills, wrong poses of
// 87-104 deg had both at 0.56-0.94 px, correct ones never both above 0.38 px).
TEST(SelfCheck, BothErrorsHighTogetherFailWhereEitherAloneDoesNot) {
  ReconstructionOptions o;  // 1 px each
  EXPECT_TRUE(passesSelfCheck(o, 0.1, 0.1));
  EXPECT_TRUE(passesSelfCheck(o, 0.3, 0.95));   // a combed rim
  EXPECT_TRUE(passesSelfCheck(o, 0.9, 0.2));    // a spot under glare
  EXPECT_FALSE(passesSelfCheck(o, 0.8, 0.85));  // a bent rim and spots that disagree
  EXPECT_FALSE(passesSelfCheck(o, 0.75, 0.56));
  EXPECT_TRUE(passesSelfCheck(o, 0.75, 0.4));
  EXPECT_FALSE(passesSelfCheck(o, 1.1, 0.0));
  EXPECT_FALSE(passesSelfCheck(o, 0.0, 1.1));
  // The joint limit follows the limits.
  o.max_spot_error_px = o.max_rim_error_px = 2.0;
  EXPECT_TRUE(passesSelfCheck(o, 0.8, 0.85));
  EXPECT_FALSE(passesSelfCheck(o, 1.3, 1.3));
}

}  // namespace
}  // namespace imagepro
