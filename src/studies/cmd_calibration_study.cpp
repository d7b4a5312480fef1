// imagepro-studies calibration-study: the measured accuracy of the lens distortion calibration
// (thesis 4.6) written to docs/calibration.md. Four virtual images of the pattern at +-45 deg
// about x and y, grey, blurred and noisy, through the thesis camera's distortion: the field
// the procedure recovers against the true one over the whole image, next to OpenCV's
// cv::calibrateCamera given the same spot grid; then the pose accuracy of the whole chain on
// distorted target frames corrected with the recovered, the true and no parameters. The prose
// is docs/calibration.md's own; the study fills in the figures at its measured places.
#include <Eigen/Geometry>
#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "cli/command.h"
#include "core/calibration/calibrate.h"
#include "core/calibration/pattern.h"
#include "core/calibration/pattern_document.h"
#include "core/calibration/spacing.h"
#include "core/common/atomic_file.h"
#include "core/pipeline/engine.h"
#include "core/source/virtual_renderer.h"
#include "studies/measured_doc.h"
#include "studies/report.h"

namespace imagepro::studies {
namespace {

using namespace imagepro::cli;

constexpr double kViewDistanceMm = 800.0;
constexpr double kNoiseSigma = 3.0, kBlurSigmaPx = 0.8;
constexpr double kDeg = M_PI / 180.0;

// OpenCV's model (normalised coordinates, k3 = 0 here) as a pixel displacement field.
DisplacementField openCvField(const cv::Mat& K, const cv::Mat& dist) {
  const double fx = K.at<double>(0, 0), fy = K.at<double>(1, 1), cx = K.at<double>(0, 2), cy = K.at<double>(1, 2);
  const double k1 = dist.at<double>(0), k2 = dist.at<double>(1), p1 = dist.at<double>(2), p2 = dist.at<double>(3),
               k3 = dist.total() > 4 ? dist.at<double>(4) : 0.0;
  return [=](const Eigen::Vector2d& q) {
    const double x = (q.x() - cx) / fx, y = (q.y() - cy) / fy;
    const double r2 = x * x + y * y;
    const double radial = 1.0 + k1 * r2 + k2 * r2 * r2 + k3 * r2 * r2 * r2;
    const double xd = x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x);
    const double yd = y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y;
    return Eigen::Vector2d(fx * xd + cx - q.x(), fy * yd + cy - q.y());
  };
}

struct OpenCvRun {
  bool ok = false;
  double reprojection_rms_px = 0.0;
  cv::Mat K, dist;
  Distortion asPixels;  // eq. 4.7 in pixels: exact when fx = fy
  double ms = 0.0;
};

// cv::calibrateCamera on the spot grid the procedure matched: plane points and spot centres,
// focal lengths and principal point fixed at the camera's, k1, k2, p1, p2 free (k3 fixed at 0).
OpenCvRun runOpenCv(const CameraModel& cam, const CalibrationResult& ours) {
  std::vector<std::vector<cv::Point3f>> object;
  std::vector<std::vector<cv::Point2f>> image;
  for (const CalibrationImageReport& im : ours.images) {
    if (!ok(im.status)) continue;
    object.emplace_back();
    image.emplace_back();
    for (const SpotCorrespondence& c : im.correspondences) {
      object.back().emplace_back(static_cast<float>(c.pattern_mm.x()), static_cast<float>(c.pattern_mm.y()), 0.0f);
      image.back().emplace_back(static_cast<float>(c.seen_px.x()), static_cast<float>(c.seen_px.y()));
    }
  }
  OpenCvRun r;
  if (object.empty()) return r;
  r.K = (cv::Mat_<double>(3, 3) << cam.fu(), 0, cam.u0(), 0, cam.fv(), cam.v0(), 0, 0, 1);
  r.dist = cv::Mat::zeros(5, 1, CV_64F);
  std::vector<cv::Mat> rvecs, tvecs;
  const int flags = cv::CALIB_USE_INTRINSIC_GUESS | cv::CALIB_FIX_FOCAL_LENGTH | cv::CALIB_FIX_PRINCIPAL_POINT |
                    cv::CALIB_FIX_K3;
  const auto start = std::chrono::steady_clock::now();
  r.reprojection_rms_px = cv::calibrateCamera(object, image, cv::Size(cam.width, cam.height), r.K, r.dist, rvecs,
                                              tvecs, flags);
  r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const double f = r.K.at<double>(0, 0);
  r.asPixels = {r.dist.at<double>(0) / (f * f), r.dist.at<double>(1) / (f * f * f * f), r.dist.at<double>(2) / f,
                r.dist.at<double>(3) / f};
  r.ok = true;
  return r;
}

struct Trial {
  std::string name;
  Status status = Status::Stopped;
  CalibrationResult ours;
  FieldComparison oursField;
  OpenCvRun cv;
  FieldComparison cvField;
  double ms = 0.0;
};

// The four views of thesis 4.6: +-tilt about x, then about y, the target on the optical axis.
std::array<Pose, 4> calibrationViews(double distance_mm, double tilt_deg = 45.0) {
  return {Pose{tilt_deg, 0.0, 0.0, 0.0, 0.0, distance_mm}, Pose{-tilt_deg, 0.0, 0.0, 0.0, 0.0, distance_mm},
          Pose{0.0, tilt_deg, 0.0, 0.0, 0.0, distance_mm}, Pose{0.0, -tilt_deg, 0.0, 0.0, 0.0, distance_mm}};
}

Trial runTrial(const Settings& settings, const std::string& name, const VirtualSceneOptions& scene,
               std::uint64_t seedBase, bool refinePose, const std::array<Pose, 4>& views = recommendedCalibrationViews(kViewDistanceMm)) {
  Trial t;
  t.name = name;
  CameraModel lens = settings.camera();
  lens.distortion = kThesisCameraDistortion;
  std::vector<cv::Mat> images(views.size());
  for (size_t i = 0; i < views.size(); ++i)
    renderPattern(lens, settings.target, settings.pattern, scene, views[i], images[i], seedBase + i);
  Settings s = settings;
  s.camera().distortion = {};
  s.pipeline.calibration.refine_pose = refinePose;
  const auto start = std::chrono::steady_clock::now();
  t.status = calibrateDistortion(s, images, t.ours);
  t.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  t.oursField = compareDistortionFields(s.camera(), t.ours.distortion, kThesisCameraDistortion);
  if (!ok(t.status) && t.status != Status::PoorCoverage) return t;
  t.cv = runOpenCv(s.camera(), t.ours);
  if (t.cv.ok)
    t.cvField = compareDisplacementFields(s.camera(), openCvField(t.cv.K, t.cv.dist),
                                          displacementField(s.camera(), kThesisCameraDistortion));
  return t;
}

// Pose accuracy of the whole chain on distorted target frames.
struct ChainStats {
  int frames = 0, ok = 0;
  double rotMedian = 0, rotP95 = 0, posMedian = 0, posP95 = 0;
  double rotP95HeadOn = 0, rotP95Tilted = 0;  // tilt below / from kHeadOnTiltDeg
};

// Below this tilt the rim's ellipse is nearly a circle and its normal poorly determined
// (docs/accuracy.md's 0-15 deg band).
constexpr double kHeadOnTiltDeg = 15.0;

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double at = p * (v.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(at)), hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (at - lo) * (v[hi] - v[lo]);
}

struct ChainFrame {
  Pose pose;
  double tilt_deg = 0.0;  // between the target's normal and the line of sight
  cv::Mat image;          // through the lens
  cv::Mat withoutLens;    // the same frame through a distortion-free lens
};

std::vector<ChainFrame> chainFrames(const Settings& settings, int count, std::uint64_t seed) {
  CameraModel lens = settings.camera();
  lens.distortion = kThesisCameraDistortion;
  // The whole card in view: its corners are a disk of radius half the card's diagonal.
  TargetGeometry card = settings.target;
  card.radius_mm = 0.5 * std::sqrt(2.0) * settings.virtual_scene.card_size_mm;
  std::mt19937_64 rng(seed);
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  VirtualSceneOptions scene = settings.virtual_scene;
  scene.mode = RenderMode::Grey;
  scene.backdrop = Backdrop::Plain;
  scene.noise_sigma = kNoiseSigma;
  scene.blur_sigma_px = kBlurSigmaPx;
  std::vector<ChainFrame> frames;
  while (static_cast<int>(frames.size()) < count) {
    // Anywhere in the image (the corners are where the distortion is), 500-1000 mm away,
    // tilted up to 45 deg from the line of sight, turned at random in its plane.
    const Eigen::Vector2d ideal(uniform(0, lens.width - 1), uniform(0, lens.height - 1));
    const Eigen::Vector3d sight = backProjectIdeal(lens, ideal).normalized();
    const double tiltDeg = uniform(0.0, 45.0), tilt = tiltDeg * kDeg, azimuth = uniform(0.0, 2 * M_PI);
    const Eigen::Vector3d e1 = sight.cross(Eigen::Vector3d::UnitY()).normalized(), e2 = sight.cross(e1);
    const Eigen::Vector3d n =
        std::cos(tilt) * sight + std::sin(tilt) * (std::cos(azimuth) * e1 + std::sin(azimuth) * e2);
    Eigen::Matrix3d R;
    R.col(2) = n;
    R.col(0) = Eigen::AngleAxisd(uniform(-M_PI, M_PI), n) * (Eigen::Vector3d::UnitX() - n * n.x()).normalized();
    R.col(1) = n.cross(R.col(0));
    const Pose pose = poseFromRt(R, uniform(500.0, 1000.0) * sight);
    if (!targetInView(lens, card, pose)) continue;
    ChainFrame f;
    f.pose = pose;
    f.tilt_deg = tiltDeg;
    renderTarget(lens, settings.target, scene, pose, f.image, frames.size() + 1);
    renderTarget(settings.camera(), settings.target, scene, pose, f.withoutLens, frames.size() + 1);
    frames.push_back(std::move(f));
  }
  return frames;
}

ChainStats runChain(const Settings& settings, const Distortion& correction, bool correct,
                    const std::vector<ChainFrame>& frames, bool throughLens = true) {
  Settings s = settings;
  s.camera().distortion = correction;
  s.pipeline.reconstruction.distortion_correction = correct;
  s.pipeline.tracking.mode = TrackingMode::Off;
  Engine engine(s);
  ChainStats st;
  std::vector<double> rot, pos, rotHeadOn, rotTilted;
  Frame frame;
  FrameResult r;
  for (const ChainFrame& f : frames) {
    frame.image = throughLens ? f.image : f.withoutLens;
    ++frame.index;
    engine.process(frame, r);
    ++st.frames;
    if (!ok(r.status) || !r.pose) continue;
    ++st.ok;
    rot.push_back(rotationAngleBetweenDeg(rotationMatrix(f.pose), rotationMatrix(*r.pose)));
    (f.tilt_deg < kHeadOnTiltDeg ? rotHeadOn : rotTilted).push_back(rot.back());
    pos.push_back(100.0 * (translation(*r.pose) - translation(f.pose)).norm() / translation(f.pose).norm());
  }
  st.rotMedian = percentile(rot, 0.5);
  st.rotP95 = percentile(rot, 0.95);
  st.posMedian = percentile(pos, 0.5);
  st.posP95 = percentile(pos, 0.95);
  st.rotP95HeadOn = percentile(rotHeadOn, 0.95);
  st.rotP95Tilted = percentile(rotTilted, 0.95);
  return st;
}

// The printed pages (imagepro-cli pattern) seen at the four views from a range of distances:
// how far the matched spots reach, what the fit makes of it, and where PoorCoverage stops it.
void measureCoverage(const Settings& settings, const VirtualSceneOptions& scene, std::uint64_t seedBase,
                     MeasuredValues& v) {
  const Paper papers[] = {Paper::A4, Paper::A3};
  const double distances[] = {300, 400, 500, 600, 700, 800, 900, 1000, 1200};
  constexpr double kGoodFieldPx = 0.05;  // half the 0.1 px goal
  Settings sheets[2];
  std::string grids;
  for (size_t k = 0; k < 2; ++k) {
    PatternPage page;
    layoutPatternPage(settings.pattern, settings.target, papers[k], page);
    sheets[k] = settings;
    sheets[k].pattern.columns = page.grid_columns;  // the sheet of the page's grid
    sheets[k].pattern.rows = page.grid_rows;
    grids += format("%s%s %d x %d spots", k ? ", " : "", paperName(papers[k]), page.grid_columns, page.grid_rows);
  }
  v["coverage.threshold"] = format("%.2f", kMinCoverageRadiusFraction);
  v["coverage.sheets"] = grids;
  std::string table = "| distance (mm) | A4 | A3 |\n| --- | --- | --- |\n";
  double farthestOk[2] = {0.0, 0.0};
  bool stillOk[2] = {true, true};
  for (const double d : distances) {
    table += format("| %.0f |", d);
    for (size_t k = 0; k < 2; ++k) {
      const Trial t = runTrial(sheets[k], "", scene, seedBase + static_cast<std::uint64_t>(d), true, calibrationViews(d));
      table += format(" %s, %.2f, %.3f / %.3f |", std::string(statusName(t.status)).c_str(),
                      t.ours.coverage_radius_fraction, t.oursField.rms_px, t.oursField.max_px);
      stillOk[k] = stillOk[k] && ok(t.status);
      if (stillOk[k]) farthestOk[k] = d;
    }
    table += "\n";
  }
  v["coverage.table"] = table;
  v["coverage.nearest"] = format("%.0f", distances[0]);
  v["coverage.farthest.A4"] = format("%.0f", farthestOk[0]);
  v["coverage.farthest.A3"] = format("%.0f", farthestOk[1]);

  // The threshold: over both pages, views tilted 35 and 45 deg and three noise seeds, every run
  // whose fit converged (ok or PoorCoverage), by its reach.
  struct Run {
    double reach, field, residual;
  };
  std::vector<Run> runs;
  for (size_t k = 0; k < 2; ++k)
    for (const double tilt : {35.0, 45.0})
      for (std::uint64_t seed = 0; seed < 3; ++seed)
        for (const double d : distances) {
          const Trial t = runTrial(sheets[k], "", scene, seedBase + 5000 + 1000 * seed + static_cast<std::uint64_t>(d),
                                   true, calibrationViews(d, tilt));
          if (t.ours.converged)
            runs.push_back({t.ours.coverage_radius_fraction, t.oursField.rms_px, t.ours.rms_residual_px});
        }
  double lowestBad = 1.0, highestBad = 0.0, worstAbove = 0.0, worstBelow = 0.0, badResidual = 0.0;
  int above = 0, below = 0, badBelow = 0;
  for (const Run& r : runs) {
    if (r.field > kGoodFieldPx) {
      lowestBad = std::min(lowestBad, r.reach);
      badResidual = std::max(badResidual, r.residual);
      highestBad = std::max(highestBad, r.reach);
    }
    if (r.reach >= kMinCoverageRadiusFraction) {
      ++above;
      worstAbove = std::max(worstAbove, r.field);
    } else {
      ++below;
      badBelow += r.field > kGoodFieldPx ? 1 : 0;
      worstBelow = std::max(worstBelow, r.field);
    }
  }
  v["threshold.runs"] = std::to_string(runs.size());
  v["threshold.good"] = format("%.2f", kGoodFieldPx);
  v["threshold.bad.reach"] = format("%.2f-%.2f", runs.empty() || highestBad == 0.0 ? 0.0 : lowestBad, highestBad);
  v["threshold.above"] = std::to_string(above);
  v["threshold.above.worst"] = format("%.3f", worstAbove);
  v["threshold.below"] = std::to_string(below);
  v["threshold.below.bad"] = std::to_string(badBelow);
  v["threshold.below.worst"] = format("%.3f", worstBelow);
  v["threshold.bad.residual"] = format("%.3f", badResidual);
}

std::string distortionCells(const std::string& what, const Distortion& d) {
  return format("| %s | %.4e | %.4e | %.4e | %.4e |", what.c_str(), d.k1, d.k2, d.p1, d.p2);
}

std::string distortionRow(const std::string& what, const Distortion& d, const std::string& tail) {
  return distortionCells(what, d) + " " + tail + " |\n";
}

// The iteration's history, each view's spot matching and pose, and step 7 with and without the
// pose correction.
void measureIteration(const Trial& main, const Trial& thesis, MeasuredValues& v) {
  v["main.status"] = std::string(statusName(main.status));
  v["main.iterations"] = std::to_string(main.ours.iterations);
  v["main.residual"] = format("%.4f", main.ours.rms_residual_px);
  v["main.field.rms"] = format("%.4f", main.oursField.rms_px);
  v["main.field.max"] = format("%.4f", main.oursField.max_px);
  std::string iterations =
      "| iteration | k1 (px^-2) | k2 (px^-4) | p1 (px^-1) | p2 (px^-1) | relative change, residual, spots |\n"
      "| --- | --- | --- | --- | --- | --- |\n";
  for (const CalibrationIteration& it : main.ours.history)
    iterations += distortionRow(std::to_string(it.iteration), it.distortion,
                                format("%.4f, %.4f px, %d", it.relative_change, it.rms_residual_px, it.matches));
  v["iteration.table"] = iterations + distortionRow("true", kThesisCameraDistortion, "");

  std::string views =
      "| view | spots matched / expected | ambiguous | target's pose error (deg) | corrected pose error (deg) |\n"
      "| --- | --- | --- | --- | --- |\n";
  const auto truth = recommendedCalibrationViews(kViewDistanceMm);
  double worstTarget = 0.0;
  for (size_t i = 0; i < main.ours.images.size(); ++i) {
    const CalibrationImageReport& im = main.ours.images[i];
    const double targetError = rotationAngleBetweenDeg(rotationMatrix(im.target_pose), rotationMatrix(truth[i]));
    worstTarget = std::max(worstTarget, targetError);
    views += format("| Rx %+.0f, Ry %+.0f | %d / %d | %d | %.3f | %.4f |\n", truth[i].rx_deg, truth[i].ry_deg,
                    im.match.matched, im.spots_expected, im.match.ambiguous, targetError,
                    rotationAngleBetweenDeg(rotationMatrix(im.pose), rotationMatrix(truth[i])));
  }
  v["views.table"] = views;
  v["views.worst"] = format("%.3f", worstTarget);

  auto step7 = [](const char* what, const Trial& t) {
    return format("| %s | %s | %d | %.4f | %.4f |\n", what, std::string(statusName(t.status)).c_str(),
                  t.ours.iterations, t.oursField.rms_px, t.oursField.max_px);
  };
  v["step7.table"] = "| step 7 | status | iterations | field error RMS (px) | field error max (px) |\n"
                     "| --- | --- | --- | --- | --- |\n" +
                     step7("eq. 4.8 with pose correction (default)", main) + step7("eq. 4.8 alone (thesis)", thesis);
}

void measureOpenCv(const Trial& main, const std::vector<Trial>& trials, MeasuredValues& v) {
  std::string table =
      "| images | ours: status, iterations | ours: field error RMS / max (px) | OpenCV: field error RMS / max (px) "
      "| OpenCV reprojection RMS (px) |\n| --- | --- | --- | --- | --- |\n";
  auto trialRow = [&](const Trial& t) {
    table += format("| %s | %s, %d | %.4f / %.4f | %.4f / %.4f | %.4f |\n", t.name.c_str(),
                    std::string(statusName(t.status)).c_str(), t.ours.iterations, t.oursField.rms_px,
                    t.oursField.max_px, t.cvField.rms_px, t.cvField.max_px, t.cv.reprojection_rms_px);
  };
  trialRow(main);
  for (const Trial& t : trials) trialRow(t);
  v["opencv.table"] = table;
  v["opencv.parameters"] = "| | k1 (px^-2) | k2 (px^-4) | p1 (px^-1) | p2 (px^-1) |\n| --- | --- | --- | --- | --- |\n" +
                           distortionCells("true", kThesisCameraDistortion) + "\n" +
                           distortionCells("ours", main.ours.distortion) + "\n" +
                           distortionCells("OpenCV", main.cv.asPixels) + "\n";
  // The figures that vary from run to run: the docs check skips their line (tools/regenerate-docs.sh).
  v["time.ours"] = format("%.0f", main.ms);
  v["time.opencv"] = format("%.0f", main.cv.ms);
}

// The whole chain on distorted target frames, corrected with each set of parameters.
void measureReconstruction(const Settings& settings, const Trial& main, int frames, int seed, MeasuredValues& v) {
  std::fprintf(stderr, "pose accuracy over %d frames ...\n", frames);
  const std::vector<ChainFrame> chain = chainFrames(settings, frames, static_cast<std::uint64_t>(seed));
  const ChainStats withTrue = runChain(settings, kThesisCameraDistortion, true, chain);
  const ChainStats withOurs = runChain(settings, main.ours.distortion, true, chain);
  const ChainStats withCv = runChain(settings, main.cv.asPixels, true, chain);
  const ChainStats without = runChain(settings, Distortion{}, false, chain);
  const ChainStats noLens = runChain(settings, Distortion{}, false, chain, false);
  int headOn = 0;
  for (const ChainFrame& f : chain) headOn += f.tilt_deg < kHeadOnTiltDeg ? 1 : 0;
  std::string table = format(
      "| correction with | poses | rotation error median / 95th pct (deg) | rotation 95th pct, tilt 0-%.0f / %.0f-45 deg "
      "| position error median / 95th pct (%%) |\n| --- | --- | --- | --- | --- |\n",
      kHeadOnTiltDeg, kHeadOnTiltDeg);
  auto chainRow = [&](const char* what, const ChainStats& c) {
    table += format("| %s | %d / %d | %.3f / %.3f | %.3f / %.3f | %.3f / %.3f |\n", what, c.ok, c.frames, c.rotMedian,
                    c.rotP95, c.rotP95HeadOn, c.rotP95Tilted, c.posMedian, c.posP95);
  };
  chainRow("the true parameters", withTrue);
  chainRow("the recovered parameters (ours)", withOurs);
  chainRow("OpenCV's parameters", withCv);
  chainRow("none (correction off)", without);
  chainRow("no lens distortion in the frames (reference)", noLens);
  v["chain.table"] = table;
  v["chain.true.p95"] = format("%.3f", withTrue.rotP95);
  v["chain.nolens.p95"] = format("%.3f", noLens.rotP95);
  v["chain.headon"] = std::to_string(headOn);
  v["chain.true.p95.headon"] = format("%.3f", withTrue.rotP95HeadOn);
  v["chain.true.p95.tilted"] = format("%.3f", withTrue.rotP95Tilted);
}

// The smallest spot spacing the matching stays unambiguous at (thesis 4.3), and the pattern's.
void measureSpacing(const Settings& settings, MeasuredValues& v) {
  CameraModel expected = settings.camera();
  expected.distortion = kThesisCameraDistortion;
  const auto views = recommendedCalibrationViews(kViewDistanceMm);
  const double withNeighbours = minimumSpotSpacingMm(expected, settings.target, settings.pattern, views, true);
  const double idealOnly = minimumSpotSpacingMm(expected, settings.target, settings.pattern, views, false);
  const SpacingCheck current = checkSpotSpacing(expected, settings.target, settings.pattern, views);
  v["spacing.table"] =
      "| matching | smallest unambiguous spacing |\n| --- | --- |\n" +
      format("| from the origin outwards, predicted by the matched neighbours' displacement (ours) | %.1f mm |\n",
             withNeighbours) +
      format("| by the ideal positions alone | %.1f mm |\n", idealOnly);
  v["spacing.worst"] = format("%.2f", current.worst_ratio);
  v["spacing.gap"] = format("%.2f", current.smallest_gap_px);
  v["spacing.verdict"] = current.unambiguous ? "unambiguous" : "NOT unambiguous";
}

int run(const Args& args) {
  args.rejectUnknown({"out", "template", "frames", "seed"});
  const auto out = args.value("out");
  if (!out) throw UsageError("--out FILE is required (e.g. docs/calibration.md)");
  const std::string templatePath = args.valueOr("template", *out);
  const int frames = args.integer("frames", 200);
  if (frames < 10 || frames > 100000) throw UsageError("--frames must be 10..100000");
  const int seed = args.integer("seed", 1);
  if (std::string error; !checkMeasuredDoc(templatePath, error)) throw InputError(error);
  const Settings settings = loadConfig(args);
  std::string command = "imagepro-studies calibration-study --out " + *out;
  if (args.has("frames")) command += " --frames " + std::to_string(frames);
  if (args.has("seed")) command += " --seed " + std::to_string(seed);
  if (const auto config = args.value("config")) command += " --config " + *config;

  VirtualSceneOptions realistic = settings.virtual_scene;
  realistic.mode = RenderMode::Grey;
  realistic.backdrop = Backdrop::Plain;
  realistic.noise_sigma = kNoiseSigma;
  realistic.blur_sigma_px = kBlurSigmaPx;
  VirtualSceneOptions clean = realistic;
  clean.noise_sigma = clean.blur_sigma_px = 0.0;

  MeasuredValues v;
  v["command"] = "`" + command + "`";
  v["frames"] = std::to_string(frames);
  const PatternGeometry& pattern = settings.pattern;
  v["pattern.grid"] = format("%d x %d", pattern.columns, pattern.rows);
  v["pattern.spacing"] = format("%g", pattern.spot_spacing_mm);
  v["pattern.spot"] = format("%g", 2.0 * patternSpotRadiusMm(pattern));
  v["pattern.card"] = format("%g", pattern.card_size_mm);
  v["pattern.size"] =
      format("%.0f x %.0f", pattern.columns * pattern.spot_spacing_mm, pattern.rows * pattern.spot_spacing_mm);
  const FieldComparison whole = compareDistortionFields(settings.camera(), kThesisCameraDistortion, Distortion{});
  v["lens.max"] = format("%.2f", whole.max_px);
  v["lens.rms"] = format("%.2f", whole.rms_px);

  std::fprintf(stderr, "calibrating ...\n");
  const std::uint64_t base = static_cast<std::uint64_t>(seed) * 1000;
  const Trial main = runTrial(settings, "noise 3, blur 0.8", realistic, base + 1, true);
  std::vector<Trial> trials;
  trials.push_back(runTrial(settings, "no noise, no blur", clean, base + 11, true));
  for (int k = 0; k < 4; ++k)
    trials.push_back(runTrial(settings, format("noise 3, blur 0.8, seed %d", k + 2), realistic, base + 21 + 10 * k, true));
  const Trial thesis = runTrial(settings, "thesis step 7 (no pose correction)", realistic, base + 1, false);
  measureIteration(main, thesis, v);
  measureOpenCv(main, trials, v);
  measureReconstruction(settings, main, frames, seed, v);
  std::fprintf(stderr, "coverage of the printed pages ...\n");
  measureCoverage(settings, realistic, base + 100, v);
  measureSpacing(settings, v);

  // Every place of the doc is this study's: all are filled.
  std::string error;
  if (!fillMeasuredDoc(templatePath, *out, v, {""}, error)) throw InputError(error);
  std::printf("wrote %s\n", out->c_str());
  return 0;
}

const CommandRegistration kRegistration{{
    "calibration-study",
    "measure the distortion calibration against the truth and OpenCV (docs/calibration.md)",
    "usage: imagepro-studies calibration-study --out FILE [--template DOC] [--frames N] [--seed S]\n"
    "                                         [--config FILE]\n\n"
    "Calibrates from four virtual pattern views (+-45 deg about x and y, grey, blurred, noisy,\n"
    "the thesis camera's distortion) and compares the recovered distortion field with the true one\n"
    "and with OpenCV's cv::calibrateCamera on the same spot grid; then reconstructs N distorted\n"
    "target frames (default 200) with the recovered, OpenCV's, the true and no parameters.\n"
    "Fills the measured places (<!--m:NAME-->...<!--/m-->) of the hand-written doc given with\n"
    "--template (default: FILE itself, e.g. docs/calibration.md) and writes it to FILE; the prose\n"
    "stays as written. A doc without a place for a figure, or with a place the study does not\n"
    "fill, is refused with the place named.",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::studies
