#include "core/reconstruction/reconstruct.h"

#include "core/ellipse/direct_fit.h"
#include "core/reconstruction/pose.h"
#include "core/reconstruction/undistort.h"

namespace imagepro {

ReconstructionConfig reconstructionConfig(const Settings& settings) {
  return {settings.camera, settings.target, settings.pipeline.rethreshold,
          settings.pipeline.reconstruction};
}

Status reconstructTarget(const ReconstructionConfig& config, const cv::Mat& grey,
                         const Ellipse& detected, int frameThreshold,
                         ReconstructionWorkspace& ws, ReconstructionResult& out) {
  out.steps = ReconstructionSteps{};
  out.contour.clear();
  out.contour_ideal.clear();
  out.spots = SpotFeatures{};
  out.threshold = -1;
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
      extractContour(config.options.contour_mode, grey, out.crop, detected, fw, out.contour);
  if (!ok(contourStatus)) return fail(out.steps.contour, contourStatus);
  out.steps.contour = Status::Ok;

  const Status spotStatus = extractSpots(grey, out.crop, detected, config.target, fw, out.spots);
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

  // The direct fit (thesis 2.6.2) without its quality measures: the detection stage has
  // already judged the rim.
  ConicMoments moments;
  moments.add(std::span<const Eigen::Vector2d>(out.contour_ideal));
  EllipseFit fit;
  const Status fitStatus = fitEllipse(moments, fit);
  if (!ok(fitStatus)) return fail(out.steps.fit, fitStatus);
  out.steps.fit = Status::Ok;
  out.conic = fit.conic;
  out.ellipse = fit.ellipse;

  const Status poseStatus = poseFromEllipse(config.camera, config.target, out.conic,
                                            out.centre_spot_ideal, out.offset_spot_ideal, out.pose,
                                            config.options.centre_spot_normal);
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
