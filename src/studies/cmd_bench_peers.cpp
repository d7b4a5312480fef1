// imagepro-studies bench-peers: the engine's throughput (imagepro-cli bench) beside two
// peers timed on the very same frames in the same run: a pipeline composed of stock
// OpenCV calls, and AprilTag 3 (tag36h11) on the same scenes with a tag over the target.
#include <cstdio>
#include <vector>

#include "cli/command.h"
#include "cli/engine_bench.h"
#include "core/source/bench_scene.h"
#include "studies/peers/apriltag_peer.h"
#include "studies/peers/opencv_peer.h"

namespace imagepro::studies {
namespace {

using namespace imagepro::cli;

// The bench scenes with an AprilTag as wide as the disk drawn over the target before the
// blur and noise, which are the target frames' own.
std::vector<Frame> renderTagFrames(const Settings& scene, int frames) {
  AprilTagPeer tags(scene.camera, 2.0 * scene.target.radius_mm);
  std::vector<Frame> out;
  out.reserve(static_cast<std::size_t>(frames));
  for (int i = 0; i < frames; ++i) {
    Frame f = renderCleanBenchFrame(scene, i);
    tags.drawTag(*f.truth, f.image);
    degradeBenchFrame(f.image, kBenchBlurSigmaPx, kBenchNoiseSigma, static_cast<unsigned>(i));
    out.push_back(std::move(f));
  }
  return out;
}

BenchRun timeOpenCvPeer(const BenchSequence& sequence) {
  const Settings& s = sequence.settings;
  OpenCvPeerWorkspace ws;
  auto detect = [&](const cv::Mat& grey, Pose& pose) { return opencvPeerPose(grey, s.camera, s.target, ws, pose); };
  Pose pose;
  for (const Frame& f : sequence.frames) detect(f.image, pose);  // grows the workspace
  return timeDetector(sequence.frames, detect);
}

BenchRun timeAprilTag(const Settings& scene, const std::vector<Frame>& tag_frames) {
  AprilTagPeer peer(scene.camera, 2.0 * scene.target.radius_mm);
  return timeDetector(tag_frames, [&](const cv::Mat& grey, Pose& pose) { return peer.detect(grey, pose); });
}

void timePeers(const BenchSequence& sequence, BenchResolution& r) {
  std::fprintf(stderr, "rendering the AprilTag frames, timing the OpenCV pipeline and AprilTag ...\n");
  const std::vector<Frame> tag_frames = renderTagFrames(sequence.settings, static_cast<int>(sequence.frames.size()));
  r.peers.push_back({"OpenCV composed pipeline", "OpenCV", "opencv_pipeline", timeOpenCvPeer(sequence)});
  r.peers.push_back({"AprilTag 3 (tag36h11)", "AprilTag", "apriltag", timeAprilTag(sequence.settings, tag_frames)});
}

int run(const Args& args) {
  args.rejectUnknown({"frames", "resolution", "format"});
  runBench(benchOptions(args), timePeers);
  return 0;
}

const CommandRegistration kRegistration{{
    "bench-peers",
    "frames/s of the engine (tracking off and on) beside an OpenCV pipeline and AprilTag",
    "usage: imagepro-studies bench-peers [--config FILE] [--frames N] [--resolution WxH|all]\n"
    "                                    [--format text|json]\n\n"
    "Renders N realistic grey frames of a moving target (and the same scenes with an\n"
    "AprilTag tag36h11 as wide as the disk over the target), then times on one core:\n"
    "ImagePro's engine with tracking off and on, a pipeline of stock OpenCV calls\n"
    "(Otsu, findContours, fitEllipseDirect, solvePnP) and AprilTag 3 — same frames, same run.\n"
    "Prints frames/s, ratios, per-stage median and 99th-percentile microseconds, heap\n"
    "allocations per frame and peak memory. --resolution all also runs 1280x720 and 1920x1080.\n"
    "--format json prints one object with full_frame_hz, tracked_hz, opencv_pipeline_hz, apriltag_hz.",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::studies
