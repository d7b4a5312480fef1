// imagepro-cli threshold: the threshold of each image (thesis 2.3) by the chosen
// method, one row per image; an unreadable image gets its row and a line on stderr,
// the rest go on, and the exit status says that one failed.
#include <cstdio>

#include "cli/command.h"
#include "cli/enum_options.h"
#include "cli/option_ranges.h"
#include "cli/image_inputs.h"
#include "core/common/pose_csv.h"
#include "core/pipeline/stage_chain.h"
#include "core/settings/enum_names.h"

namespace imagepro::cli {
namespace {

// "none" (the re-thresholding's by-pass) gives no threshold to print.
bool namesAThreshold(ThresholdMethod m) { return m != ThresholdMethod::None; }

ThresholdOptions chosenOptions(const Args& args, const Settings& settings) {
  ThresholdOptions o = settings.pipeline.threshold;
  if (args.has("method")) o.method = enumOption(args, "method", o.method, namesAThreshold);
  if (args.has("value")) {
    if (args.has("method") && o.method != ThresholdMethod::Manual)
      throw UsageError("--value applies to --method manual only");
    o.method = ThresholdMethod::Manual;
    o.manual_value = args.integer("value", o.manual_value);
    const SettingKey* range = findSettingKey("pipeline.threshold.value");
    if (range && (o.manual_value < range->lo || o.manual_value > range->hi))
      throw UsageError("--value must be " + rangeText(range->path));
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
  Settings settings = loadConfig(args);
  settings.source = SourceKind::File;  // images: the File source's camera
  settings.pipeline.threshold = chosenOptions(args, settings);
  settings.pipeline.level = ApplicationLevel::Threshold;

  const bool csv = format == "csv";
  if (csv) std::printf("image,status,threshold\n");
  cv::Mat grey;
  StageChain chain;
  FrameResult result;
  bool unreadable = false;
  for (const ImageInput& input : expandImageInputs(args.positionals())) {
    int t = 0;
    std::string problem = input.error;
    Status status = input.status;
    if (ok(status)) status = readGreyImageQuietly(input.path, grey, problem);
    const bool loaded = ok(status);
    if (loaded) {
      runStageChain(settings, grey, {}, TargetsToReconstruct::Best, chain, result);
      status = result.status;
      t = result.threshold;
      problem = statusMessage(status);
    } else {
      unreadable = true;
      std::fflush(stdout);
      std::fprintf(stderr, "imagepro-cli threshold: %s: %s\n", std::string(statusName(status)).c_str(), problem.c_str());
    }
    const std::string name(statusName(status));
    if (csv) {
      std::printf("%s,%s,%s\n", csvField(input.path).c_str(), name.c_str(), ok(status) ? std::to_string(t).c_str() : "");
    } else if (ok(status)) {
      std::printf("%s: %d\n", input.path.c_str(), t);
    } else if (loaded) {
      std::printf("%s: %s (%s)\n", input.path.c_str(), name.c_str(), problem.c_str());
    } else {
      std::printf("%s: %s\n", input.path.c_str(), name.c_str());  // the reason is on stderr
    }
  }
  return unreadable ? 1 : 0;
}

const CommandRegistration kRegistration{{
    "threshold",
    "print the threshold of each image by the chosen method (thesis 2.3)",
    "usage: imagepro-cli threshold [--config FILE] [--method M] [--value N] [--format F] IMAGES...\n\n"
    "Prints the threshold t of each image (thesis 2.3); binarization makes the pixels\n"
    "above t white (eq. 2.1). at-orig and at-mod give the same t at different speed.\n"
    "IMAGES are image files, folders (their images in natural order) or text files listing paths.\n"
    "  --method M   the threshold method (default: the settings' threshold.method):\n" +
    choicesHelp<ThresholdMethod>(namesAThreshold) +
    "  --value N    the manual threshold, " + rangeText("pipeline.threshold.value") +
    "; selects manual when --method is not given\n"
    "  --format F   text (default): \"IMAGE: t\", or the error's name (and what it means);\n"
    "               csv: image,status,threshold with status ok or the error's name and\n"
    "               the threshold empty unless ok\n"
    "Every image gets its row. One that cannot be read (missing, corrupt, a folder or\n"
    "list without images) also gets one line on stderr naming it and the reason, the\n"
    "others are still processed, and the exit status is 1. An image without a threshold\n"
    "(e.g. a flat one) is a result, reported in its row only. Exit status 2: a wrong\n"
    "command line; 1: wrong settings or an image that could not be read; else 0.",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
