// imagepro-cli threshold: the threshold of each image (thesis 2.3) by the chosen
// method, one row per image; unreadable images get their error and the rest go on.
#include <cstdio>

#include "cli/command.h"
#include "core/common/pose_csv.h"
#include "core/segmentation/histogram.h"
#include "core/segmentation/threshold.h"
#include "core/settings/enum_names.h"
#include "core/source/image_file.h"

namespace imagepro::cli {
namespace {

ThresholdOptions chosenOptions(const Args& args, const Settings& settings) {
  ThresholdOptions o = settings.pipeline.threshold;
  if (const auto name = args.value("method")) {
    const auto method = parseEnum<ThresholdMethod>(*name);
    if (!method || *method == ThresholdMethod::None)
      throw UsageError("--method: \"" + *name + "\" is not one of manual, at-orig, at-mod");
    o.method = *method;
  }
  if (args.has("value")) {
    if (args.has("method") && o.method != ThresholdMethod::Manual)
      throw UsageError("--value applies to --method manual only");
    o.method = ThresholdMethod::Manual;
    o.manual_value = args.integer("value", o.manual_value);
    if (o.manual_value < 0 || o.manual_value > 255) throw UsageError("--value must be 0..255");
  }
  if (o.method == ThresholdMethod::None)
    throw InputError("the settings' threshold method \"none\" names no threshold; choose one with --method");
  return o;
}

int run(const Args& args) {
  args.rejectUnknown({"method", "value", "format"});
  const std::string format = args.valueOr("format", "text");
  if (format != "text" && format != "csv") throw UsageError("--format: \"" + format + "\" is not text or csv");
  if (args.positionals().empty()) throw UsageError("no images given");
  const ThresholdOptions options = chosenOptions(args, loadConfig(args));

  const bool csv = format == "csv";
  if (csv) std::printf("image,status,threshold\n");
  cv::Mat grey;
  Histogram hist;
  for (const auto& path : args.positionals()) {
    int t = 0;
    std::string problem;
    Status status = readGreyImage(path, grey, problem);
    if (ok(status)) {
      computeHistogram(grey, hist);
      status = computeThreshold(options, hist, t);
      problem = statusMessage(status);
    }
    const std::string value = ok(status) ? std::to_string(t) : std::string();
    if (csv) {
      std::printf("%s,%s,%s\n", csvField(path).c_str(), std::string(statusName(status)).c_str(), value.c_str());
    } else if (ok(status)) {
      std::printf("%s: %d\n", path.c_str(), t);
    } else {
      std::printf("%s: %s (%s)\n", path.c_str(), std::string(statusName(status)).c_str(), problem.c_str());
    }
  }
  return 0;
}

const CommandRegistration kRegistration{{
    "threshold",
    "print the threshold of each image (manual, at-orig or at-mod)",
    "usage: imagepro-cli threshold [--config FILE] [--method M] [--value N] [--format F] IMAGES...\n\n"
    "Prints the threshold t of each image (thesis 2.3); binarization makes the pixels\n"
    "above t white (eq. 2.1). at-orig and at-mod are Kittler and Illingworth's minimum\n"
    "error threshold in its original and incremental forms: the same t, different speed.\n"
    "  --method M   manual, at-orig or at-mod (default: the settings' threshold method)\n"
    "  --value N    the manual threshold, 0..255; selects manual when --method is not given\n"
    "  --format F   text (default): \"IMAGE: t\", or the error's name and what it means;\n"
    "               csv: image,status,threshold with status ok or the error's name and\n"
    "               the threshold empty unless ok\n"
    "An image that cannot be read or has no threshold (e.g. a flat image) is reported\n"
    "in its row and the other images are still processed; the exit status is 0 unless\n"
    "the command line or the settings are wrong.",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
