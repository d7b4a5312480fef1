// imagepro-studies calibration-study: the measured accuracy of the lens distortion calibration
// (thesis 4.6) written to docs/calibration.md. Four virtual images of the pattern at +-45 deg
// about x and y, grey, blurred and noisy, through the thesis camera's distortion: the field
// the procedure recovers against the true one over the whole image, next to OpenCV's
// cv::calibrateCamera given the same spot grid; then the pose accuracy of the whole chain on
// distorted target frames corrected with the recovered, the true and no parameters.
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
#include "studies/report.h"

namespace imagepro::studies {
namespace {

using namespace imagepro::cli;

constexpr double kViewDistanceMm = 800.0;
constexpr double kNoiseSigma = 3.0, kBlurSigmaPx = 0.8;
constexpr double kDeg = M_PI / 180.0;
// Everything from this line on in an existing FILE is written by hand (the application's
// calibration wizard) and kept when the figures above it are measured again.
constexpr const char* kKeptSectionsMarker = "<!-- Hand-written sections below: kept by imagepro-studies calibration-study -->";

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
std::string coverageSection(const Settings& settings, const VirtualSceneOptions& scene, std::uint64_t seedBase) {
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

  std::string md = "\n## Coverage: how close the pattern must be\n\n";
  md += format("The fit extrapolates eq. 4.7 beyond the matched spots, and its r^4 term goes wrong fast. So the\n"
               "calibration also measures how far the spots it matched reach: the largest distance of a matched\n"
               "spot's ideal position from the principal point, over the distance of the image's farthest corner\n"
               "(`coverageRadiusFraction`, over every image used). Below %.2f it ends with `PoorCoverage` (\"the\n"
               "pattern covers too little of the image to calibrate it to its corners: move the pattern closer or\n"
               "print it larger\"), the estimate left in the result and no calibration file written.\n\n"
               "The printed pages of `imagepro-cli pattern` with the settings' pattern (%s: the sheets\n"
               "calibrated here), at the four views above from each distance (the target on the optical axis),\n"
               "through the thesis camera, grey, blur 0.8 px, noise 3; reach, then the field error RMS / max:\n\n",
               kMinCoverageRadiusFraction, grids.c_str());
  md += "| distance (mm) | A4 | A3 |\n| --- | --- | --- |\n";
  double farthestOk[2] = {0.0, 0.0};
  bool stillOk[2] = {true, true};
  for (const double d : distances) {
    md += format("| %.0f |", d);
    for (size_t k = 0; k < 2; ++k) {
      const Trial t = runTrial(sheets[k], "", scene, seedBase + static_cast<std::uint64_t>(d), true, calibrationViews(d));
      md += format(" %s, %.2f, %.3f / %.3f |", std::string(statusName(t.status)).c_str(),
                   t.ours.coverage_radius_fraction, t.oursField.rms_px, t.oursField.max_px);
      stillOk[k] = stillOk[k] && ok(t.status);
      if (stillOk[k]) farthestOk[k] = d;
    }
    md += "\n";
  }
  md += format("\nWorking distance with the thesis camera (640x480, d0 = 8 mm, 0.01 mm pixels), the target on the\n"
               "optical axis: from %.0f mm (the nearest measured) up to %.0f mm for A4, %.0f mm for A3, the farthest\n"
               "distance of the table up to which every calibration passed. The settings' default sheet (%d x %d\n"
               "spots, %.0f x %.0f mm; the Virtual source's) fills the image at every distance of the views above;\n"
               "a printed sheet that large must be assembled from pages or printed on a plotter.\n",
               distances[0], farthestOk[0], farthestOk[1], settings.pattern.columns, settings.pattern.rows,
               settings.pattern.columns * settings.pattern.spot_spacing_mm,
               settings.pattern.rows * settings.pattern.spot_spacing_mm);

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
  md += format("\nThe threshold, measured: the same pages at the same distances, views tilted 35 and 45 deg, three\n"
               "noise seeds each; of the %zu runs whose fit converged, those with a field error above %.2f px RMS\n"
               "(half the 0.1 px goal) reached %.2f-%.2f of the corner distance. At or above %.2f: %d runs, the\n"
               "largest field error %.3f px RMS. Below it: %d runs, %d of them above %.2f px, the largest %.3f px\n"
               "RMS. The fit's residual does not tell them apart: at most %.3f px on the runs above %.2f px, as\n"
               "small as a good calibration's.\n",
               runs.size(), kGoodFieldPx, runs.empty() || highestBad == 0.0 ? 0.0 : lowestBad, highestBad,
               kMinCoverageRadiusFraction, above, worstAbove, below, badBelow, kGoodFieldPx, worstBelow, badResidual,
               kGoodFieldPx);
  return md;
}

std::string distortionCells(const std::string& what, const Distortion& d) {
  return format("| %s | %.4e | %.4e | %.4e | %.4e |", what.c_str(), d.k1, d.k2, d.p1, d.p2);
}

std::string distortionRow(const std::string& what, const Distortion& d, const std::string& tail) {
  return distortionCells(what, d) + " " + tail + " |\n";
}

int run(const Args& args) {
  args.rejectUnknown({"out", "frames", "seed"});
  const auto out = args.value("out");
  if (!out) throw UsageError("--out FILE is required (e.g. docs/calibration.md)");
  const int frames = args.integer("frames", 200);
  if (frames < 10 || frames > 100000) throw UsageError("--frames must be 10..100000");
  const int seed = args.integer("seed", 1);
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

  std::fprintf(stderr, "calibrating ...\n");
  const std::uint64_t base = static_cast<std::uint64_t>(seed) * 1000;
  const Trial main = runTrial(settings, "noise 3, blur 0.8", realistic, base + 1, true);
  std::vector<Trial> trials;
  trials.push_back(runTrial(settings, "no noise, no blur", clean, base + 11, true));
  for (int k = 0; k < 4; ++k)
    trials.push_back(runTrial(settings, format("noise 3, blur 0.8, seed %d", k + 2), realistic, base + 21 + 10 * k, true));
  const Trial thesis = runTrial(settings, "thesis step 7 (no pose correction)", realistic, base + 1, false);

  const CameraModel& cam = settings.camera();
  const FieldComparison whole = compareDistortionFields(cam, kThesisCameraDistortion, Distortion{});

  std::string md;
  md += "# Lens distortion calibration: measured accuracy\n\n";
  md += "Produced by `" + command + "` (" + std::to_string(frames) +
        " target frames for the pose accuracy).\n\n";
  md += "The procedure of thesis 4.6 (`core/calibration/calibrate.h`) on four virtual images of the\n";
  md += format("calibration pattern (`core/calibration/pattern.h`; %d x %d spots %g mm apart, each %g mm across,\n"
               "%g mm card; the section \"The pattern\" below) rotated\n",
               settings.pattern.columns, settings.pattern.rows, settings.pattern.spot_spacing_mm,
               2.0 * patternSpotRadiusMm(settings.pattern), settings.pattern.card_size_mm);
  md += "+45 and -45 deg about x and then about y, the target on the optical axis 800 mm away, rendered by\n"
        "the Virtual source's renderer through the thesis camera's lens (640x480, d0 = 8 mm, 0.01 mm pixels,\n"
        "k1 = -2.05e-7, k2 = -1.21e-13, p1 = 3.39e-6, p2 = 2.56e-6, thesis 4.6), anti-aliased grey with\n"
        "Gaussian blur sigma 0.8 px and noise sigma 3 grey levels. The procedure starts from zero distortion\n"
        "and finds the pattern's pose from the target alone. The true distortion moves the image's corners\n";
  md += format("by %.2f px (RMS over the image %.2f px).\n\n", whole.max_px, whole.rms_px);
  md += "Field error: the recovered displacement field (eq. 4.7) minus the true one, at every pixel centre\n"
        "of the 640x480 image taken as the undistorted position, RMS and largest.\n\n";

  md += "## The iteration (thesis 4.6 steps 3-8)\n\n";
  md += "| iteration | k1 (px^-2) | k2 (px^-4) | p1 (px^-1) | p2 (px^-1) | relative change, residual, spots |\n";
  md += "| --- | --- | --- | --- | --- | --- |\n";
  for (const CalibrationIteration& it : main.ours.history)
    md += distortionRow(std::to_string(it.iteration), it.distortion,
                        format("%.4f, %.4f px, %d", it.relative_change, it.rms_residual_px, it.matches));
  md += distortionRow("true", kThesisCameraDistortion, "");
  md += format("\nStatus %s after %d iterations (the thesis: 3; limit asked: 5), RMS residual %.4f px.\n"
               "**Field error %.4f px RMS, %.4f px largest** (asked: at most 0.1 px RMS).\n\n",
               std::string(statusName(main.status)).c_str(), main.ours.iterations, main.ours.rms_residual_px,
               main.oursField.rms_px, main.oursField.max_px);
  md += "| view | spots matched / expected | ambiguous | target's pose error (deg) | corrected pose error (deg) |\n";
  md += "| --- | --- | --- | --- | --- |\n";
  const auto views = recommendedCalibrationViews(kViewDistanceMm);
  for (size_t i = 0; i < main.ours.images.size(); ++i) {
    const CalibrationImageReport& im = main.ours.images[i];
    md += format("| Rx %+.0f, Ry %+.0f | %d / %d | %d | %.3f | %.4f |\n", views[i].rx_deg, views[i].ry_deg,
                 im.match.matched, im.spots_expected, im.match.ambiguous,
                 rotationAngleBetweenDeg(rotationMatrix(im.target_pose), rotationMatrix(views[i])),
                 rotationAngleBetweenDeg(rotationMatrix(im.pose), rotationMatrix(views[i])));
  }
  double worstTarget = 0.0;
  for (size_t i = 0; i < main.ours.images.size(); ++i)
    worstTarget = std::max(worstTarget, rotationAngleBetweenDeg(rotationMatrix(main.ours.images[i].target_pose),
                                                                rotationMatrix(views[i])));
  md += format("\nThe target gives each view's pose to within %.3f deg here. The pattern reaches 700 mm and more\n"
               "from the target, where such an error moves the spots' ideal positions by tenths of a pixel, and\n"
               "eq. 4.8 alone takes that for distortion. So step 7 solves eq. 4.8 together with a linearised\n"
               "correction of each image's pose (six more columns per image; `fitDistortionAndPoses`), and the\n"
               "next iteration starts from the corrected pose. With the thesis's step 7 alone (eq. 4.8 over the\n"
               "target's poses, `pipeline.calibration.refine_pose = false`) on the same images:\n\n",
               worstTarget);
  md += format("| step 7 | status | iterations | field error RMS (px) | field error max (px) |\n| --- | --- | --- | --- | --- |\n");
  md += format("| eq. 4.8 with pose correction (default) | %s | %d | %.4f | %.4f |\n",
               std::string(statusName(main.status)).c_str(), main.ours.iterations, main.oursField.rms_px,
               main.oursField.max_px);
  md += format("| eq. 4.8 alone (thesis) | %s | %d | %.4f | %.4f |\n\n",
               std::string(statusName(thesis.status)).c_str(), thesis.ours.iterations, thesis.oursField.rms_px,
               thesis.oursField.max_px);

  md += "## Side by side with OpenCV\n\n";
  md += "`cv::calibrateCamera` on the same images' spot grid: the plane positions of the spots the procedure\n"
        "matched in its last iteration and their measured centres, focal lengths and principal point fixed at\n"
        "the camera's (`CALIB_USE_INTRINSIC_GUESS | CALIB_FIX_FOCAL_LENGTH | CALIB_FIX_PRINCIPAL_POINT`),\n"
        "k1, k2, p1, p2 free, k3 fixed at 0 (`CALIB_FIX_K3`). OpenCV's model is eq. 4.7 in normalised\n"
        "coordinates, so with fx = fy = f its parameters are k1 f^2, k2 f^4, p1 f, p2 f of ours; both fields\n"
        "are compared as pixel displacement fields, the same way.\n\n";
  md += "| images | ours: status, iterations | ours: field error RMS / max (px) | OpenCV: field error RMS / max (px) | OpenCV reprojection RMS (px) |\n";
  md += "| --- | --- | --- | --- | --- |\n";
  auto trialRow = [&](const Trial& t) {
    md += format("| %s | %s, %d | %.4f / %.4f | %.4f / %.4f | %.4f |\n", t.name.c_str(),
                 std::string(statusName(t.status)).c_str(), t.ours.iterations, t.oursField.rms_px,
                 t.oursField.max_px, t.cvField.rms_px, t.cvField.max_px, t.cv.reprojection_rms_px);
  };
  trialRow(main);
  for (const Trial& t : trials) trialRow(t);
  md += "\nParameters of the first row (OpenCV's converted to pixel units):\n\n";
  md += "| | k1 (px^-2) | k2 (px^-4) | p1 (px^-1) | p2 (px^-1) |\n| --- | --- | --- | --- | --- |\n";
  md += distortionCells("true", kThesisCameraDistortion) + "\n";
  md += distortionCells("ours", main.ours.distortion) + "\n";
  md += distortionCells("OpenCV", main.cv.asPixels) + "\n";
  // The one line that varies from run to run: the docs check skips it (tools/regenerate-docs.sh).
  md += format("\nCalibration time on the machine that wrote this: ours %.0f ms, OpenCV %.0f ms.\n", main.ms, main.cv.ms);
  md += "\nBoth fit the same model to the same spot centres; ours with each image's pose from the target\n"
        "corrected linearly, OpenCV by Levenberg-Marquardt over all poses and parameters from its own\n"
        "homography start. Their fields agree to the noise of the spot centres.\n\n";

  std::fprintf(stderr, "pose accuracy over %d frames ...\n", frames);
  const std::vector<ChainFrame> chain = chainFrames(settings, frames, static_cast<std::uint64_t>(seed));
  const ChainStats withTrue = runChain(settings, kThesisCameraDistortion, true, chain);
  const ChainStats withOurs = runChain(settings, main.ours.distortion, true, chain);
  const ChainStats withCv = runChain(settings, main.cv.asPixels, true, chain);
  const ChainStats without = runChain(settings, Distortion{}, false, chain);
  const ChainStats noLens = runChain(settings, Distortion{}, false, chain, false);
  int headOn = 0;
  for (const ChainFrame& f : chain) headOn += f.tilt_deg < kHeadOnTiltDeg ? 1 : 0;
  md += "## Reconstruction with the recovered parameters\n\n";
  md += format("%d virtual target frames through the same lens (grey, blur 0.8 px, noise 3), the target anywhere "
               "in the\nimage with its whole card, 500-1000 mm away, tilted up to 45 deg; the whole chain (detection, "
               "features,\ndistortion correction by the Taylor inverse, pose; default settings) with each set of "
               "parameters.\nRotation error: the angle of R_true^-1 R_est; position error: |T_est - T_true| in %% of "
               "the distance\n(the measure of docs/accuracy.md).\n\n",
               frames);
  md += format("| correction with | poses | rotation error median / 95th pct (deg) | rotation 95th pct, tilt "
               "0-%.0f / %.0f-45 deg | position error median / 95th pct (%%) |\n",
               kHeadOnTiltDeg, kHeadOnTiltDeg);
  md += "| --- | --- | --- | --- | --- |\n";
  auto chainRow = [&](const char* what, const ChainStats& c) {
    md += format("| %s | %d / %d | %.3f / %.3f | %.3f / %.3f | %.3f / %.3f |\n", what, c.ok, c.frames, c.rotMedian,
                 c.rotP95, c.rotP95HeadOn, c.rotP95Tilted, c.posMedian, c.posP95);
  };
  chainRow("the true parameters", withTrue);
  chainRow("the recovered parameters (ours)", withOurs);
  chainRow("OpenCV's parameters", withCv);
  chainRow("none (correction off)", without);
  chainRow("no lens distortion in the frames (reference)", noLens);
  md += format(
      "\nThe recovered parameters reconstruct as well as the true ones. The 95th percentile of the rotation error,\n"
      "%.3f deg with the true parameters, is set by this scene, not by the calibration: the same frames rendered\n"
      "without any lens distortion still give %.3f deg (last row). It comes from the frames seen nearly head-on\n"
      "(tilt below %.0f deg: %d of the %d here), where the rim's ellipse is almost a circle and its normal\n"
      "poorly determined: their 95th percentile is %.3f deg, that of the others %.3f deg. docs/accuracy.md\n"
      "measures its 95th percentile (goal 0.5 deg) on another scene: tilt 0-60 deg (a quarter of its frames below\n"
      "15 deg, against a third here), distance 400-1200 mm, and noise 0-3 grey levels and blur 0-1 px drawn per\n"
      "frame, where every frame here has noise 3 and blur 0.8; there too the 0-15 deg band has by far the largest\n"
      "95th percentile.\n",
      withTrue.rotP95, noLens.rotP95, kHeadOnTiltDeg, headOn, withTrue.frames, withTrue.rotP95HeadOn,
      withTrue.rotP95Tilted);
  std::fprintf(stderr, "coverage of the printed pages ...\n");
  md += coverageSection(settings, realistic, base + 100);

  md += "\n## The spot spacing (thesis 4.3)\n\n";
  CameraModel expected = cam;
  expected.distortion = kThesisCameraDistortion;
  const double withNeighbours = minimumSpotSpacingMm(expected, settings.target, settings.pattern, views, true);
  const double idealOnly = minimumSpotSpacingMm(expected, settings.target, settings.pattern, views, false);
  const SpacingCheck current = checkSpotSpacing(expected, settings.target, settings.pattern, views);
  md += "The smallest spacing that never gives a matching ambiguity for the expected distortion\n"
        "(`core/calibration/spacing.h`): in the first iteration (estimate zero), at the four views above, every\n"
        "spot must match its own image with its prediction within half its gate (half the local spacing),\n"
        "and neighbouring spots must stay more than 3 px apart for the spot finder. For the thesis camera:\n\n";
  md += "| matching | smallest unambiguous spacing |\n| --- | --- |\n";
  md += format("| from the origin outwards, predicted by the matched neighbours' displacement (ours) | %.1f mm |\n",
               withNeighbours);
  md += format("| by the ideal positions alone | %.1f mm |\n\n", idealOnly);
  md += format("The pattern's %.0f mm: worst prediction error %.2f of the gate, smallest gap between spots %.2f px, "
               "%s.\n",
               settings.pattern.spot_spacing_mm, current.worst_ratio, current.smallest_gap_px,
               current.unambiguous ? "unambiguous" : "NOT unambiguous");
  md += "Searched in 0.5 mm steps with the sheet kept at its size. With the neighbours' displacement the\n"
        "unexplained displacement only has to change by less than half a spacing from one spot to the next,\n"
        "so it is the spots' separation on the far side of the tilted views that sets the limit; matching by\n"
        "the ideal positions alone needs the whole displacement (16 px at the corners) within a quarter of\n"
        "the local spacing.\n";

  std::string existing, error;
  if (readWholeFile(*out, existing, error)) {
    const auto kept = existing.find(kKeptSectionsMarker);
    if (kept != std::string::npos) md += "\n" + existing.substr(kept);
  }
  if (!writeFileAtomically(*out, md, error)) throw InputError(error);
  std::printf("wrote %s\n", out->c_str());
  return 0;
}

const CommandRegistration kRegistration{{
    "calibration-study",
    "measure the distortion calibration against the truth and OpenCV (docs/calibration.md)",
    "usage: imagepro-studies calibration-study --out FILE [--frames N] [--seed S] [--config FILE]\n\n"
    "Calibrates from four virtual pattern views (+-45 deg about x and y, grey, blurred, noisy,\n"
    "the thesis camera's distortion) and compares the recovered distortion field with the true one\n"
    "and with OpenCV's cv::calibrateCamera on the same spot grid; then reconstructs N distorted\n"
    "target frames (default 200) with the recovered, OpenCV's, the true and no parameters.\n"
    "Writes the figures as Markdown to FILE, keeping the hand-written sections at the end of an\n"
    "existing FILE (from the marker line they start with on).",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::studies
