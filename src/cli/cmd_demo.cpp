// imagepro-cli demo: the headless counterpart of starting the application on the
// Virtual source — the target moves in front of the virtual camera, and every
// frame's reconstructed pose is printed beside the true one.
#include <chrono>
#include <cstdio>

#include "cli/command.h"
#include "core/common/geometry.h"
#include "core/pipeline/engine.h"
#include "core/settings/enum_names.h"
#include "core/source/sources.h"

namespace imagepro::cli {
namespace {

int run(const Args& args) {
  args.rejectUnknown({"frames"});
  Settings settings = loadConfig(args);
  // Without a --config, move the target so there is something to follow.
  if (!args.has("config")) {
    settings.virtual_scene.motion.kind = MotionKind::Sinusoid;
    settings.virtual_scene.motion.axis = PoseAxis::Tx;
    settings.virtual_scene.motion.amplitude = 150.0;
    settings.virtual_scene.initial_pose.ry_deg = 25.0;
    settings.virtual_scene.initial_pose.rz_deg = 30.0;
    settings.virtual_scene.clutter = 6;
    settings.virtual_scene.noise_sigma = 3.0;
  }
  const int frames = args.integer("frames", 100);
  if (frames < 1) throw UsageError("--frames must be at least 1");
  auto source = makeVirtualSource(settings);

  std::printf("ImagePro headless demo: virtual target, %s motion along %s, tracking %s\n",
              std::string(enumName(settings.virtual_scene.motion.kind)).c_str(),
              std::string(enumName(settings.virtual_scene.motion.axis)).c_str(),
              std::string(enumName(settings.pipeline.tracking.mode)).c_str());
  std::printf("%6s %-10s %8s %8s %8s %9s %9s %9s | %9s %9s %9s\n", "frame", "status", "Rx", "Ry", "Rz", "Tx", "Ty",
              "Tz", "true Tx", "true Ty", "true Tz");
  Engine engine(settings);
  FrameResult r;
  int found = 0;
  double max_rot_err = 0.0, max_pos_err = 0.0;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i) {
    engine.step(*source, r);
    const Pose t = r.truth.value_or(Pose{});
    if (ok(r.status) && r.pose) {
      const Pose& p = *r.pose;
      ++found;
      max_rot_err = std::max(max_rot_err, rotationAngleBetweenDeg(rotationMatrix(t), rotationMatrix(p)));
      max_pos_err = std::max(max_pos_err, (translation(t) - translation(p)).norm());
      std::printf("%6lld %-10s %8.2f %8.2f %8.2f %9.2f %9.2f %9.2f | %9.2f %9.2f %9.2f\n", static_cast<long long>(r.index),
                  "ok", p.rx_deg, p.ry_deg, p.rz_deg, p.tx_mm, p.ty_mm, p.tz_mm, t.tx_mm, t.ty_mm, t.tz_mm);
    } else {
      std::printf("%6lld %-10s %8s %8s %8s %9s %9s %9s | %9.2f %9.2f %9.2f\n", static_cast<long long>(r.index),
                  std::string(statusName(r.status)).c_str(), "", "", "", "", "", "", t.tx_mm, t.ty_mm, t.tz_mm);
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("\n%d of %d frames reconstructed; largest rotation error %.3f deg, position error %.3f mm; "
              "%.0f frames/s (unpaced, rendering included)\n",
              found, frames, max_rot_err, max_pos_err, frames / std::max(seconds, 1e-9));
  return 0;
}

const CommandRegistration kRegistration{{
    "demo",
    "headless demo: a moving virtual target, its reconstructed and true poses",
    "usage: imagepro-cli demo [--config FILE] [--frames N]\n\n"
    "Runs the Virtual source through the whole pipeline and prints each frame's pose\n"
    "beside the true one. Without --config the target swings sideways in a cluttered,\n"
    "noisy scene. This is what `tools/setup.sh run` shows when there is no display.",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
