// imagepro-cli bench: frames per second of the whole engine on a realistic virtual
// sequence and on real scenes, with tracking off and on, per-stage times, peak memory and heap
// allocations per frame (the peers' comparison is imagepro-studies bench-peers).
#include "cli/bench_camera.h"
#include "cli/command.h"
#include "cli/engine_bench.h"

namespace imagepro::cli {
namespace {

int run(const Args& args) {
  if (args.has("camera")) return runCameraBench(args);
  args.rejectUnknown(kBenchOptionNames);
  runBench(benchOptions(args));
  return 0;
}

const CommandRegistration kRegistration{{
    "bench",
    "frames/s of the engine, tracking off and on, on rendered or live camera frames",
    "usage: imagepro-cli bench [--config FILE] [--frames N] [--resolution WxH|all]\n"
    "                          [--backgrounds DIR] [--format text|json]\n\n"
    "Renders N realistic grey frames of a moving target in the virtual bench scene, and N\n"
    "real-scene frames (the target moving over photographs, 50 frames over each, light,\n"
    "blur, noise, JPEG), then times ImagePro's engine on one core with tracking off and on,\n"
    "on each kind. Prints frames/s, per-stage median and 99th-percentile microseconds, heap\n"
    "allocations per frame, a summary and peak memory. --resolution all also runs 1280x720\n"
    "and 1920x1080. --backgrounds DIR: the photographs (default $IMAGEPRO_BACKGROUNDS or\n"
    "opencv-doc's; without any, one line says so and the virtual kind stands alone).\n"
    "--format json prints one object with full_frame_hz, tracked_hz, real_full_frame_hz,\n"
    "real_tracked_hz. --config FILE times its pipeline (methods and parameters) on the same\n"
    "frames: two runs, one with a setting changed, compare it side by side.\n"
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
