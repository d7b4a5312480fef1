// imagepro-cli render: frames of the Virtual perspective projection source (thesis
// 2.2) as PNG files, with their exact poses in truth.csv (the pose CSV of
// docs/conventions.md, frame = PNG file name, so reconstruct's output compares row by row).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include "cli/command.h"
#include "core/common/atomic_file.h"
#include "core/common/pose_csv.h"
#include "core/settings/enum_names.h"
#include "core/source/sources.h"
#include "core/source/virtual_renderer.h"

namespace imagepro::cli {
namespace {

namespace fs = std::filesystem;

template <class E>
E enumOption(const Args& args, const std::string& key, E fallback) {
  const auto name = args.value(key);
  if (!name) return fallback;
  const auto value = parseEnum<E>(*name);
  if (!value) throw UsageError("--" + key + ": \"" + *name + "\" is not one of " + enumChoices<E>());
  return *value;
}

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

Pose poseOption(const Args& args, const Pose& fallback) {
  const auto text = args.value("pose");
  if (!text) return fallback;
  double v[6];
  std::istringstream in(*text);
  std::string field;
  int n = 0;
  while (std::getline(in, field, ',')) {
    if (n == 6) throw UsageError("--pose takes six numbers: RX,RY,RZ,TX,TY,TZ");
    try {
      size_t used = 0;
      v[n] = std::stod(field, &used);
      if (used != field.size()) throw std::invalid_argument(field);
    } catch (const std::exception&) {
      throw UsageError("--pose: \"" + field + "\" is not a number");
    }
    ++n;
  }
  if (n != 6) throw UsageError("--pose takes six numbers: RX,RY,RZ,TX,TY,TZ");
  return Pose{v[0], v[1], v[2], v[3], v[4], v[5]};
}

// The settings' virtual scene with the command line's changes.
void applyOptions(const Args& args, VirtualSceneOptions& s) {
  s.mode = enumOption(args, "mode", s.mode);
  s.motion.kind = enumOption(args, "motion", s.motion.kind);
  s.motion.axis = enumOption(args, "axis", s.motion.axis);
  s.motion.amplitude = args.number("amplitude", s.motion.amplitude);
  s.motion.period_s = args.number("period", s.motion.period_s);
  if (!(s.motion.period_s > 0.0)) throw UsageError("--period must be more than 0");
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
  s.initial_pose = poseOption(args, s.initial_pose);
}

int run(const Args& args) {
  args.rejectUnknown({"out", "frames", "mode", "motion", "axis", "amplitude", "period", "noise", "blur", "clutter",
                      "gradient", "white", "black", "background", "seed", "rate", "pose", "pattern", "name",
                      "append"});
  if (!args.positionals().empty()) throw UsageError("unexpected argument \"" + args.positionals()[0] + "\"");
  const auto out_dir = args.value("out");
  if (!out_dir || out_dir->empty()) throw UsageError("--out DIR is required");
  const int frames = args.integer("frames", 1);
  if (frames < 1) throw UsageError("--frames must be 1 or more");
  const auto name = args.value("name");
  if (name && frames != 1) throw UsageError("--name applies to a single frame (--frames 1)");
  if (name && (name->empty() || name->find('/') != std::string::npos))
    throw UsageError("--name must be a file name without a folder");

  Settings settings = loadConfig(args);
  applyOptions(args, settings.virtual_scene);

  std::error_code ec;
  fs::create_directories(*out_dir, ec);
  if (ec || !fs::is_directory(*out_dir)) throw InputError(*out_dir + ": cannot create the folder (" + ec.message() + ")");
  const std::string truth_path = (fs::path(*out_dir) / "truth.csv").string();
  std::string csv;
  std::string error;
  if (args.has("append") && fs::exists(truth_path)) {
    if (!readWholeFile(truth_path, csv, error)) throw InputError(error);
    if (csv.rfind(poseCsvHeader(), 0) != 0) throw InputError(truth_path + ": not a pose CSV, cannot append");
    if (!csv.empty() && csv.back() != '\n') csv += '\n';
  } else {
    csv = poseCsvHeader("in_view") + "\n";
  }

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
    const std::string path = (fs::path(*out_dir) / file_name).string();
    bool written = false;
    try {
      written = cv::imwrite(path, frame.image);
    } catch (const cv::Exception& e) {
      throw InputError(path + ": cannot be written (" + e.err + ")");
    }
    if (!written) throw InputError(path + ": cannot be written");
    const bool in_view = targetInView(settings.camera, settings.target, *frame.truth);
    csv += poseCsvRow(file_name, Status::Ok, frame.truth, in_view ? "1" : "0") + "\n";
    const auto now = std::chrono::steady_clock::now();
    if (now - last_report > std::chrono::seconds(1)) {
      std::fprintf(stderr, "render: %d / %d frames\r", i + 1, frames);
      last_report = now;
      progress_shown = true;
    }
  }
  if (progress_shown) std::fputc('\n', stderr);
  if (!writeFileAtomically(truth_path, csv, error)) throw InputError(error);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr, "render: wrote %d frame%s and %s in %.1f s\n", frames, frames == 1 ? "" : "s",
               truth_path.c_str(), seconds);
  return 0;
}

const CommandRegistration kRegistration{{
    "render",
    "render virtual frames (PNG) and their ground-truth poses (truth.csv)",
    "usage: imagepro-cli render --out DIR [--config FILE] [--frames N] [options]\n\n"
    "Renders N frames (default 1) of the Virtual perspective projection source: the\n"
    "target of the settings, seen through the settings' camera with its lens distortion,\n"
    "at the pose of the virtual motion at t = i / rate. Writes DIR/frame_00000.png ...\n"
    "and DIR/truth.csv (frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm,in_view;\n"
    "frame is the PNG file name, the pose is exact, in_view is 1 when the whole disk\n"
    "faces the camera inside the image, else 0). Options override the settings'\n"
    "\"virtual\" section:\n"
    "  --mode M          binary (0/255, the thesis's) or grey (anti-aliased)\n"
    "  --motion K        static, sinusoid, saw-tooth or pendulum\n"
    "  --axis A          tx, ty, tz, rx, ry or rz: the parameter the motion moves\n"
    "  --amplitude A     mm or degrees;  --period S  seconds;  --rate HZ  frames per second\n"
    "  --pose RX,RY,RZ,TX,TY,TZ   the initial pose (degrees, mm)\n"
    "  --noise S         Gaussian noise sigma, grey levels (grey mode)\n"
    "  --blur S          Gaussian blur sigma, pixels (grey mode)\n"
    "  --gradient G      illumination gradient across the width, -1..1 (grey mode)\n"
    "  --clutter N       white bars and rectangles behind the target's card\n"
    "  --white L --black L --background L   grey levels 0..255 (grey mode)\n"
    "  --seed N          clutter and noise seed\n"
    "  --pattern         the calibration pattern instead of the target alone\n"
    "  --name NAME       with --frames 1: write NAME.png instead of frame_00000.png\n"
    "  --append          add rows to an existing DIR/truth.csv instead of replacing it",
    {"pattern", "append"},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
