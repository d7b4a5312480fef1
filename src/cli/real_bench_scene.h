#pragma once
// The bench's real-scene kind: the target moving over photographs (the core's real-scene
// videos, core/source/real_scene_video.h), in the bench scene's camera at any resolution.
// The sequence is cut into videos of kRealBenchVideoFrames frames, each over its own
// photograph (seeds 1, 2, ...), the target visible throughout; a cut is a loss of track.
#include <string>

#include "cli/engine_bench.h"

namespace imagepro::cli {

inline constexpr int kRealBenchVideoFrames = 50;

// `frames` frames at `size` over the photographs of `backgrounds` into `out` (kind Real, its
// redraw set). False with `error` when the folder holds none or one cannot be read.
bool renderRealBenchFrames(cv::Size size, int frames, const std::string& backgrounds, BenchSequence& out,
                           std::string& error);

}  // namespace imagepro::cli
