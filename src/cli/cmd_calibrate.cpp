// imagepro-cli calibrate: lens distortion from one to four images of the calibration
// pattern (thesis 4.6, calibration/calibrate.h). Prints every iteration's parameters and
// the final RMS residual, and writes the camera section of the settings JSON with the
// distortion found (atomically; a file already there is kept as FILE.bak).
#include <nlohmann/json.hpp>

#include <cstdio>
#include <string>
#include <vector>

#include "cli/cmd_calibrate_intrinsics.h"
#include "cli/command.h"
#include "cli/enum_options.h"
#include "cli/image_inputs.h"
#include "core/calibration/calibrate.h"
#include "core/calibration/calibration_file.h"

namespace imagepro::cli {
namespace {

using json = nlohmann::ordered_json;

constexpr size_t kMaxImages = 4;

json resultJson(const CalibrationResult& r) {
  json j;
  j["status"] = std::string(statusName(r.status));
  j["k1"] = r.distortion.k1;
  j["k2"] = r.distortion.k2;
  j["p1"] = r.distortion.p1;
  j["p2"] = r.distortion.p2;
  j["iterations"] = r.iterations;
  j["rms_residual_px"] = r.rms_residual_px;
  j["coverage_radius_fraction"] = r.coverage_radius_fraction;
  return j;
}

int run(const Args& args) {
  if (args.has("intrinsics")) return runIntrinsicCalibration(args);
  args.rejectUnknown({"out", "format", "source"});
  const std::string format = args.valueOr("format", "text");
  if (format != "text" && format != "json") throw UsageError("--format: \"" + format + "\" is not text or json");
  const auto out = args.value("out");
  if (!out) throw UsageError("--out FILE is required (the camera section of the settings is written there)");
  if (args.positionals().empty()) throw UsageError("no images given (one to four images of the pattern)");
  // Folders and list files stand for their images, as in every other command.
  const std::vector<ImageInput> inputs = expandImageInputs(args.positionals());
  if (inputs.size() > kMaxImages)
    throw UsageError("at most four images (thesis 4.6: one to four views of the pattern), " +
                     std::to_string(inputs.size()) + " given");
  Settings settings = loadConfig(args);
  settings.source = enumOption(args, "source", SourceKind::File);
  const bool text = format == "text";

  // Unreadable files and images of another size than the camera's are reported and left
  // out; the others may still suffice.
  std::vector<cv::Mat> images;
  std::vector<std::string> names;
  for (const ImageInput& input : inputs) {
    const std::string& path = input.path;
    cv::Mat grey;
    std::string error = input.error;
    if (!ok(input.status) || !ok(readGreyImageQuietly(path, grey, error))) {
      std::fprintf(stderr, "%s (skipped)\n", error.c_str());
      continue;
    }
    if (grey.cols != settings.camera().width || grey.rows != settings.camera().height) {
      std::fprintf(stderr, "%s: %dx%d, but the settings' camera is %dx%d (skipped)\n", path.c_str(), grey.cols,
                   grey.rows, settings.camera().width, settings.camera().height);
      continue;
    }
    images.push_back(grey);
    names.push_back(path);
  }
  if (images.empty()) throw InputError("none of the images can be used");

  if (text)
    std::printf("calibrating from %zu image(s); pattern spots %g mm apart, %d x %d grid\n", images.size(),
                settings.pattern.spot_spacing_mm, settings.pattern.columns, settings.pattern.rows);
  CalibrationResult result;
  const IterationCallback show = [&](const CalibrationIteration& it) {
    if (!text) return;
    std::printf("iteration %d: k1 %.4e  k2 %.4e  p1 %.4e  p2 %.4e  change %.4f  residual %.4f px  %d spots in %d "
                "image(s)\n",
                it.iteration, it.distortion.k1, it.distortion.k2, it.distortion.p1, it.distortion.p2,
                it.relative_change, it.rms_residual_px, it.matches, it.images_used);
    std::fflush(stdout);
  };
  const Status status = calibrateDistortion(settings, images, result, show);

  for (size_t i = 0; i < result.images.size(); ++i) {
    const CalibrationImageReport& im = result.images[i];
    if (ok(im.status)) {
      if (text)
        std::printf("%s: %d of %d spots matched (%d ambiguous), pattern at Rx %.2f Ry %.2f Rz %.2f deg, Tz %.1f mm\n",
                    names[i].c_str(), im.match.matched, im.spots_expected, im.match.ambiguous, im.pose.rx_deg,
                    im.pose.ry_deg, im.pose.rz_deg, im.pose.tz_mm);
    } else {
      std::fprintf(text ? stdout : stderr, "%s: %s: %s (skipped)\n", names[i].c_str(),
                   std::string(statusName(im.status)).c_str(), std::string(statusMessage(im.status)).c_str());
    }
  }
  if (text)
    std::printf("coverage: the matched spots reach %.0f %% of the way from the principal point to the farthest "
                "corner (at least %.0f %% needed)\n",
                100.0 * result.coverage_radius_fraction, 100.0 * kMinCoverageRadiusFraction);
  if (!text) std::printf("%s\n", resultJson(result).dump().c_str());
  if (!ok(status))
    throw InputError("calibration failed: " + std::string(statusName(status)) + ": " +
                     std::string(statusMessage(status)));

  if (text)
    std::printf("converged in %d iterations; RMS residual %.4f px\n", result.iterations, result.rms_residual_px);
  settings.camera().distortion = result.distortion;
  std::string error;
  if (!writeCalibrationFile(*out, settings, error)) throw InputError(error);
  if (text) std::printf("wrote %s\n", out->c_str());
  return 0;
}

const CommandRegistration kRegistration{{
    "calibrate",
    "lens distortion from the thesis's pattern (thesis 4.6), or --intrinsics from a dot grid",
    "usage: imagepro-cli calibrate IMAGES... --out FILE [--config FILE] [--source S] [--format text|json]\n\n"
    "IMAGES are image files, folders (their images in natural order) or lists of paths\n"
    "(text files, one path a line), one to four images in all.\n"
    "Finds k1, k2, p1, p2 of the distortion model (thesis eq. 4.7) from images of the\n"
    "calibration pattern (imagepro-cli pattern), best four: the pattern turned about +-45 deg\n"
    "about x and about y, its target near the image centre. Starts from zero distortion and\n"
    "iterates until every parameter changes by less than pipeline.calibration.relative_change.\n"
    "An image without target or pattern is reported and skipped when the others suffice.\n"
    "The camera, target and pattern come from the settings (--config).\n"
    "  --out FILE      write the source's camera with the distortion found (JSON: the settings'\n"
    "                  cameras section with that source only, atomically; an existing FILE is\n"
    "                  kept as FILE.bak)\n"
    "  --source S      the source whose camera took the images and gets the distortion: file\n"
    "                  (default), camera or virtual\n"
    "  --format F      text (default): every iteration and the RMS residual in px;\n"
    "                  json: one object {status, k1, k2, p1, p2, iterations, rms_residual_px,\n"
    "                  coverage_radius_fraction}\n"
    "An image that cannot be read or is not the camera's size is reported and skipped.\n"
    "The matched spots must reach far enough towards the image's corners, else PoorCoverage:\n"
    "move the pattern closer or print it larger (docs/calibration.md gives the distances).\n"
    "Exit code 1 when the calibration fails (its error is named), 2 for a usage error\n"
    "(e.g. more than four images).\n\n" + std::string(kIntrinsicCalibrationUsage),
    {"intrinsics", "fit-k3"},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
