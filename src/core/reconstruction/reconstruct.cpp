#include "core/reconstruction/reconstruct.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/ellipse/direct_fit.h"
#include "core/reconstruction/pose.h"
#include "core/reconstruction/refine.h"
#include "core/reconstruction/rim_fit.h"
#include "core/reconstruction/undistort.h"

namespace imagepro {

ReconstructionConfig reconstructionConfig(const Settings& settings) {
  ReconstructionConfig config{settings.camera(), settings.target, settings.pipeline.rethreshold,
                              settings.pipeline.reconstruction};
  ReconstructionOptions& o = config.options;
  if (o.distortion_correction && !o.exact_undistortion && !config.camera.distortion.isZero() &&
      taylorInverseErrorPx(config.camera) > kTaylorInverseLimitPx) {
    o.exact_undistortion = true;
    config.exact_for_wide_lens = true;
  }
  return config;
}

bool passesSelfCheck(const ReconstructionOptions& o, double spotErrorPx, double rimErrorPx) {
  if (spotErrorPx > o.max_spot_error_px || rimErrorPx > o.max_rim_error_px) return false;
  return spotErrorPx <= kJointErrorShare * o.max_spot_error_px || rimErrorPx <= kJointErrorShare * o.max_rim_error_px;
}

LensInverse lensInverse(const ReconstructionConfig& config) {
  const ReconstructionOptions& o = config.options;
  if (!o.distortion_correction || config.camera.distortion.isZero()) return LensInverse::None;
  if (config.exact_for_wide_lens) return LensInverse::ExactWideLens;
  return o.exact_undistortion ? LensInverse::Exact : LensInverse::Taylor;
}

namespace {

double rotationBetweenDeg(const Pose& a, const Pose& b) {
  const Eigen::AngleAxisd turn(rotationMatrix(a).transpose() * rotationMatrix(b));
  return std::abs(turn.angle()) * 180.0 / M_PI;
}

double normalsApartDeg(const Pose& a, const Pose& b) {
  const Eigen::Vector3d na = rotationMatrix(a).col(2), nb = rotationMatrix(b).col(2);
  return std::atan2(na.cross(nb).norm(), na.dot(nb)) * 180.0 / M_PI;
}

// Root-mean-square distance (first-order, Sampson) of the contour points from the rim's
// image under `pose`.
double rimReprojectionError(const CameraModel& cam, const TargetGeometry& target, const Pose& pose,
                            const std::vector<Eigen::Vector2d>& contour) {
  if (contour.empty()) return 0.0;
  const Eigen::Matrix3d C = imageConicOfTargetCircle(cam, pose, 0.0, 0.0, target.radius_mm);
  double sum = 0.0;
  for (const Eigen::Vector2d& p : contour) {
    const Eigen::Vector3d h(p.x(), p.y(), 1.0);
    const Eigen::Vector3d g = C * h;
    const double gradient = 2.0 * g.head<2>().norm();
    const double d = gradient > 0.0 ? h.dot(g) / gradient : 0.0;
    sum += d * d;
  }
  return std::sqrt(sum / static_cast<double>(contour.size()));
}

// The pose halfway between `a` and `b`: the midpoint of the shortest turn between their
// rotations and of their translations.
Pose midPose(const Pose& a, const Pose& b) {
  const Eigen::Quaterniond qa(rotationMatrix(a));
  Eigen::Quaterniond qb(rotationMatrix(b));
  if (qa.dot(qb) < 0.0) qb.coeffs() = -qb.coeffs();
  const Eigen::Quaterniond mid((qa.coeffs() + qb.coeffs()).normalized());
  return poseFromRt(mid.toRotationMatrix(), 0.5 * (translation(a) + translation(b)));
}

double sumOfSquares(const std::array<double, 2>& e) { return e[0] * e[0] + e[1] * e[1]; }

// The blur spread (ReconstructionResult::blur_spread_px) up to which the pose choice's
// margin is ambiguity_margin_px itself; beyond it the margin grows in proportion. A spot
// seen a few pixels across scatters about as much as it is blurred, motion blur most: on
// real-scene stills every pose kept wrong under a fixed margin of 0.07 px had a spread
// over 1.1 px (docs/reconstruction.md, The margin follows the blur).
constexpr double kSharpSpreadPx = 1.0;

// Of the rim's two circles (out.candidates, centre-nearest first), keeps the one that
// reprojects the spots better when the spots tell them apart, else the one nearer
// `expected`, else, when their normals lie within twice ambiguity_tolerance_deg, the pose halfway
// between them (within ambiguity_tolerance_deg of either), else reports AmbiguousPose. The spots
// are compared by the sum of their squared errors: the offset spot's radial error and the
// centre spot's both tell the circles apart. The margin the better one must win by grows
// with the rim's blur. A kept pose (or the better of two ambiguous ones) that does not fit
// the image is PoseInconsistent: a doubt between two poses of which neither fits is no
// doubt.
Status choosePose(const ReconstructionConfig& config, const Pose* expected, ReconstructionResult& out) {
  const ReconstructionOptions& o = config.options;
  PoseCandidates& c = out.candidates;
  auto swapCandidates = [&c] {
    std::swap(c.pose[0], c.pose[1]);
    std::swap(c.status[0], c.status[1]);
    std::swap(c.spot_errors_px[0], c.spot_errors_px[1]);
  };
  auto keepFirst = [&] {
    out.pose = c.pose[0];
    out.spot_error_px = std::max(c.spot_errors_px[0][0], c.spot_errors_px[0][1]);
  };
  // The thesis's pixel contour modes keep its rule (the circle whose centre projects
  // nearer the centre spot) and no check: their rim, from whole pixels, moves the pose's
  // spots by more than the checks' sub-pixel limits on a good frame (docs/reconstruction.md).
  if (o.contour_mode != ContourMode::SubPixel) {
    keepFirst();
    out.rim_error_px = rimReprojectionError(config.camera, config.target, out.pose, out.contour_ideal);
    return Status::Ok;
  }
  if (ok(c.status[1]) && sumOfSquares(c.spot_errors_px[1]) < sumOfSquares(c.spot_errors_px[0])) swapCandidates();
  keepFirst();
  bool ambiguous = false;
  if (ok(c.status[1])) {
    const double best = sumOfSquares(c.spot_errors_px[0]), other = sumOfSquares(c.spot_errors_px[1]);
    const double margin = o.ambiguity_margin_px * std::max(1.0, out.blur_spread_px / kSharpSpreadPx);
    const double needed = std::max(margin * margin, (o.ambiguity_ratio * o.ambiguity_ratio - 1.0) * best);
    const bool spotsDecide = other - best > needed;
    if (!spotsDecide && expected) {
      if (rotationBetweenDeg(c.pose[1], *expected) < rotationBetweenDeg(c.pose[0], *expected)) swapCandidates();
      keepFirst();
    } else if (!spotsDecide && normalsApartDeg(c.pose[0], c.pose[1]) <= 2.0 * o.ambiguity_tolerance_deg) {
      // Far and near head-on, the circles lie a few degrees either side of the line of
      // sight and their spots a tenth of a pixel apart: halfway is the best that is known.
      out.pose = midPose(c.pose[0], c.pose[1]);
      out.halfway_pose = true;
      const std::array<double, 2> e = spotReprojectionErrors(config.camera, config.target, out.pose,
                                                             out.centre_spot_ideal, out.offset_spot_ideal);
      out.spot_error_px = std::max(e[0], e[1]);
    } else {
      ambiguous = !spotsDecide;
    }
  }
  out.rim_error_px = rimReprojectionError(config.camera, config.target, out.pose, out.contour_ideal);
  if (!passesSelfCheck(o, out.spot_error_px, out.rim_error_px)) return Status::PoseInconsistent;
  return ambiguous ? Status::AmbiguousPose : Status::Ok;
}

}  // namespace

Status reconstructTarget(const ReconstructionConfig& config, const cv::Mat& grey,
                         const Ellipse& detected, int frameThreshold,
                         ReconstructionWorkspace& ws, ReconstructionResult& out, const Pose* expected,
                         const std::array<cv::Rect, 2>* detectedSpots) {
  out.steps = ReconstructionSteps{};
  out.contour.clear();
  out.blur_spread_px = 0.0;
  out.contour_ideal.clear();
  out.spots = SpotFeatures{};
  out.threshold = -1;
  out.candidates = PoseCandidates{};
  out.halfway_pose = false;
  out.spot_error_px = out.rim_error_px = 0.0;
  out.rim_seen = 0.0;
  auto fail = [&](Status& step, Status s) {
    step = s;
    out.status = s;
    return s;
  };
  if (grey.empty() || grey.type() != CV_8UC1) return fail(out.steps.crop, Status::EmptyFrame);
  // The camera model (principal point, focal lengths in pixels, distortion) belongs to one
  // image size: another size, as from a camera switched to another resolution, would give
  // a pose that looks valid and is wrong.
  if (grey.cols != config.camera.width || grey.rows != config.camera.height)
    return fail(out.steps.crop, Status::FrameSizeMismatch);

  const Status cropStatus = targetCrop(detected, config.options.crop_margin_px, grey.size(), out.crop);
  if (!ok(cropStatus)) return fail(out.steps.crop, cropStatus);
  out.steps.crop = Status::Ok;

  FeatureWorkspace& fw = ws.features;
  const Status thresholdStatus =
      rethresholdCrop(grey, out.crop, config.rethreshold, frameThreshold, fw, out.threshold,
                      config.options.contour_mode == ContourMode::SubPixel);
  if (!ok(thresholdStatus)) return fail(out.steps.threshold, thresholdStatus);
  out.steps.threshold = Status::Ok;

  const Status contourStatus =
      extractContour(config.options.contour_mode, grey, out.crop, detected, fw, out.contour, config.options.rim_edge_model);
  if (!ok(contourStatus)) return fail(out.steps.contour, contourStatus);
  out.steps.contour = Status::Ok;
  out.blur_spread_px = fw.rim_blur_spread_px;

  const Status spotStatus = extractSpots(grey, out.crop, detected, config.target,
                                         config.options.weighted_spot_centres, fw, out.spots, detectedSpots);
  if (!ok(spotStatus)) return fail(out.steps.spots, spotStatus);
  out.steps.spots = Status::Ok;

  // Distortion correction of every feature point (thesis 4.5).
  out.contour_ideal.assign(out.contour.begin(), out.contour.end());
  std::array<Eigen::Vector2d, 2> spotsIdeal{out.spots.centre_spot, out.spots.offset_spot};
  if (config.options.distortion_correction) {
    undistortPoints(config.camera, config.options.exact_undistortion, out.contour_ideal);
    undistortPoints(config.camera, config.options.exact_undistortion, spotsIdeal);
  }
  out.centre_spot_ideal = spotsIdeal[0];
  out.offset_spot_ideal = spotsIdeal[1];

  // The direct fit (thesis 2.6.2) of the points on the rim, those off it (an occluder's
  // edge, a crossing under glare) left out of the contour (rim_fit.h); the detection stage
  // has already judged the rim.
  // The thesis's pixel contour modes keep its plain fit, as they keep its pose choice.
  const bool robust = config.options.robust_rim_fit && config.options.contour_mode == ContourMode::SubPixel;
  RimFit rim;
  const Status fitStatus = fitRim(out.contour_ideal, out.contour, robust, ws.rim, rim);
  if (!ok(fitStatus)) return fail(out.steps.fit, fitStatus);
  out.steps.fit = Status::Ok;
  out.conic = rim.fit.conic;
  out.ellipse = rim.fit.ellipse;
  out.rim_seen = rim.seen;

  Status poseStatus = poseFromEllipse(config.camera, config.target, out.conic, out.centre_spot_ideal,
                                      out.offset_spot_ideal, out.pose, config.options.centre_spot_normal,
                                      &out.candidates);
  if (ok(poseStatus)) poseStatus = choosePose(config, expected, out);
  // A halfway pose is not refined: the refinement would choose between the circles on the
  // same spots that could not.
  if (ok(poseStatus) && config.options.refine_pose && !out.halfway_pose)
    out.steps.refine = refineReconstructedPose(config, out);
  if (!ok(poseStatus)) return fail(out.steps.pose, poseStatus);
  out.steps.pose = Status::Ok;
  out.status = Status::Ok;
  return Status::Ok;
}

Status reconstructTarget(const Settings& settings, const cv::Mat& grey, const Ellipse& detected,
                         int frameThreshold, ReconstructionWorkspace& ws,
                         ReconstructionResult& out) {
  return reconstructTarget(reconstructionConfig(settings), grey, detected, frameThreshold, ws, out);
}

}  // namespace imagepro
