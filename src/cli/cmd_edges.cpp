// imagepro-cli edges: thresholds each image, detects its edges and groups them into
// connected paths (thesis 2.3-2.5); writes the binary, edge and path images for
// inspection and prints one CSV row per image. An image that cannot be read or
// written is named on stderr too, and the exit status is 1.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "cli/command.h"
#include "cli/enum_options.h"
#include "cli/image_inputs.h"
#include "core/common/pose_csv.h"
#include "core/pipeline/stage_chain.h"
#include "core/settings/enum_names.h"

namespace imagepro::cli {
namespace {

// Each path a distinct colour on black: hues a golden-ratio step apart, so paths
// next to each other in the list (often next to each other in the image) differ.
void drawPaths(const Paths& paths, cv::Size size, cv::Mat& out) {
  out.create(size, CV_8UC3);
  out.setTo(cv::Scalar::all(0));
  if (paths.pathCount() == 0) return;
  cv::Mat hsv(1, static_cast<int>(paths.pathCount()), CV_8UC3);
  for (std::size_t i = 0; i < paths.pathCount(); ++i) {
    const double hue = std::fmod(0.618033988749895 * static_cast<double>(i), 1.0) * 180.0;
    hsv.at<cv::Vec3b>(0, static_cast<int>(i)) =
        cv::Vec3b(static_cast<std::uint8_t>(hue), i % 3 == 2 ? 160 : 255, i % 2 ? 200 : 255);
  }
  cv::Mat bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  for (std::size_t i = 0; i < paths.pathCount(); ++i)
    for (const auto& p : paths.path(i)) out.at<cv::Vec3b>(p.y, p.x) = bgr.at<cv::Vec3b>(0, static_cast<int>(i));
}

bool writePng(const std::filesystem::path& file, const cv::Mat& image) {
  try {
    return cv::imwrite(file.string(), image);
  } catch (const cv::Exception&) {
    return false;
  }
}

struct Row {
  Status status = Status::Ok;
  std::string threshold, edgePixels, paths, longestPath;  // empty until the stage ran
};

int run(const Args& args) {
  args.rejectUnknown({"out", "method", "connectivity"});
  if (args.positionals().empty()) throw UsageError("no images given");
  Settings settings = loadConfig(args);
  settings.source = SourceKind::File;  // images: the File source's camera
  settings.pipeline.edge_method = enumOption(args, "method", settings.pipeline.edge_method);
  settings.pipeline.connectivity = enumOption(args, "connectivity", settings.pipeline.connectivity);
  settings.pipeline.level = ApplicationLevel::Connectivity;
  if (settings.pipeline.threshold.method == ThresholdMethod::None)
    throw InputError("the settings' threshold method \"none\" names no threshold");

  std::optional<std::filesystem::path> outDir;
  if (const auto dir = args.value("out")) outDir = outputFolder("out", *dir);

  std::printf("frame,status,threshold,edge_pixels,paths,longest_path\n");
  cv::Mat grey, edgeImage, pathImage;
  StageChain chain;
  FrameResult result;
  const cv::Mat& binary = chain.binary;
  const EdgeList& edges = chain.edges;
  const Paths& paths = chain.paths;
  UniqueNames outNames;
  bool failed = false;
  for (const ImageInput& input : expandImageInputs(args.positionals())) {
    const std::string& file = input.path;
    Row row;
    std::string error = input.error;
    bool binaryReady = false;
    row.status = ok(input.status) ? readGreyImageQuietly(file, grey, error) : input.status;
    if (!ok(row.status)) {
      failed = true;
      std::fflush(stdout);
      std::fprintf(stderr, "imagepro-cli edges: %s: %s\n", std::string(statusName(row.status)).c_str(), error.c_str());
    } else {
      runStageChain(settings, grey, {}, TargetsToReconstruct::Best, chain, result);
      row.status = result.status;
      binaryReady = stageRan(result, ApplicationLevel::Edges);  // edges run whenever the threshold is found
      if (binaryReady) {
        std::size_t longest = 0;
        for (std::size_t i = 0; i < paths.pathCount(); ++i) longest = std::max(longest, paths.path(i).size());
        row.threshold = std::to_string(result.threshold);
        row.edgePixels = std::to_string(edges.size());
        row.paths = std::to_string(paths.pathCount());
        row.longestPath = std::to_string(longest);
      }
    }
    if (outDir && binaryReady) {
      const std::string stem = outNames.take(std::filesystem::path(file).stem().string());
      bool written = writePng(*outDir / (stem + "_binary.png"), binary);
      edgeImage.create(binary.size(), CV_8UC1);
      edgeImage.setTo(0);
      for (const auto& p : edges) edgeImage.at<std::uint8_t>(p.y, p.x) = 255;
      drawPaths(paths, binary.size(), pathImage);
      written = writePng(*outDir / (stem + "_edges.png"), edgeImage) && written;
      written = writePng(*outDir / (stem + "_paths.png"), pathImage) && written;
      if (!written) {
        failed = true;
        if (ok(row.status) || row.status == Status::NoEdges) row.status = Status::FileNotWritable;
        std::fflush(stdout);
        std::fprintf(stderr, "imagepro-cli edges: FileNotWritable: %s: cannot write %s_*.png into %s\n", file.c_str(),
                     stem.c_str(), outDir->string().c_str());
      }
    }
    std::printf("%s,%s,%s,%s,%s,%s\n", csvField(file).c_str(), std::string(statusName(row.status)).c_str(),
                row.threshold.c_str(), row.edgePixels.c_str(), row.paths.c_str(), row.longestPath.c_str());
  }
  return failed ? 1 : 0;
}

const CommandRegistration kRegistration{{
    "edges",
    "threshold, edge-detect and connect each image; write PNGs and a CSV summary",
    "usage: imagepro-cli edges [--config FILE] [--out DIR] [--method M] [--connectivity C] IMAGES...\n\n"
    "For each image: the threshold of the settings (thesis 2.3), binarization (eq. 2.1),\n"
    "edge detection (2.4) and connectivity analysis (2.5). IMAGES are image files,\n"
    "folders (their images in natural order) or text files listing paths. Prints one CSV row\n"
    "per image:\n"
    "  frame,status,threshold,edge_pixels,paths,longest_path\n"
    "status is ok or the error's name; a column is empty when its stage did not run\n"
    "(an unreadable file, no threshold). NoEdges rows carry 0 edge pixels and paths.\n"
    "  --out DIR         also write <name>_binary.png, <name>_edges.png (edge pixels white\n"
    "                    on black) and <name>_paths.png (each connected path its own colour\n"
    "                    on black) into DIR, created if missing; <name> is the image's file\n"
    "                    name without extension, with _2, _3 ... added when an earlier image\n"
    "                    of the run had the same name (e.g. from another folder).\n"
    "  --method M        the edge detection method (default: the settings' edge_method):\n" +
    choicesHelp<EdgeMethod>() +
    "  --connectivity C  the connectivity analysis (default: the settings' connectivity):\n" +
    choicesHelp<ConnectivityMethod>() +
    "An image that cannot be read (missing, corrupt, a folder or list without images)\n"
    "or whose PNGs cannot be written also gets one line on stderr naming it and the\n"
    "reason (status FileNotWritable for a failed write); the others are still processed\n"
    "and the exit status is 1. Exit status 2: a wrong command line; 1: wrong settings,\n"
    "--out not creatable, or such a failed image; else 0 (an image without a threshold\n"
    "or without edges is a result, reported in its row).",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
