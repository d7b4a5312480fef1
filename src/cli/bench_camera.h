#pragma once
// imagepro-cli bench --camera: the engine timed on frames grabbed live from a V4L2
// camera. Every frame is processed twice, by an engine that tracks (as the GUI runs it)
// and by one that searches the whole frame, each timed on its own; the camera's
// delivered rate comes from the driver's timestamps. A live loop runs at the smaller of
// the camera's rate and the engine's: the engine keeps up when its rate is the larger.
#include "cli/command.h"

namespace imagepro::cli {

// The bench subcommand's run() with --camera given (also --size, --fps, --frames,
// --format, --config). A camera that cannot be opened: InputError naming it.
int runCameraBench(const Args& args);

}  // namespace imagepro::cli
