// imagepro-cli render: frames of the Virtual perspective projection source (thesis
// 2.2) as PNG files, with their exact poses in truth.csv (the pose CSV of
// docs/conventions.md, frame = PNG file name, so reconstruct's output compares row by row).
#include <chrono>
#include <cstdio>

#include "cli/command.h"
#include "cli/enum_options.h"
#include "cli/option_ranges.h"
#include "cli/render_output.h"
#include "cli/render_real.h"
#include "cli/virtual_motion_options.h"
#include "core/common/pose_csv.h"
#include "core/settings/enum_names.h"
#include "core/source/sources.h"
#include "core/source/virtual_renderer.h"

namespace imagepro::cli {
namespace {

double nonNegative(const Args& args, const std::string& key, double fallback) {
  const double v = args.number(key, fallback);
  if (!(v >= 0.0)) throw UsageError("--" + key + " must be 0 or more");
  return v;
}

int level(const Args& args, const std::string& key, int fallback) {
  const int v = args.integer(key, fallback);
  if (v < 0 || v > 255) throw UsageError("--" + key + " must be 0..255");
  return v;
}

// The settings' virtual scene with the command line's changes.
void applyOptions(const Args& args, VirtualSceneOptions& s) {
  s.mode = enumOption(args, "mode", s.mode);
  s.backdrop = enumOption(args, "backdrop", s.backdrop);
  applyVirtualMotionOptions(args, s);
  s.noise_sigma = nonNegative(args, "noise", s.noise_sigma);
  s.blur_sigma_px = nonNegative(args, "blur", s.blur_sigma_px);
  s.clutter = args.integer("clutter", s.clutter);
  if (s.clutter < 0) throw UsageError("--clutter must be 0 or more");
  s.illumination_gradient = args.number("gradient", s.illumination_gradient);
  if (!(s.illumination_gradient >= -1.0 && s.illumination_gradient <= 1.0))
    throw UsageError("--gradient must be -1..1");
  s.white_level = level(args, "white", s.white_level);
  s.black_level = level(args, "black", s.black_level);
  s.background_level = level(args, "background", s.background_level);
  const int seed = args.integer("seed", static_cast<int>(s.seed));
  if (seed < 0) throw UsageError("--seed must be 0 or more");
  s.seed = static_cast<unsigned>(seed);
  s.frame_rate_hz = args.number("rate", s.frame_rate_hz);
  if (!(s.frame_rate_hz > 0.0)) throw UsageError("--rate must be more than 0");
  s.initial_pose = sixNumbersOption(args, "pose", s.initial_pose);
}

// The settings keys the options above set, for the settings file's range checks.
const std::vector<OptionKey> kSceneOptionKeys = {
    {"virtual.noise_sigma", "--noise"},          {"virtual.blur_sigma_px", "--blur"},
    {"virtual.clutter", "--clutter"},            {"virtual.illumination_gradient", "--gradient"},
    {"virtual.white_level", "--white"},          {"virtual.black_level", "--black"},
    {"virtual.background_level", "--background"}, {"virtual.seed", "--seed"},
    {"virtual.frame_rate_hz", "--rate"},         {"virtual.pose.", "--pose"},
};

int renderVirtual(const Args& args, Settings settings) {
  const auto out_dir = args.value("out");
  if (!out_dir || out_dir->empty()) throw UsageError("--out DIR is required");
  const int frames = args.integer("frames", 1);
  if (frames < 1) throw UsageError("--frames must be 1 or more");
  const auto name = args.value("name");
  if (name && frames != 1) throw UsageError("--name applies to a single frame (--frames 1)");
  if (name && (name->empty() || name->find('/') != std::string::npos))
    throw UsageError("--name must be a file name without a folder");
  applyOptions(args, settings.virtual_scene);
  std::vector<OptionKey> keys = kSceneOptionKeys;
  keys.insert(keys.end(), kVirtualMotionOptionKeys.begin(), kVirtualMotionOptionKeys.end());
  checkOptionRanges(settings, keys);

  RenderOutput out(*out_dir, args.has("append"), poseCsvHeader("in_view"));
  auto source = makeVirtualSource(settings, args.has("pattern") ? VirtualContent::Pattern : VirtualContent::Target);
  Frame frame;
  const auto start = std::chrono::steady_clock::now();
  auto last_report = start;
  bool progress_shown = false;
  for (int i = 0; i < frames; ++i) {
    const Status status = source->next(frame);
    if (!ok(status)) throw InputError("frame " + std::to_string(i) + ": " + std::string(statusMessage(status)));
    char file[64];
    std::snprintf(file, sizeof file, "frame_%05d.png", i);
    const std::string file_name = name ? *name + ".png" : std::string(file);
    const bool in_view = targetInView(settings.camera(), settings.target, *frame.truth);
    out.write(file_name, frame.image, poseCsvRow(file_name, Status::Ok, frame.truth, in_view ? "1" : "0"));
    const auto now = std::chrono::steady_clock::now();
    if (now - last_report > std::chrono::seconds(1)) {
      std::fprintf(stderr, "render: %d / %d frames\r", i + 1, frames);
      last_report = now;
      progress_shown = true;
    }
  }
  if (progress_shown) std::fputc('\n', stderr);
  out.commit();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr, "render: wrote %d frame%s and %s in %.1f s\n", frames, frames == 1 ? "" : "s",
               out.truthPath().c_str(), seconds);
  return 0;
}

int run(const Args& args) {
  std::vector<std::string> known = {"out",   "frames", "mode",  "backdrop", "noise", "blur",    "clutter", "gradient",
                                    "white", "black",  "background", "seed", "rate", "pose", "pattern", "name",
                                    "append", "scene"};
  known.insert(known.end(), kVirtualMotionOptions.begin(), kVirtualMotionOptions.end());
  known.insert(known.end(), kRealSceneOptions.begin(), kRealSceneOptions.end());
  args.rejectUnknown(known);
  if (!args.positionals().empty()) throw UsageError("unexpected argument \"" + args.positionals()[0] + "\"");
  const std::string scene = args.valueOr("scene", "virtual");
  if (scene != "virtual" && scene != "real" && scene != "video")
    throw UsageError("--scene: \"" + scene + "\" is not one of virtual, real, video");
  const Settings settings = loadConfig(args);
  if (scene != "virtual") return renderRealScenes(args, settings, scene == "video");
  for (const auto& key : kRealSceneOptions)
    if (args.has(key)) throw UsageError("--" + key + " applies to --scene real or video only");
  return renderVirtual(args, settings);
}

const CommandRegistration kRegistration{{
    "render",
    "render virtual or real-scene frames (PNG) and their ground-truth poses (truth.csv)",
    "usage: imagepro-cli render --out DIR [--config FILE] [--scene virtual|real|video] [--frames N] [options]\n\n"
    "--scene virtual (the default): renders N frames (default 1) of the Virtual perspective\n"
    "projection source: the target of the settings, seen through the settings' camera with\n"
    "its lens distortion, at the pose of the virtual motion at t = i / rate. Writes\n"
    "DIR/frame_00000.png ... and DIR/truth.csv (frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,\n"
    "Ty_mm,Tz_mm,in_view; frame is the PNG file name, the pose is exact, in_view is 1 when\n"
    "the whole disk faces the camera inside the image, else 0). Options override the\n"
    "settings' \"virtual\" section, within the ranges the settings file allows:\n"
    "  --mode M          how the frames are drawn:\n" +
    choicesHelp<RenderMode>() +
    "  --backdrop B      what lies around the target's card (grey mode):\n" +
    choicesHelp<Backdrop>() +
    virtualMotionHelp() +
    "  --rate HZ         frames per second\n"
    "  --pose RX,RY,RZ,TX,TY,TZ   the initial pose (degrees " + rangeText("virtual.pose.rx_deg") + ", mm, TZ > 0)\n" +
    "  --noise S         Gaussian noise sigma, " + rangeText("virtual.noise_sigma") + " grey levels (grey mode)\n" +
    "  --blur S          Gaussian blur sigma, " + rangeText("virtual.blur_sigma_px") + " pixels (grey mode)\n" +
    "  --gradient G      illumination gradient across the width, " + rangeText("virtual.illumination_gradient") +
    " (grey mode)\n" +
    "  --clutter N       " + rangeText("virtual.clutter") + " white bars and rectangles behind the target's card\n" +
    "  --white L --black L --background L   grey levels " + rangeText("virtual.white_level") + " (grey mode)\n"
    "  --seed N          backdrop, clutter and noise seed\n"
    "  --pattern         the calibration pattern instead of the target alone\n"
    "  --name NAME       with --frames 1: write NAME.png instead of frame_00000.png\n"
    "  --append          add rows to an existing DIR/truth.csv instead of replacing it\n\n"
    "--scene real: N stills (default 1) of the settings' target on its black card over\n"
    "photographs: 0.4-2.5 m away, tilted 0-60 deg, turned at random, the card inside the\n"
    "frame; light falling off across the frame by up to +-40 %, optical blur 0.5-1.6 px,\n"
    "2-6 px motion blur on a third of the frames, noise sigma 1-6, JPEG quality 40-95.\n"
    "--scene video: one photograph, the target moving smoothly at 0.4-1.4 m, light\n"
    "drifting +-30 %, blur 0.8 px, noise sigma 2, JPEG 75, N frames (default 150) at 25 Hz,\n"
    "the target hidden for the middle 12. Both draw everything from --seed (the same seed,\n"
    "the same frames) and write DIR/frame_00000.png ... and DIR/truth.csv, the pose CSV\n"
    "with status NoTarget and no pose for a frame without the target, then in_view,\n"
    "background (the photograph), white, black (the target's grey levels), light_shape,\n"
    "light_amplitude, light_gain, blur_px, motion_px, motion_deg, noise_sigma, jpeg_quality,\n"
    "occluder_mm, occluder_grey (0: none), glare_mm (0: none).\n"
    "  --backgrounds DIR the photographs (JPEG, PNG); default $IMAGEPRO_BACKGROUNDS, else\n"
    "                    Debian's opencv-doc sample photographs\n"
    "  --negatives M     (real) M more frames, DIR/negative_00000.png ..., drawn the same way\n"
    "                    but without the target: false detections show there\n"
    "  --hidden K        (video) frames without the target in the middle (default 12)\n"
    "  --webcam          (real) what a rig does to the target: a flat occluder 10-25 mm wide\n"
    "                    across the rim on half the stills (dark or grey, clear of the spots),\n"
    "                    a saturating glare 4-12 mm across on the paper and a dim room (paper\n"
    "                    at grey 70-120) on 30 % each. With the wide lens of\n"
    "                    data/webcam-1280x720.json (--config) it is the webcam set of\n"
    "                    docs/accuracy.md\n"
    "  --occluders F --glare F --dim F   (real) the share (0..1) of stills with each effect\n"
    "  --set             every target of the settings' \"targets\" set: (real) on each still,\n"
    "                    each at a pose of its own, its card clear of the others'; (video) each\n"
    "                    on a path of its own, hidden --hidden frames in a window of its own\n"
    "                    (the first in the middle, each next one --hidden + 10 frames later),\n"
    "                    the cards drawn far to near. truth.csv has a row per target drawn,\n"
    "                    its id in a column target; a video's rows end with covered (1: a\n"
    "                    nearer card meets the disk's image box, it may be out of sight)\n"
    "  --seed N          the set to draw (default: the settings' virtual seed)\n\n"
    "Frames are written to a staging folder and moved in only when all are rendered, so\n"
    "an interrupted render leaves DIR as it was (or, if stopped while moving them in, no\n"
    "truth.csv): truth.csv never names frames other than the ones beside it.",
    {"pattern", "append", "webcam", "set"},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
