#pragma once
// Turns the command line's input (image files, folders, list files, --virtual) into
// a FrameSource, shared by every command that runs the pipeline.
#include <memory>

#include "cli/command.h"
#include "core/source/source.h"

namespace imagepro::cli {

// Options understood: positionals (images, folders, .txt lists), --virtual,
// --frames N (virtual: how many; default 100), --video FILE, --camera DEV.
// Throws UsageError when no input is given, InputError when it cannot be opened.
std::unique_ptr<FrameSource> openFrameInput(const Args& args, const Settings& settings);

// The option names openFrameInput reads, for rejectUnknown and --help.
inline const std::vector<std::string> kFrameInputOptions{"virtual", "frames"};
inline constexpr const char* kFrameInputHelp =
    "input: IMAGES... (files, folders in natural order, or .txt lists of paths)\n"
    "       or --virtual [--frames N] (the Virtual source of the settings, default 100 frames)";

}  // namespace imagepro::cli
