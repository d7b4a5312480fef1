// imagepro-cli bench: frames per second of the whole engine on a realistic virtual
// sequence, with tracking off and on, per-stage times, peak memory and heap
// allocations per frame (the peers' comparison is imagepro-studies bench-peers).
#include "cli/bench_camera.h"
#include "cli/command.h"
#include "cli/engine_bench.h"

namespace imagepro::cli {
namespace {

int run(const Args& args) {
  if (args.has("camera")) return runCameraBench(args);
  args.rejectUnknown({"frames", "resolution", "format"});
  runBench(benchOptions(args));
  return 0;
}

const CommandRegistration kRegistration{{
    "bench",
    "frames/s of the engine, tracking off and on, on rendered or live camera frames",
    "usage: imagepro-cli bench [--config FILE] [--frames N] [--resolution WxH|all] [--format text|json]\n\n"
    "Renders N realistic grey frames of a moving target, then times ImagePro's engine on one\n"
    "core with tracking off and on. Prints frames/s, per-stage median and 99th-percentile\n"
    "microseconds, heap allocations per frame and peak memory. --resolution all also runs\n"
    "1280x720 and 1920x1080. --format json prints one object with full_frame_hz, tracked_hz.\n"
    "The same frames timed beside an OpenCV pipeline and AprilTag: imagepro-studies bench-peers.\n\n"
    "usage: imagepro-cli bench --camera /dev/videoN [--size WxH] [--fps N] [--frames N] [--config FILE]\n"
    "                          [--format text|json]\n\n"
    "Times the engine on N frames (default 200) grabbed live from a V4L2 camera (size and rate\n"
    "as for reconstruct --camera, stored controls set): each frame is processed by an engine\n"
    "that tracks and by one that searches the whole frame. Prints the camera's rate by the\n"
    "driver's clock, dropped frames, each engine's median and 99th-percentile microseconds\n"
    "and frames/s, and whether the live loop is capture-limited or engine-limited.",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
