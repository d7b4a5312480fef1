// imagepro-studies bench-peers: the engine's throughput (imagepro-cli bench) beside peers
// timed on the very same scenes in the same run. Virtual scene: a pipeline composed of
// stock OpenCV calls, and AprilTag 3 (tag36h11) with a tag over the target. Real scenes:
// OpenCV's ArUco detector (default, adaptive thresholds) as the robust peer, its marker
// drawn by the real-scene generator in the target's place.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/engine_bench.h"
#include "core/source/bench_scene.h"
#include "studies/marker_scene.h"
#include "studies/peers/apriltag_peer.h"
#include "studies/peers/opencv_peer.h"

namespace imagepro::studies {
namespace {

using namespace imagepro::cli;

// The bench scenes with an AprilTag as wide as the disk drawn over the target before the
// blur and noise, which are the target frames' own.
std::vector<Frame> renderTagFrames(const Settings& scene, int frames) {
  AprilTagPeer tags(scene.camera(), 2.0 * scene.target.radius_mm);
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
  auto detect = [&](const cv::Mat& grey, Pose& pose) { return opencvPeerPose(grey, s.camera(), s.target, ws, pose); };
  Pose pose;
  for (const Frame& f : sequence.frames) detect(f.image, pose);  // grows the workspace
  return timeDetector(sequence.frames, detect);
}

BenchRun timeAprilTag(const Settings& scene, const std::vector<Frame>& tag_frames) {
  AprilTagPeer peer(scene.camera(), 2.0 * scene.target.radius_mm);
  return timeDetector(tag_frames, [&](const cv::Mat& grey, Pose& pose) { return peer.detect(grey, pose); });
}

// The sequence's frames with the ArUco marker in the target's place, then the detector
// (with the pose, as the engine gives one) timed on them.
BenchRun timeAruco(const BenchSequence& sequence) {
  const Settings& s = sequence.settings;
  const MarkerGeometry marker = markerLikeTarget(s.target, s.virtual_scene.card_size_mm);
  const ScenePainter painter = markerPainter(s.camera(), marker);
  std::vector<Frame> frames;
  frames.reserve(sequence.frames.size());
  for (const Frame& f : sequence.frames) {
    RealSceneFrame twin;
    std::string error;
    if (!sequence.redraw(static_cast<int>(f.index), painter, twin, error)) throw InputError(error);
    Frame frame = f;
    frame.image = twin.image;
    frames.push_back(std::move(frame));
  }
  auto detect = [&](const cv::Mat& grey, Pose& pose) { return estimateMarkerPose(s.camera(), marker, grey, pose); };
  Pose pose;
  for (std::size_t i = 0; i < std::min<std::size_t>(frames.size(), 10); ++i) detect(frames[i].image, pose);
  return timeDetector(frames, detect);
}

void timePeers(const BenchSequence& sequence, BenchKindRun& r) {
  if (sequence.kind == BenchKind::Real) {
    std::fprintf(stderr, "rendering the ArUco frames, timing OpenCV's ArUco detector ...\n");
    r.peers.push_back({"ArUco 4x4 (OpenCV, IPPE)", "ArUco", "aruco", timeAruco(sequence)});
    return;
  }
  std::fprintf(stderr, "rendering the AprilTag frames, timing the OpenCV pipeline and AprilTag ...\n");
  const std::vector<Frame> tag_frames = renderTagFrames(sequence.settings, static_cast<int>(sequence.frames.size()));
  r.peers.push_back({"OpenCV composed pipeline", "OpenCV", "opencv_pipeline", timeOpenCvPeer(sequence)});
  r.peers.push_back({"AprilTag 3 (tag36h11)", "AprilTag", "apriltag", timeAprilTag(sequence.settings, tag_frames)});
}

int run(const Args& args) {
  args.rejectUnknown(kBenchOptionNames);
  runBench(benchOptions(args), timePeers);
  return 0;
}

const CommandRegistration kRegistration{{
    "bench-peers",
    "frames/s of the engine (tracking off and on) beside an OpenCV pipeline and AprilTag",
    "usage: imagepro-studies bench-peers [--config FILE] [--frames N] [--resolution WxH|all]\n"
    "                                    [--backgrounds DIR] [--format text|json]\n\n"
    "Renders N realistic grey frames of a moving target (and the same scenes with an\n"
    "AprilTag tag36h11 as wide as the disk over the target), then times on one core:\n"
    "ImagePro's engine with tracking off and on, a pipeline of stock OpenCV calls\n"
    "(Otsu, findContours, fitEllipseDirect, solvePnP) and AprilTag 3 — same frames, same run.\n"
    "Then N real-scene frames (imagepro-cli bench's), the engine beside OpenCV's ArUco\n"
    "detector (DICT_4X4_50, default adaptive thresholds, IPPE) on the same frames with its\n"
    "marker in the target's place. Prints frames/s, ratios, per-stage median and\n"
    "99th-percentile microseconds, heap allocations per frame and peak memory.\n"
    "--resolution all also runs 1280x720 and 1920x1080. --backgrounds DIR: the photographs\n"
    "(without any, the real scenes are left out with a line saying so).\n"
    "--format json prints one object with full_frame_hz, tracked_hz, opencv_pipeline_hz,\n"
    "apriltag_hz, real_full_frame_hz, real_tracked_hz, real_aruco_hz.",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::studies
