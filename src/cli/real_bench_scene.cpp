#include "cli/real_bench_scene.h"

#include <memory>
#include <vector>

#include "core/source/bench_scene.h"
#include "core/source/real_scene_video.h"

namespace imagepro::cli {

bool renderRealBenchFrames(cv::Size size, int frames, const std::string& backgrounds, BenchSequence& out,
                           std::string& error) {
  std::vector<std::string> photos = listBackgrounds(backgrounds);
  if (photos.empty()) {
    error = "no photographs in " + backgrounds;
    return false;
  }
  out = BenchSequence{};
  out.kind = BenchKind::Real;
  out.settings = benchSceneSettings(size);
  // Shared with `redraw`, which outlives this call.
  auto scenes = std::make_shared<const RealScenes>(out.settings, std::move(photos));
  auto videos = std::make_shared<std::vector<RealSceneVideo>>();
  for (int start = 0, seed = 1; start < frames; start += kRealBenchVideoFrames, ++seed)
    videos->emplace_back(*scenes, static_cast<std::uint64_t>(seed), kRealBenchVideoFrames, 0);
  out.redraw = [scenes, videos](int index, const ScenePainter& painter, RealSceneFrame& f, std::string& e) {
    const RealSceneVideo& video = (*videos)[static_cast<std::size_t>(index / kRealBenchVideoFrames)];
    return video.frame(index % kRealBenchVideoFrames, f, e, painter);
  };
  out.frames.reserve(static_cast<std::size_t>(frames));
  for (int i = 0; i < frames; ++i) {
    RealSceneFrame f;  // a fresh image each: the frame keeps it
    if (!out.redraw(i, {}, f, error)) return false;
    Frame frame;
    frame.image = f.image;
    frame.index = i;
    frame.timestamp_s = i / RealSceneVideo::kFrameRateHz;
    frame.truth = f.truth;
    out.frames.push_back(std::move(frame));
  }
  return true;
}

}  // namespace imagepro::cli
