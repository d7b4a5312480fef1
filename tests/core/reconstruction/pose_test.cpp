#include "core/reconstruction/pose.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "status_print.h"
#include "test_scenes.h"

namespace imagepro {
namespace {

using testing::makePose;
constexpr double kDeg = M_PI / 180.0;

Conic conicFromMatrix(const Eigen::Matrix3d& M) {
  Conic c;
  c << M(0, 0), 2 * M(0, 1), M(1, 1), 2 * M(0, 2), 2 * M(1, 2), M(2, 2);
  return c / c.norm();
}

Eigen::Vector2d conicCentre(const Eigen::Matrix3d& M) {
  Eigen::Vector2d c;
  EXPECT_TRUE(conicMatrixCentre(M, c));
  return c;
}

// The exact images of the rim and of both spots' centroids at a pose.
struct ExactImage {
  Conic rim;
  Eigen::Vector2d centreSpot, offsetSpot;
};
ExactImage exactImage(const CameraModel& cam, const TargetGeometry& t, const Pose& pose) {
  ExactImage im;
  im.rim = conicFromMatrix(imageConicOfTargetCircle(cam, pose, 0, 0, t.radius_mm));
  im.centreSpot = conicCentre(imageConicOfTargetCircle(cam, pose, 0, 0, t.spot_radius_mm));
  im.offsetSpot =
      conicCentre(imageConicOfTargetCircle(cam, pose, t.spot_offset_mm, 0, t.spot_radius_mm));
  return im;
}

// Projected rim points of the target at a pose.
std::vector<Eigen::Vector2d> rimPoints(const CameraModel& cam, const TargetGeometry& t,
                                       const Pose& pose, int n) {
  const Eigen::Matrix3d R = rotationMatrix(pose);
  const Eigen::Vector3d T = translation(pose);
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    pts.push_back(projectIdeal(cam, R * Eigen::Vector3d(t.radius_mm * std::cos(a),
                                                        t.radius_mm * std::sin(a), 0) + T));
  }
  return pts;
}

// Algebraic conic through points (null vector of the design matrix, coordinates centred and
// scaled for conditioning): exact for exact points.
Conic fitConic(const std::vector<Eigen::Vector2d>& pts) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : pts) mean += p;
  mean /= pts.size();
  double s = 0;
  for (const auto& p : pts) s += (p - mean).norm();
  s = pts.size() / s;
  Eigen::MatrixXd D(pts.size(), 6);
  for (size_t i = 0; i < pts.size(); ++i) {
    const Eigen::Vector2d q = (pts[i] - mean) * s;
    D.row(i) << q.x() * q.x(), q.x() * q.y(), q.y() * q.y(), q.x(), q.y(), 1;
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(D, Eigen::ComputeFullV);
  const Eigen::VectorXd v = svd.matrixV().col(5);
  Eigen::Matrix3d Mn;
  Mn << v[0], v[1] / 2, v[3] / 2, v[1] / 2, v[2], v[4] / 2, v[3] / 2, v[4] / 2, v[5];
  Eigen::Matrix3d N;  // normalised coordinates q = N x
  N << s, 0, -s * mean.x(), 0, s, -s * mean.y(), 0, 0, 1;
  return conicFromMatrix(N.transpose() * Mn * N);
}

double rotationError(const Pose& a, const Pose& b) {
  return rotationAngleBetweenDeg(rotationMatrix(a), rotationMatrix(b));
}
double positionError(const Pose& a, const Pose& b) {
  return (translation(a) - translation(b)).norm();
}

struct PoseTest : ::testing::Test {
  CameraModel cam;
  TargetGeometry target;
  std::mt19937 rng{11};
  Pose randomPose() {
    std::uniform_real_distribution<double> z(400, 1200), tilt(0, 60), angle(-180, 180),
        u(150, 490), v(130, 350);
    return makePose(cam, z(rng), tilt(rng), angle(rng), angle(rng), u(rng), v(rng));
  }
};

TEST_F(PoseTest, RecoversRandomPosesFromTheExactConic) {
  for (int i = 0; i < 2000; ++i) {
    const Pose truth = randomPose();
    const ExactImage im = exactImage(cam, target, truth);
    Pose est;
    ASSERT_EQ(poseFromEllipse(cam, target, im.rim, im.centreSpot, im.offsetSpot, est), Status::Ok);
    EXPECT_LT(rotationError(truth, est), 1e-6) << i;
    EXPECT_LT(positionError(truth, est), 1e-7 * truth.tz_mm) << i;
  }
}

TEST_F(PoseTest, FrontoParallelAndRzNearHalfTurn) {
  for (double tilt : {0.0, 1e-4, 0.01, 0.5}) {
    for (double rz : {0.0, 90.0, 179.999, 180.0, -179.999, -90.0}) {
      for (double u : {cam.u0(), 100.0, 560.0}) {
        const Pose truth = makePose(cam, 800, tilt, 30, rz, u, cam.v0() + 40);
        const ExactImage im = exactImage(cam, target, truth);
        Pose est;
        ASSERT_EQ(poseFromEllipse(cam, target, im.rim, im.centreSpot, im.offsetSpot, est),
                  Status::Ok);
        EXPECT_LT(rotationError(truth, est), 1e-5) << tilt << " " << rz << " " << u;
        EXPECT_LT(positionError(truth, est), 1e-6 * 800) << tilt << " " << rz << " " << u;
      }
    }
  }
}

TEST_F(PoseTest, IdentityPoseGivesZeroAngles) {
  Pose truth;  // facing the camera, 1000 mm ahead
  const ExactImage im = exactImage(cam, target, truth);
  Pose est;
  ASSERT_EQ(poseFromEllipse(cam, target, im.rim, im.centreSpot, im.offsetSpot, est), Status::Ok);
  EXPECT_NEAR(est.rx_deg, 0, 1e-9);
  EXPECT_NEAR(est.ry_deg, 0, 1e-9);
  EXPECT_NEAR(est.rz_deg, 0, 1e-9);
  EXPECT_NEAR(est.tz_mm, 1000, 1e-9);
}

TEST_F(PoseTest, RecoversPosesFromAConicFittedToProjectedRimPoints) {
  for (int i = 0; i < 300; ++i) {
    const Pose truth = randomPose();
    const ExactImage im = exactImage(cam, target, truth);
    const Conic fitted = fitConic(rimPoints(cam, target, truth, 12 + i % 50));
    Pose est;
    ASSERT_EQ(poseFromEllipse(cam, target, fitted, im.centreSpot, im.offsetSpot, est), Status::Ok);
    EXPECT_LT(rotationError(truth, est), 1e-5) << i;
    EXPECT_LT(positionError(truth, est), 1e-6 * truth.tz_mm) << i;
  }
}

TEST_F(PoseTest, BothCandidatesAreCirclesOfTheRadiusWithTheSameImage) {
  for (int i = 0; i < 200; ++i) {
    const Pose truth = randomPose();
    const Conic rim = exactImage(cam, target, truth).rim;
    std::array<CircleCandidate, 2> cands;
    ASSERT_EQ(circleCandidates(cam, rim, target.radius_mm, cands), Status::Ok);
    for (const CircleCandidate& c : cands) {
      EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
      EXPECT_GT(c.normal.dot(c.centre), 0.0);  // +Z away from the camera
      // Points of that circle project onto the conic.
      const Eigen::Vector3d a = c.normal.unitOrthogonal(), b = c.normal.cross(a);
      for (int k = 0; k < 8; ++k) {
        const double t = k * M_PI / 4;
        const Eigen::Vector3d P = c.centre + target.radius_mm * (std::cos(t) * a + std::sin(t) * b);
        const Eigen::Vector2d p = projectIdeal(cam, P);
        const Eigen::Vector3d x(p.x(), p.y(), 1);
        // The conic's value relative to its gradient: a distance in pixels.
        Eigen::Matrix3d M;
        M << rim[0], rim[1] / 2, rim[3] / 2, rim[1] / 2, rim[2], rim[4] / 2, rim[3] / 2, rim[4] / 2,
            rim[5];
        const double value = x.dot(M * x);
        const double grad = 2 * (M.topRows<2>() * x).norm();
        EXPECT_LT(std::abs(value) / grad, 1e-7);
      }
    }
    // One of them is the truth.
    const Eigen::Vector3d n = rotationMatrix(truth).col(2);
    const double best = std::min(std::acos(std::min(1.0, cands[0].normal.dot(n))),
                                 std::acos(std::min(1.0, cands[1].normal.dot(n))));
    EXPECT_LT(best, 1e-6);
  }
}

TEST_F(PoseTest, PolarLineNormalAgreesOnExactData) {
  for (int i = 0; i < 500; ++i) {
    const Pose truth = randomPose();
    const ExactImage im = exactImage(cam, target, truth);
    // The polar line needs the image of the centre itself, not a spot centroid.
    const Eigen::Vector2d centreImage = projectIdeal(cam, translation(truth));
    Eigen::Vector3d n;
    ASSERT_EQ(normalFromPolarLine(cam, im.rim, centreImage, n), Status::Ok);
    EXPECT_LT(std::acos(std::min(1.0, n.dot(rotationMatrix(truth).col(2)))), 1e-7);
  }
}

// The eigen-structure against the polar line, with the same noisy rim points. The polar line
// is exact for the image of the disk's centre, not for the spot's centroid (perspective
// moves it): it is given that image itself plus the centroid's noise, so what differs is
// the sensitivity to noise alone. Near fronto-parallel the eigen-structure is
// ill-conditioned too and the gap narrows (docs/accuracy.md: about 4x on the median, 1.3x
// on the 95th percentile there); beyond 15 deg it is an order of magnitude.
TEST_F(PoseTest, EigenNormalIsMoreRobustToNoiseThanThePolarLine) {
  std::normal_distribution<double> noise(0.0, 0.3);
  std::vector<double> eigenNear, polarNear, eigenFar, polarFar;
  for (int i = 0; i < 600; ++i) {
    const Pose truth = randomPose();
    std::vector<Eigen::Vector2d> pts = rimPoints(cam, target, truth, 200);
    for (auto& p : pts) p += Eigen::Vector2d(noise(rng), noise(rng));
    const Conic rim = fitConic(pts);
    const ExactImage im = exactImage(cam, target, truth);
    const Eigen::Vector2d spotNoise = Eigen::Vector2d(noise(rng), noise(rng)) * 0.2;
    Pose est;
    ASSERT_EQ(poseFromEllipse(cam, target, rim, im.centreSpot + spotNoise, im.offsetSpot, est, false), Status::Ok);
    Eigen::Vector3d n;
    ASSERT_EQ(normalFromPolarLine(cam, rim, projectIdeal(cam, translation(truth)) + spotNoise, n), Status::Ok);
    const Eigen::Vector3d truthN = rotationMatrix(truth).col(2);
    const bool near = testing::viewAngleDeg(truth) < 15.0;
    (near ? eigenNear : eigenFar).push_back(std::acos(std::min(1.0, rotationMatrix(est).col(2).dot(truthN))) / kDeg);
    (near ? polarNear : polarFar).push_back(std::acos(std::min(1.0, n.dot(truthN))) / kDeg);
  }
  using testing::quantile;
  std::printf("normal error, eigen / polar line: 0-15 deg (%zu poses) median %.3f / %.3f, p95 %.3f / %.3f; "
              "15-60 deg (%zu poses) median %.3f / %.3f, p95 %.3f / %.3f\n",
              eigenNear.size(), quantile(eigenNear, 0.5), quantile(polarNear, 0.5), quantile(eigenNear, 0.95),
              quantile(polarNear, 0.95), eigenFar.size(), quantile(eigenFar, 0.5), quantile(polarFar, 0.5),
              quantile(eigenFar, 0.95), quantile(polarFar, 0.95));
  ASSERT_GT(eigenNear.size(), 20u);
  // Beyond 15 deg: about an order of magnitude (measured 10x on both).
  EXPECT_GT(quantile(polarFar, 0.5), 7.0 * quantile(eigenFar, 0.5));
  EXPECT_GT(quantile(polarFar, 0.95), 7.0 * quantile(eigenFar, 0.95));
  // Near fronto-parallel: still worse, by much less (measured 2.8x and 2.7x here).
  EXPECT_GT(quantile(polarNear, 0.5), 2.0 * quantile(eigenNear, 0.5));
  EXPECT_GT(quantile(polarNear, 0.95), 1.2 * quantile(eigenNear, 0.95));
}

TEST_F(PoseTest, SingularConics) {
  Pose est;
  const Eigen::Vector2d c(320, 240), o(340, 240);
  EXPECT_EQ(poseFromEllipse(cam, target, Conic::Zero(), c, o, est), Status::SingularConic);
  Conic nan = Conic::Zero();
  nan[0] = std::nan("");
  EXPECT_EQ(poseFromEllipse(cam, target, nan, c, o, est), Status::SingularConic);
  // An ellipse with no real points: u^2 + v^2 + 1 = 0 (about the principal point).
  Eigen::Matrix3d imaginary = Eigen::Matrix3d::Identity();
  imaginary(0, 2) = imaginary(2, 0) = -cam.u0();
  imaginary(1, 2) = imaginary(2, 1) = -cam.v0();
  imaginary(2, 2) = cam.u0() * cam.u0() + cam.v0() * cam.v0() + 1.0;
  EXPECT_EQ(poseFromEllipse(cam, target, conicFromMatrix(imaginary), c, o, est),
            Status::SingularConic);
  // A single point (degenerate cone): (u - 320)^2 + (v - 240)^2 = 0.
  Eigen::Matrix3d point = imaginary;
  point(0, 2) = point(2, 0) = -320;
  point(1, 2) = point(2, 1) = -240;
  point(2, 2) = 320 * 320 + 240 * 240;
  EXPECT_EQ(poseFromEllipse(cam, target, conicFromMatrix(point), c, o, est), Status::SingularConic);
  // Hyperbola and parabola: not an ellipse.
  Conic hyperbola;
  hyperbola << 1, 0, -1, -2 * 320, 2 * 240, 320.0 * 320 - 240.0 * 240 - 100;
  EXPECT_EQ(poseFromEllipse(cam, target, hyperbola / hyperbola.norm(), c, o, est),
            Status::NotAnEllipse);
  Conic parabola;
  parabola << 1, 0, 0, -640, -1, 320.0 * 320;
  EXPECT_EQ(poseFromEllipse(cam, target, parabola / parabola.norm(), c, o, est),
            Status::NotAnEllipse);
}

TEST_F(PoseTest, CentreSpotOutsideTheEllipse) {
  const Pose truth = makePose(cam, 800, 30, 0, 0, 320, 240);
  const ExactImage im = exactImage(cam, target, truth);
  Pose est;
  EXPECT_EQ(poseFromEllipse(cam, target, im.rim, Eigen::Vector2d(600, 50), im.offsetSpot, est),
            Status::CentreSpotOutsideEllipse);
  // The ellipse's own centre is inside even when the conic's overall sign is flipped.
  EXPECT_EQ(poseFromEllipse(cam, target, -im.rim, im.centreSpot, im.offsetSpot, est), Status::Ok);
  EXPECT_LT(rotationError(truth, est), 1e-6);
}

TEST_F(PoseTest, TargetSeenEdgeOnFacesAway) {
  // Seen at 89 degrees from its normal, the rim is a sliver that does not fix the plane.
  const Pose truth = makePose(cam, 800, 89.5, 0, 0, cam.u0(), cam.v0());
  const ExactImage im = exactImage(cam, target, truth);
  Pose est;
  EXPECT_EQ(poseFromEllipse(cam, target, im.rim, im.centreSpot, im.offsetSpot, est),
            Status::NormalFacingAway);
}

TEST_F(PoseTest, OffsetSpotBeyondThePlanesHorizonFacesAway) {
  // Tilted 60 degrees about the camera's X axis: the plane's vanishing line is a horizontal
  // image line; a pixel beyond it sees the plane only behind the camera.
  const Pose truth = makePose(cam, 800, 60, 0, 0, cam.u0(), cam.v0());
  const ExactImage im = exactImage(cam, target, truth);
  const Eigen::Vector3d n = rotationMatrix(truth).col(2);
  // Vanishing line: n . (K^-1 x) = 0 -> v on the u0 column.
  const double vHorizon = cam.v0() - cam.fv() * n.z() / n.y();
  const Eigen::Vector2d beyond(cam.u0(), vHorizon + (vHorizon < cam.v0() ? -50.0 : 50.0));
  Pose est;
  EXPECT_EQ(poseFromEllipse(cam, target, im.rim, im.centreSpot, beyond, est),
            Status::NormalFacingAway);
}

TEST_F(PoseTest, OffsetSpotAtTheCentreIsNotASpot) {
  const Pose truth = makePose(cam, 800, 20, 40, 10, 300, 200);
  const ExactImage im = exactImage(cam, target, truth);
  Pose est;
  EXPECT_EQ(poseFromEllipse(cam, target, im.rim, im.centreSpot, im.centreSpot, est),
            Status::SpotsNotFound);
  // A rim point is twice as far as the offset spot should be.
  const Eigen::Vector2d rimPoint = rimPoints(cam, target, truth, 4)[1];
  EXPECT_EQ(poseFromEllipse(cam, target, im.rim, im.centreSpot, rimPoint, est),
            Status::SpotsNotFound);
  const Eigen::Vector2d nanPoint(std::nan(""), 1);
  EXPECT_EQ(poseFromEllipse(cam, target, im.rim, nanPoint, im.offsetSpot, est),
            Status::SpotsNotFound);
}


// Head-on the rim's ellipse is nearly a circle and its normal goes with the square root of
// the axes' difference; the centre spot's polar line is linear there. Weighed together,
// the normal is much better head-on and no worse where the rim is well conditioned. Rim
// points scatter by 0.3 px as in the test above; the centre spot's image by 0.01 px, the
// centroid error measured on grey frames (0.009-0.02 px, docs/reconstruction.md).
TEST_F(PoseTest, WeighingTheCentreSpotMendsTheNormalHeadOnAndCostsNothingBeyond) {
  std::normal_distribution<double> rimNoise(0.0, 0.3), spotNoise(0.0, 0.01);
  std::uniform_real_distribution<double> angle(-180, 180), u(150, 490), v(130, 350), z(400, 1200);
  for (const auto& [tiltLo, tiltHi] : {std::pair{0.0, 3.0}, std::pair{20.0, 60.0}}) {
    std::uniform_real_distribution<double> tilt(tiltLo, tiltHi);
    std::vector<double> rimOnly, weighed;
    for (int i = 0; i < 300; ++i) {
      const Pose truth = makePose(cam, z(rng), tilt(rng), angle(rng), angle(rng), u(rng), v(rng));
      std::vector<Eigen::Vector2d> pts = rimPoints(cam, target, truth, 200);
      for (auto& p : pts) p += Eigen::Vector2d(rimNoise(rng), rimNoise(rng));
      const Conic rim = fitConic(pts);
      const ExactImage im = exactImage(cam, target, truth);
      const Eigen::Vector2d centreSpot = im.centreSpot + Eigen::Vector2d(spotNoise(rng), spotNoise(rng));
      const Eigen::Vector3d truthN = rotationMatrix(truth).col(2);
      for (const bool weigh : {false, true}) {
        Pose est;
        ASSERT_EQ(poseFromEllipse(cam, target, rim, centreSpot, im.offsetSpot, est, weigh), Status::Ok);
        (weigh ? weighed : rimOnly)
            .push_back(std::acos(std::min(1.0, rotationMatrix(est).col(2).dot(truthN))) / kDeg);
      }
    }
    using testing::quantile;
    std::printf("tilt %.0f-%.0f deg: normal error rim only / weighed: median %.3f / %.3f, p95 %.3f / %.3f\n", tiltLo,
                tiltHi, quantile(rimOnly, 0.5), quantile(weighed, 0.5), quantile(rimOnly, 0.95),
                quantile(weighed, 0.95));
    // Measured 0.91x on the median and 0.78x on the 95th percentile head-on, 0.98x on both
    // beyond 20 deg. (The weights take the spot's error as 1.3 times the rim axes', as suits
    // grey frames; here the rim's axes scatter by about 0.03 px, three times the spot's, so
    // the gain is smaller than the frames' halving of the 95th percentile.)
    if (tiltHi <= 3.0) {
      EXPECT_LT(quantile(weighed, 0.5), 0.95 * quantile(rimOnly, 0.5));
      EXPECT_LT(quantile(weighed, 0.95), 0.85 * quantile(rimOnly, 0.95));
    } else {
      EXPECT_LT(quantile(weighed, 0.5), 1.05 * quantile(rimOnly, 0.5));
      EXPECT_LT(quantile(weighed, 0.95), 1.05 * quantile(rimOnly, 0.95));
    }
  }
}

}  // namespace
}  // namespace imagepro
