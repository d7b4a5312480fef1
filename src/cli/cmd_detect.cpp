// imagepro-cli detect: the ellipse detection stage on image files (thesis 2.6): each
// image is thresholded, its edges detected and grouped into paths, and the target's
// ellipse chosen; one row per image (per target with report_all_targets).
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "cli/bennett_accumulators.h"
#include "cli/command.h"
#include "cli/enum_options.h"
#include "cli/image_inputs.h"
#include "core/common/pose_csv.h"
#include "core/ellipse/detect.h"
#include "core/pipeline/stage_chain.h"
#include "core/settings/enum_names.h"

namespace imagepro::cli {
namespace {

// Everything one image goes through, reused from image to image.
struct Stage {
  cv::Mat grey;
  StageChain chain;
  FrameResult result;
  std::vector<TargetDetection> ellipses;
};

// The stage chain up to the ellipse stage, on the whole image.
Status detectImage(const Settings& s, const std::string& file, Stage& st, std::string& problem) {
  st.chain.detections.clear();
  st.chain.paths.clear();
  const Status status = readGreyImageQuietly(file, st.grey, problem);
  if (!ok(status)) return status;
  runStageChain(s, st.grey, {}, TargetsToReconstruct::Best, st.chain, st.result);
  return st.result.status;
}

double fitError(const EllipseOptions& o, const TargetDetection& d) {
  return o.accept_rule == FitAcceptRule::RelativeError ? d.fit_error : d.sampson_px;
}

// The grey image in colour: every accepted ellipse thin in yellow, the target thick in
// green (red when ambiguous) with its spots' paths in blue and its fit error x 1000 at
// the centre (thesis fig. 2.26).
void drawOverlay(const Settings& s, Stage& st, Status status, cv::Mat& out) {
  cv::cvtColor(st.grey, out, cv::COLOR_GRAY2BGR);
  if (st.chain.paths.pathCount() > 0) detectEllipses(s.pipeline.ellipse, st.chain.paths, st.grey.size(), st.chain.ellipse_ws, st.ellipses);
  else st.ellipses.clear();
  auto draw = [&](const Ellipse& e, const cv::Scalar& colour, int thickness) {
    cv::ellipse(out, cv::RotatedRect(cv::Point2f(float(e.cx), float(e.cy)), cv::Size2f(float(2 * e.a), float(2 * e.b)),
                                     float(e.angle_deg)),
                colour, thickness, cv::LINE_AA);
  };
  for (const auto& e : st.ellipses) draw(e.ellipse, cv::Scalar(0, 220, 220), 1);
  if (status != Status::Ok && status != Status::AmbiguousTarget) return;
  for (const auto& d : st.chain.detections) {
    for (std::size_t spot : d.spot_paths) {
      if (spot == kNoPath) continue;
      for (const auto& p : st.chain.paths.path(spot)) out.at<cv::Vec3b>(p.y, p.x) = cv::Vec3b(255, 80, 0);
    }
    draw(d.ellipse, status == Status::Ok ? cv::Scalar(0, 200, 0) : cv::Scalar(0, 0, 255), 2);
    char label[32];
    std::snprintf(label, sizeof label, "%.0f", 1000.0 * fitError(s.pipeline.ellipse, d));
    cv::putText(out, label, cv::Point(int(d.ellipse.cx) - 8, int(d.ellipse.cy) + 4), cv::FONT_HERSHEY_SIMPLEX, 0.4,
                cv::Scalar(0, 200, 0), 1, cv::LINE_AA);
  }
}

void writePicture(const std::string& option, const std::filesystem::path& out, const cv::Mat& picture) {
  bool written = false;
  try {
    written = cv::imwrite(out.string(), picture);
  } catch (const cv::Exception&) {
    written = false;
  }
  if (!written) throw InputError("--" + option + ": cannot write \"" + out.string() + "\"");
}

// The accumulator pictures of one image: <name>_accumulator.png and <name>_path<N>.png.
void writeAccumulators(const Settings& s, Stage& st, const std::filesystem::path& dir, const std::string& name,
                       BennettAccumulators& acc) {
  drawBennettAccumulators(s.pipeline.ellipse, st.chain.paths, st.grey.size(), st.chain.ellipse_ws, acc);
  writePicture("accumulators", dir / (name + "_accumulator.png"), acc.all);
  for (const PathAccumulator& p : acc.shown)
    writePicture("accumulators", dir / (name + "_path" + std::to_string(p.path) + ".png"), p.image);
}

int run(const Args& args) {
  args.rejectUnknown({"format", "overlay", "method", "accumulators"});
  const std::string format = args.valueOr("format", "csv");
  if (format != "text" && format != "csv") throw UsageError("--format: \"" + format + "\" is not text or csv");
  if (args.positionals().empty()) throw UsageError("no images given");
  Settings settings = loadConfig(args);
  settings.source = SourceKind::File;  // images: the File source's camera
  settings.pipeline.level = ApplicationLevel::Ellipse;
  settings.pipeline.ellipse.method = enumOption(args, "method", settings.pipeline.ellipse.method);
  if (settings.pipeline.threshold.method == ThresholdMethod::None)
    throw InputError("the settings' threshold method \"none\" names no threshold");
  std::optional<std::filesystem::path> overlayDir, accumulatorDir;
  if (const auto dir = args.value("overlay")) overlayDir = outputFolder("overlay", *dir);
  if (const auto dir = args.value("accumulators")) accumulatorDir = outputFolder("accumulators", *dir);
  const EllipseOptions& eo = settings.pipeline.ellipse;
  const std::string method(enumName(eo.method));
  const bool csv = format == "csv";
  if (csv) std::printf("frame,status,cx,cy,a,b,angle_deg,fit_error,method,bennett_score,bennett_quality,bennett_symmetry_px\n");
  Stage st;
  cv::Mat overlay;
  BennettAccumulators accumulators;
  UniqueNames overlayNames, accumulatorNames;
  for (const ImageInput& input : expandImageInputs(args.positionals())) {
    const std::string& file = input.path;
    std::string problem = input.error;
    if (!ok(input.status)) st.grey.release();
    const Status status = ok(input.status) ? detectImage(settings, file, st, problem) : input.status;
    const std::string name(statusName(status));
    const bool found = status == Status::Ok || status == Status::AmbiguousTarget;
    if (st.grey.empty()) {  // not read: the reason on stderr too, as the other commands give it
      std::fflush(stdout);
      std::fprintf(stderr, "imagepro-cli detect: %s: %s\n", name.c_str(),
                   problem.empty() ? std::string(statusMessage(status)).c_str() : problem.c_str());
    }
    if (!found) {
      if (csv) std::printf("%s,%s,,,,,,,%s,,,\n", csvField(file).c_str(), name.c_str(), method.c_str());
      else std::printf("%s: %s (%s)\n", file.c_str(), name.c_str(), problem.empty() ? std::string(statusMessage(status)).c_str() : problem.c_str());
    }
    for (const auto& d : found ? st.chain.detections : std::vector<TargetDetection>{}) {
      const Ellipse& e = d.ellipse;
      if (csv) {
        std::printf("%s,%s,%.3f,%.3f,%.3f,%.3f,%.2f,%.6g,%s", csvField(file).c_str(), name.c_str(), e.cx, e.cy, e.a,
                    e.b, e.angle_deg, fitError(eo, d), method.c_str());
        // Bennett's accumulator at the peak (thesis 2.6.1): empty for the direct fit.
        if (eo.method == EllipseMethod::Bennett)
          std::printf(",%.6g,%.6g,%.2f\n", d.bennett_score, d.bennett_quality, d.bennett_symmetry);
        else
          std::printf(",,,\n");
      } else {
        std::printf("%s: %s centre (%.2f, %.2f) semi-axes %.2f x %.2f angle %.1f deg, %s %.4g%s%s\n", file.c_str(),
                    name.c_str(), e.cx, e.cy, e.a, e.b, e.angle_deg,
                    eo.accept_rule == FitAcceptRule::RelativeError ? "E_rel" : "Sampson px", fitError(eo, d),
                    d.spots_found ? ", spots found" : ", no spots", d.robust ? " (consensus fit)" : "");
      }
    }
    if (overlayDir && !st.grey.empty()) {
      drawOverlay(settings, st, status, overlay);
      writePicture("overlay", *overlayDir / (overlayNames.take(std::filesystem::path(file).stem().string()) + ".png"),
                   overlay);
    }
    if (accumulatorDir && !st.grey.empty())
      writeAccumulators(settings, st, *accumulatorDir, accumulatorNames.take(std::filesystem::path(file).stem().string()),
                        accumulators);
  }
  return 0;
}

const CommandRegistration kRegistration{{
    "detect",
    "find the target's ellipse in each image (thesis 2.6)",
    "usage: imagepro-cli detect [--config FILE] [--method M] [--format F] [--overlay DIR]\n"
    "                           [--accumulators DIR] IMAGES...\n\n"
    "Thresholds each image, detects its edges, groups them into connected paths and\n"
    "finds the target's ellipse (the settings' pipeline.threshold, edge_method,\n"
    "connectivity and ellipse). The target is the accepted ellipse that holds the\n"
    "target's two spots; without one, the best ellipse (lowest fit error, or highest\n"
    "Bennett score) unless ellipse.require_target_spots. IMAGES are image files,\n"
    "folders (their images in natural order) or text files listing paths.\n"
    "  --method M    the ellipse detection method (default: the settings' ellipse.method):\n" +
    choicesHelp<EllipseMethod>() +
    "  --format F    csv (default): frame,status,cx,cy,a,b,angle_deg,fit_error,method,\n"
    "                bennett_score,bennett_quality,bennett_symmetry_px with status ok,\n"
    "                AmbiguousTarget (one row per target) or the error's name and the\n"
    "                ellipse columns empty; text: one line each\n"
    "  --overlay DIR write DIR/<name>.png for every image read: accepted ellipses in\n"
    "                yellow, the target in green (red when ambiguous), its spots in\n"
    "                blue. <name> is the image's file name without extension, with\n"
    "                _2, _3 ... added when an earlier image of the run had the same\n"
    "                name (e.g. from another folder), so no overlay replaces another\n"
    "  --accumulators DIR  write Bennett's accumulators (thesis figs. 2.17-2.23), with\n"
    "                any --method, for every image read: DIR/<name>_accumulator.png,\n"
    "                image-sized 8-bit grey, every path's accumulator over its box\n"
    "                scaled to its own peak; and DIR/<name>_path<N>.png for each path N\n"
    "                Bennett accepts (or, accepting none, the one of highest score):\n"
    "                its accumulator enlarged, the peak's centre in red, the circle of\n"
    "                half the peak's mean score in blue (the quality factor's radius)\n"
    "                and the radius where symmetry vanishes, if inside, in orange\n"
    "cx, cy, a, b: centre and semi-axes in pixels; angle_deg: major axis from +u\n"
    "towards +v; fit_error: E_rel (eq. 2.42) or the mean Sampson distance in pixels,\n"
    "as the settings' ellipse.accept_rule; bennett_*: with --method bennett, the path's\n"
    "accumulator score, quality factor and symmetry radius (thesis 2.6.1), else empty. An image that cannot be read (missing,\n"
    "corrupt, a folder or list without images) is reported in its row (FileNotFound,\n"
    "FileUnreadable) and named with the reason on stderr, and the others are still\n"
    "processed; the exit status is 0 unless\n"
    "the command line, the settings or --overlay is wrong.",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
