// Image decoding into the pipeline: bytes of any format go through the File source's
// reader (readGreyImage: PNG, JPEG, BMP, PGM, TIFF, with its truncation and size checks)
// and, when they decode, through the engine with tracking and through the reconstruction
// of every target that the two-target study uses.
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "core/analysis/multi_target.h"
#include "core/analysis/two_targets.h"
#include "core/common/status.h"
#include "core/pipeline/engine.h"
#include "core/settings/settings.h"
#include "core/source/image_file.h"
#include "fuzz_support.h"

using namespace imagepro;

namespace {
constexpr int kMaxSide = 160;  // the largest seed's width (corpus/image)
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::scratchFile("input.img", data, size);
  cv::Mat grey;
  std::string error;
  const Status s = readGreyImage(path, grey, error);
  if (s != Status::Ok) {
    if (!grey.empty()) fuzz::fail("a failed read leaves an image", error);
    if (error.empty()) fuzz::fail("a failed read names no reason", std::string(statusName(s)));
    return 0;
  }
  if (grey.type() != CV_8UC1 || grey.empty()) fuzz::fail("a read image is not 8-bit grey", error);
  // The pipeline's cost grows with the pixels and not its paths (none depends on the
  // size), so it sees at most the seeds' size: a noisy 512x512 image took 1.1 s in the
  // fuzz build, a 160x160 corner of it 90 ms. tools/fuzz.sh caps the decoder likewise.
  if (grey.cols > kMaxSide || grey.rows > kMaxSide)
    grey = grey(cv::Rect(0, 0, std::min(grey.cols, kMaxSide), std::min(grey.rows, kMaxSide))).clone();

  Settings settings;
  settings.camera().width = grey.cols;
  settings.camera().height = grey.rows;
  settings.camera().principal_point_px = {0.5 * (grey.cols - 1), 0.5 * (grey.rows - 1)};
  Engine engine(settings);
  Frame frame;
  frame.image = grey;
  FrameResult result;
  for (int i = 0; i < 2; ++i) {  // the second frame searches where the first was found
    frame.index = i;
    engine.process(frame, result);
  }

  MultiTargetWorkspace ws;
  MultiTargetResult all;
  reconstructAllTargets(settings, grey, ws, all);
  TwoTargetMeasurement between;
  measureTwoTargets(all, between);
  return 0;
}
