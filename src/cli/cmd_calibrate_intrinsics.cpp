#include "cli/cmd_calibrate_intrinsics.h"

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cstdio>
#include <string>
#include <vector>

#include "cli/enum_options.h"
#include "cli/image_inputs.h"
#include "core/calibration/calibration_file.h"
#include "core/calibration/intrinsics.h"
#include "core/calibration/intrinsics_report.h"
#include "core/calibration/opencv_camera_file.h"
#include "core/common/atomic_file.h"

namespace imagepro::cli {
namespace {

using json = nlohmann::ordered_json;

json resultJson(const IntrinsicsResult& r, const std::vector<std::string>& names, const CoverageMap& map,
                const std::vector<CalibrationWarning>& warnings, const CameraModel& camera) {
  json j;
  j["status"] = std::string(statusName(r.status));
  j["fx_px"] = r.fx;
  j["fy_px"] = r.fy;
  j["cx_px"] = r.cx;
  j["cy_px"] = r.cy;
  j["k1"] = r.distortion.k1;
  j["k2"] = r.distortion.k2;
  j["p1"] = r.distortion.p1;
  j["p2"] = r.distortion.p2;
  j["opencv_dist"] = r.opencv_dist;
  j["rms_px"] = r.rms_px;
  j["images_used"] = r.views_used;
  j["image_plane_distance_mm"] = camera.image_plane_distance_mm;
  j["pixel_size_mm"] = camera.pixel_size_mm;
  j["pixel_aspect"] = r.fy > 0 ? r.fx / r.fy : 0.0;
  j["model_fit_rms_px"] = r.model_fit_rms_px;
  j["std_dev"] = {{"fx_px", r.deviation.fx}, {"fy_px", r.deviation.fy}, {"cx_px", r.deviation.cx},
                  {"cy_px", r.deviation.cy}, {"k1", r.deviation.k1},    {"k2", r.deviation.k2},
                  {"p1", r.deviation.p1},    {"p2", r.deviation.p2},    {"k3", r.deviation.k3}};
  json per = json::array();
  for (size_t i = 0; i < r.views.size(); ++i) {
    const IntrinsicsView& v = r.views[i];
    json e;
    e["image"] = i < names.size() ? names[i] : std::string();
    e["status"] = std::string(statusName(v.status));
    e["dots"] = v.dots;
    e["partial"] = v.partial;
    if (ok(v.status)) {
      e["rms_px"] = v.rms_px;
      e["tilt_deg"] = v.tilt_deg;
    }
    per.push_back(e);
  }
  j["per_image"] = per;
  j["coverage"] = {{"columns", kCoverageColumns}, {"rows", kCoverageRows}, {"views_per_cell", map.views},
                   {"covered_fraction", map.covered_fraction}, {"border_fraction", map.border_fraction}};
  json w = json::array();
  for (const CalibrationWarning& x : warnings) w.push_back({{"name", x.name}, {"advice", x.advice}});
  j["warnings"] = w;
  return j;
}

DotGridSpec specFromArgs(const Args& args, const Settings& settings) {
  const std::string kindArg = args.valueOr("pattern", "thesis");
  const auto kind = parseDotGridKind(kindArg);
  if (!kind) throw UsageError("--pattern: \"" + kindArg + "\" is not thesis, symmetric-circles or asymmetric-circles");
  DotGridSpec spec;
  spec.kind = *kind;
  if (*kind == DotGridKind::Thesis) {
    // The settings' pattern unless the command line says otherwise.
    spec.columns = settings.pattern.columns;
    spec.rows = settings.pattern.rows;
    spec.spacing_mm = settings.pattern.spot_spacing_mm;
    spec.dot_diameter_mm = 2.0 * settings.pattern.spot_radius_mm;
    spec.card_size_mm = settings.pattern.card_size_mm;
    spec.target = settings.target;
  } else {
    for (const char* required : {"columns", "rows", "spacing-mm"})
      if (!args.has(required))
        throw UsageError(std::string("--") + required + " is required for --pattern " + kindArg);
    spec.dot_diameter_mm = 0.0;
  }
  spec.columns = args.integer("columns", spec.columns);
  spec.rows = args.integer("rows", spec.rows);
  spec.spacing_mm = args.number("spacing-mm", spec.spacing_mm);
  spec.dot_diameter_mm = args.number("dot-diameter-mm", spec.dot_diameter_mm);
  if (const std::string e = dotGridSpecError(spec); !e.empty())
    throw UsageError("InvalidPattern: " + e);
  return spec;
}

}  // namespace

const char* const kIntrinsicCalibrationUsage =
    "usage: imagepro-cli calibrate --intrinsics --pattern thesis|symmetric-circles|asymmetric-circles\n"
    "         --columns C --rows R --spacing-mm S [--dot-diameter-mm D] IMAGES... --out FILE\n"
    "         [--format text|json] [--fit-k3] [--export-opencv FILE.yaml|FILE.json] [--coverage FILE.png]\n"
    "         [--config FILE] [--source file|camera|virtual]\n\n"
    "Full intrinsic calibration from 3 or more images (4-10 best) of a printed dot grid\n"
    "(imagepro-cli pattern): focal lengths fx, fy (d0 for the settings' pixel size, and the\n"
    "pixel aspect), principal point, k1, k2, p1, p2 (k3 with --fit-k3). OpenCV's conventions:\n"
    "C x R is points per row x rows; asymmetric dot (i, j) at ((2j + i mod 2) s, i s). The\n"
    "thesis pattern takes its size from the settings unless given, and may be partly in view.\n"
    "Take the views tilted 30-50 deg about different axes, the pattern near every edge and\n"
    "corner once. Prints each image's dots, reprojection RMS and tilt, each parameter with its\n"
    "standard deviation, a coverage map of where the dots fell, and named warnings saying what\n"
    "to do (PoorCoverage, PoorBorderCoverage, NarrowViewAngles, OneTiltAxis, FewViews,\n"
    "HighReprojectionError, UncertainFocalLength).\n"
    "  --out FILE            the source's camera with the result (the settings' cameras section\n"
    "                        with --source's only, default file; atomically; an existing FILE\n"
    "                        is kept as FILE.bak)\n"
    "  --format json         one object {status, fx_px, fy_px, cx_px, cy_px, k1, k2, p1, p2,\n"
    "                        opencv_dist, rms_px, images_used, per_image, std_dev, coverage,\n"
    "                        warnings, ...}\n"
    "  --export-opencv FILE  also OpenCV's camera file (camera_matrix, distortion_coefficients,\n"
    "                        image_width, image_height); JSON for .json, else YAML\n"
    "  --coverage FILE.png   the coverage map as a picture\n"
    "Exit code 1 when the calibration fails (its error is named: TooFewViews, ...), 2 for a\n"
    "usage error (a bad pattern description is InvalidPattern).";

int runIntrinsicCalibration(const Args& args) {
  args.rejectUnknown({"intrinsics", "out", "format", "pattern", "columns", "rows", "spacing-mm", "dot-diameter-mm",
                      "fit-k3", "export-opencv", "coverage", "config", "source"});
  const std::string format = args.valueOr("format", "text");
  if (format != "text" && format != "json") throw UsageError("--format: \"" + format + "\" is not text or json");
  const auto out = args.value("out");
  if (!out) throw UsageError("--out FILE is required (the camera section of the settings is written there)");
  if (args.positionals().empty()) throw UsageError("no images given (3 or more images of the pattern)");
  Settings settings = loadConfig(args);
  settings.source = enumOption(args, "source", SourceKind::File);
  const DotGridSpec spec = specFromArgs(args, settings);
  const bool text = format == "text";

  const std::vector<ImageInput> inputs = expandImageInputs(args.positionals());
  std::vector<cv::Mat> images;
  std::vector<std::string> names;
  for (const ImageInput& input : inputs) {
    cv::Mat grey;
    std::string error = input.error;
    if (!ok(input.status) || !ok(readGreyImageQuietly(input.path, grey, error))) {
      std::fprintf(stderr, "%s (skipped)\n", error.c_str());
      continue;
    }
    images.push_back(grey);
    names.push_back(input.path);
  }
  if (images.empty()) throw InputError("none of the images can be used");

  IntrinsicsOptions options;
  options.fit_k3 = args.has("fit-k3");
  IntrinsicsResult r;
  const Status status = calibrateIntrinsics(images, spec, options, r);
  const CoverageMap map = coverageMap(r);
  const std::vector<CalibrationWarning> warnings = intrinsicsWarnings(r, map);
  CameraModel camera = settings.camera();
  if (ok(status)) applyIntrinsics(r, camera);

  if (text) {
    std::printf("%s grid, %d x %d, spacing %g mm, dots %g mm; %zu image(s)\n",
                std::string(dotGridKindName(spec.kind)).c_str(), spec.columns, spec.rows, spec.spacing_mm,
                dotDiameterMm(spec), images.size());
    for (size_t i = 0; i < r.views.size(); ++i) {
      const IntrinsicsView& v = r.views[i];
      if (ok(v.status))
        std::printf("%s: %d dots%s, reprojection %.3f px RMS, tilted %.0f deg\n", names[i].c_str(), v.dots,
                    v.partial ? " (part of the grid)" : "", v.rms_px, v.tilt_deg);
      else
        std::printf("%s: %s: %s (skipped)\n", names[i].c_str(), std::string(statusName(v.status)).c_str(),
                    std::string(statusMessage(v.status)).c_str());
    }
  } else {
    std::printf("%s\n", resultJson(r, names, map, warnings, camera).dump().c_str());
  }
  if (!ok(status))
    throw InputError("calibration failed: " + std::string(statusName(status)) + ": " +
                     std::string(statusMessage(status)));
  if (text) {
    const IntrinsicsDeviations& d = r.deviation;
    std::printf("fx %.3f +- %.3f px, fy %.3f +- %.3f px (aspect fx/fy %.5f)\n", r.fx, d.fx, r.fy, d.fy, r.fx / r.fy);
    std::printf("principal point %.3f +- %.3f, %.3f +- %.3f px\n", r.cx, d.cx, r.cy, d.cy);
    std::printf("OpenCV distortion k1 %.5f +- %.5f, k2 %.5f +- %.5f, p1 %.6f +- %.6f, p2 %.6f +- %.6f, k3 %.5f +- "
                "%.5f\n",
                r.opencv_dist[0], d.k1, r.opencv_dist[1], d.k2, r.opencv_dist[2], d.p1, r.opencv_dist[3], d.p2,
                r.opencv_dist[4], d.k3);
    std::printf("this project's model (eq. 4.7): k1 %.4e  k2 %.4e  p1 %.4e  p2 %.4e (fit to OpenCV's field %.4f px "
                "RMS)\n",
                r.distortion.k1, r.distortion.k2, r.distortion.p1, r.distortion.p2, r.model_fit_rms_px);
    std::printf("d0 %.4f mm for %g mm pixels (sy %.6g mm)\n", camera.image_plane_distance_mm, camera.pixel_size_mm[0],
                camera.pixel_size_mm[1]);
    std::printf("reprojection %.4f px RMS over %d images\n", r.rms_px, r.views_used);
    std::printf("coverage (views with dots per cell; %.0f %% of cells, %.0f %% of the border):\n%s",
                100 * map.covered_fraction, 100 * map.border_fraction, coverageText(map).c_str());
    for (const CalibrationWarning& w : warnings) std::printf("warning %s: %s\n", w.name.c_str(), w.advice.c_str());
  } else {
    for (const CalibrationWarning& w : warnings)
      std::fprintf(stderr, "warning %s: %s\n", w.name.c_str(), w.advice.c_str());
  }

  std::string error;
  if (const auto coverage = args.value("coverage")) {
    std::vector<unsigned char> png;
    if (!cv::imencode(".png", coverageImage(r, map), png) ||
        !writeFileAtomically(*coverage, std::string(png.begin(), png.end()), error))
      throw InputError(error.empty() ? *coverage + ": cannot be written" : error);
    if (text) std::printf("wrote %s\n", coverage->c_str());
  }
  if (const auto exportPath = args.value("export-opencv")) {
    if (!writeOpenCvCamera(*exportPath, openCvCameraOf(r), error)) throw InputError(error);
    if (text) std::printf("wrote %s\n", exportPath->c_str());
  }
  settings.camera() = camera;
  if (!writeCalibrationFile(*out, settings, error)) throw InputError(error);
  if (text) std::printf("wrote %s\n", out->c_str());
  return 0;
}

}  // namespace imagepro::cli
