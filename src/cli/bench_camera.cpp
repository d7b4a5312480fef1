#include "cli/bench_camera.h"

#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <numeric>
#include <vector>

#include "cli/frame_input.h"
#include "core/camera/pixel_format.h"
#include "core/pipeline/engine.h"
#include "core/settings/enum_names.h"

namespace imagepro::cli {

namespace {

using Clock = std::chrono::steady_clock;

// Frames processed before timing starts: the engine's buffers grow to their working size.
constexpr int kWarmUpFrames = 5;
// More time-outs than this (2 s each) and the camera is taken to deliver nothing.
constexpr int kMaxTimeouts = 3;

struct EngineTimes {
  std::vector<double> us;  // per frame
  int found = 0;

  double percentile(double q) const {
    if (us.empty()) return 0.0;
    std::vector<double> v = us;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, static_cast<std::size_t>(q * (v.size() - 1) + 0.5))];
  }
  double hz() const {
    const double total = std::accumulate(us.begin(), us.end(), 0.0);
    return total > 0.0 ? 1e6 * static_cast<double>(us.size()) / total : 0.0;
  }
};

void timeEngine(Engine& engine, const Frame& frame, FrameResult& result, EngineTimes* times) {
  const auto start = Clock::now();
  engine.process(frame, result);
  const double us = std::chrono::duration<double, std::micro>(Clock::now() - start).count();
  if (!times) return;
  times->us.push_back(us);
  if (result.pose) ++times->found;
}

}  // namespace

int runCameraBench(const Args& args) {
  args.rejectUnknown({"camera", "size", "fps", "frames", "format"});
  if (!args.positionals().empty()) throw UsageError("bench --camera takes no input files");
  const int frames = args.integer("frames", 200);
  if (frames < 10) throw UsageError("--frames must be at least 10");
  const std::string format = args.valueOr("format", "text");
  if (format != "text" && format != "json") throw UsageError("--format must be text or json");
  const Settings settings = loadConfigForInput(args);  // --camera: the Camera source's model
  const auto camera = openCamera(args, settings);
  const CameraFormat agreed = camera->format();
  if (agreed.width != settings.camera().width || agreed.height != settings.camera().height)
    std::fprintf(stderr, "note: the frames are %dx%d, the camera model is for %dx%d: the times hold, the poses do not\n",
                 agreed.width, agreed.height, settings.camera().width, settings.camera().height);

  Settings tracked_settings = settings;
  if (tracked_settings.pipeline.tracking.mode == TrackingMode::Off)
    tracked_settings.pipeline.tracking.mode = TrackingOptions{}.mode;
  Settings full_settings = settings;
  full_settings.pipeline.tracking.mode = TrackingMode::Off;
  Engine tracked(tracked_settings), full(full_settings);
  cv::setNumThreads(1);  // one core, as the other benches

  std::fprintf(stderr, "grabbing %d frames from %s ...\n", kWarmUpFrames + frames, camera->describe().c_str());
  EngineTimes tracked_times, full_times;
  tracked_times.us.reserve(static_cast<std::size_t>(frames));
  full_times.us.reserve(static_cast<std::size_t>(frames));
  Frame frame;
  FrameResult result;
  int grabbed = 0, timeouts = 0, damaged = 0;
  double first_s = 0.0, last_s = 0.0;
  std::int64_t dropped_before = 0;
  while (grabbed < kWarmUpFrames + frames) {
    const Status s = camera->next(frame);
    if (s == Status::CameraTimeout && ++timeouts <= kMaxTimeouts) continue;
    if (s == Status::EmptyFrame) {
      ++damaged;
      continue;
    }
    if (!ok(s)) throw InputError(camera->lastError());
    const bool timed = grabbed >= kWarmUpFrames;
    if (grabbed == kWarmUpFrames) {
      first_s = frame.timestamp_s;
      dropped_before = camera->stats().dropped;
    }
    last_s = frame.timestamp_s;
    timeEngine(tracked, frame, result, timed ? &tracked_times : nullptr);
    timeEngine(full, frame, result, timed ? &full_times : nullptr);
    ++grabbed;
  }
  const std::int64_t dropped = camera->stats().dropped - dropped_before;
  // frames - 1 intervals between the first and the last timed frame, plus the lost ones.
  const double capture_hz = last_s > first_s ? (frames - 1 + static_cast<double>(dropped)) / (last_s - first_s) : 0.0;
  const double delivered_hz = last_s > first_s ? (frames - 1) / (last_s - first_s) : 0.0;
  const std::string fourcc = fourccText(agreed.fourcc);
  const std::string tracking(enumName(tracked_settings.pipeline.tracking.mode));

  if (format == "json") {
    std::printf("{\"device\": \"%s\", \"width\": %d, \"height\": %d, \"pixel_format\": \"%s\", \"frames\": %d, "
                "\"nominal_hz\": %.2f, \"capture_hz\": %.2f, \"delivered_hz\": %.2f, \"dropped\": %lld, "
                "\"damaged\": %d, \"tracked_hz\": %.1f, \"full_frame_hz\": %.1f, \"tracked_median_us\": %.1f, "
                "\"full_frame_median_us\": %.1f, \"tracked_p99_us\": %.1f, \"full_frame_p99_us\": %.1f, "
                "\"tracked_found\": %d, \"full_frame_found\": %d}\n",
                agreed.device.c_str(), agreed.width, agreed.height, fourcc.c_str(), frames, agreed.nominal_rate_hz,
                capture_hz, delivered_hz, static_cast<long long>(dropped), damaged, tracked_times.hz(), full_times.hz(),
                tracked_times.percentile(0.5), full_times.percentile(0.5), tracked_times.percentile(0.99),
                full_times.percentile(0.99), tracked_times.found, full_times.found);
    return 0;
  }
  std::printf("camera %s (%s): %dx%d %s, nominal %.2f frames/s\n", agreed.device.c_str(), agreed.card.c_str(),
              agreed.width, agreed.height, fourcc.c_str(), agreed.nominal_rate_hz);
  std::printf("capture: %d frames timed after %d warm-up, %.2f frames/s by the driver's clock "
              "(%.2f delivered, %lld dropped, %d damaged)\n",
              frames, kWarmUpFrames, capture_hz, delivered_hz, static_cast<long long>(dropped), damaged);
  std::printf("\n%-26s %10s %10s %12s %10s\n", "engine, per frame", "median us", "p99 us", "frames/s", "found");
  const auto row = [frames](const std::string& name, const EngineTimes& t) {
    std::printf("%-26s %10.1f %10.1f %12.0f %6d/%-4d\n", name.c_str(), t.percentile(0.5), t.percentile(0.99), t.hz(),
                t.found, frames);
  };
  row("tracked (" + tracking + ")", tracked_times);
  row("full frame", full_times);
  const auto verdict = [capture_hz](const char* name, double hz) {
    std::printf("%s: %.1f frames/s live, %s\n", name, std::min(hz, capture_hz),
                hz >= capture_hz ? "capture-limited (the engine keeps up)" : "engine-limited (frames would be dropped)");
  };
  std::printf("\n");
  verdict("tracked", tracked_times.hz());
  verdict("full frame", full_times.hz());
  return 0;
}

}  // namespace imagepro::cli
