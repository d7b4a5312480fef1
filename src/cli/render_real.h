#pragma once
// imagepro-cli render --scene real | video: real-scene frames (core/source/real_scene.h)
// as PNG files with their truth in truth.csv, through RenderOutput.
#include "cli/command.h"

namespace imagepro::cli {

// The options only real scenes take, and the virtual ones they refuse.
extern const std::vector<std::string> kRealSceneOptions;
extern const std::vector<std::string> kVirtualOnlyOptions;

// Renders the stills (and negatives) or the video `args` ask for; returns the exit code.
int renderRealScenes(const Args& args, const Settings& settings, bool video);

}  // namespace imagepro::cli
