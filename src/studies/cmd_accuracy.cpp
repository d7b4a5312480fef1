// imagepro-studies accuracy: docs/accuracy.md, measured. Its virtual part (virtual_accuracy.h)
// and its real-scene part (real_scene_accuracy.h), each with the ArUco reference beside the
// target; --scene chooses one or both. The prose is docs/accuracy.md's own: the study fills its
// measured places (measured_doc.h), those of the parts it ran.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/command.h"
#include "core/common/data_directory.h"
#include "core/source/background_photos.h"
#include "studies/measured_doc.h"
#include "studies/real_scene_accuracy.h"
#include "studies/report.h"
#include "studies/virtual_accuracy.h"

namespace imagepro::studies {
namespace {

using namespace imagepro::cli;

int count(const Args& args, const std::string& key, int fallback, int least) {
  const int n = args.integer(key, fallback);
  if (n < least || n > 100000) throw UsageError(format("--%s must be %d to 100000", key.c_str(), least));
  return n;
}

int run(const Args& args) {
  args.rejectUnknown({"frames", "out", "template", "seed", "scene", "stills", "negatives", "videos", "video-frames", "backgrounds",
                      "webcam-stills", "webcam-negatives", "webcam-config"});
  const int frames = count(args, "frames", 300, 1);
  const std::string out = args.valueOr("out", "docs/accuracy.md");
  const std::string templatePath = args.valueOr("template", out);
  const int seed = args.integer("seed", 1);
  if (seed < 0) throw UsageError("--seed must be 0 or more");
  const std::string scene = args.valueOr("scene", "all");
  if (scene != "all" && scene != "virtual" && scene != "real") throw UsageError("--scene must be virtual, real or all");
  const bool virtual_part = scene != "real", real_part = scene != "virtual";
  if (!real_part)
    for (const char* key : {"stills", "negatives", "videos", "video-frames", "backgrounds", "webcam-stills",
                            "webcam-negatives", "webcam-config"})
      if (args.has(key)) throw UsageError(std::string("--") + key + " applies to the real scenes only");
  if (!virtual_part && args.has("frames")) throw UsageError("--frames applies to the virtual scenes only");
  RealSceneStudyOptions real;
  real.stills = count(args, "stills", real.stills, 1);
  real.negatives = count(args, "negatives", real.negatives, 0);
  real.videos = count(args, "videos", real.videos, 0);
  real.video_frames = count(args, "video-frames", real.video_frames, 2 * real.hidden);
  real.seed = static_cast<std::uint64_t>(seed);
  real.backgrounds = args.valueOr("backgrounds", defaultBackgroundsDir());
  // The webcam set: the same photographs and seed, its own camera and the rig's effects.
  RealSceneStudyOptions webcam = real;
  webcam.stills = count(args, "webcam-stills", 400, 0);
  webcam.negatives = count(args, "webcam-negatives", 100, 0);
  webcam.videos = 0;
  webcam.rig = kWebcamRigEffects;
  const std::string webcam_config =
      args.valueOr("webcam-config", (dataDirectory() / "webcam-1280x720.json").string());
  const Settings settings = loadConfig(args);
  if (std::string error; !checkMeasuredDoc(templatePath, error)) throw InputError(error);
  const auto start = std::chrono::steady_clock::now();

  // The command that regenerates the report, every option that shapes it spelt out.
  std::string command = "imagepro-studies accuracy";
  if (scene != "all") command += " --scene " + scene;
  if (virtual_part) command += format(" --frames %d", frames);
  if (real_part)
    command += format(" --stills %d --negatives %d --videos %d --video-frames %d --webcam-stills %d "
                      "--webcam-negatives %d",
                      real.stills, real.negatives, real.videos, real.video_frames, webcam.stills, webcam.negatives);
  if (args.has("webcam-config")) command += " --webcam-config " + webcam_config;
  if (args.has("backgrounds")) command += " --backgrounds " + real.backgrounds;
  command += format(" --seed %d", seed);

  // The parts that ran fill every place of theirs; the others keep the doc's text.
  MeasuredValues values;
  std::vector<std::string> parts{"run."};
  if (virtual_part) {
    double seconds = 0.0;
    measureVirtualAccuracy(settings, frames, static_cast<std::uint64_t>(seed), values, seconds);
    parts.push_back("virtual.");
  }
  if (real_part) {
    RealSceneStudy study;
    std::string error;
    if (runRealSceneStudy(settings, real, study, error)) {
      measureRealScenes(settings, real, study, values);
      values["real.not_measured"] = "";
      parts.push_back("real.");
      if (webcam.stills > 0) {
        // The user's settings with the webcam's camera for every source.
        Settings webcam_settings = settings;
        if (!ok(loadSettings(webcam_config, webcam_settings, error))) throw InputError(error);
        RealSceneStudy webcam_study;
        if (!runRealSceneStudy(webcam_settings, webcam, webcam_study, error)) throw InputError(error);
        measureWebcamSet(webcam_settings, std::filesystem::path(webcam_config).filename().string(), webcam,
                         webcam_study, values);
        values["webcam.not_measured"] = "";
        parts.push_back("webcam.");
      } else {
        values["webcam.not_measured"] = "Not measured in this run (--webcam-stills 0).";
      }
    } else if (!virtual_part) {
      throw InputError(error + "; name a folder with --backgrounds or install Debian's opencv-doc");
    } else {
      // The virtual part still stands; the doc says what it lacks above the figures it keeps.
      std::fprintf(stderr, "accuracy: %s: the real-scene part is left out\n", error.c_str());
      const std::string why =
          "Not measured in this run: " + error + " (Debian's opencv-doc puts them in the default folder).";
      values["real.not_measured"] = why;
      values["webcam.not_measured"] = why;
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  values["run.command"] = "`" + command + "`";
  values["run.seconds"] = format("%.0f", seconds);
  std::string error;
  if (!fillMeasuredDoc(templatePath, out, values, parts, error)) throw InputError(error);
  std::fprintf(stderr, "wrote %s (%.0f s)\n", out.c_str(), seconds);
  return 0;
}

const CommandRegistration kRegistration{{
    "accuracy",
    "measure the pose's accuracy on virtual and real-scene frames against an ArUco marker (docs/accuracy.md)",
    "usage: imagepro-studies accuracy [--config FILE] [--scene virtual|real|all] [--frames N]\n"
    "                                 [--stills N] [--negatives N] [--videos N] [--video-frames N]\n"
    "                                 [--backgrounds DIR] [--seed S] [--template DOC] [--out FILE]\n\n"
    "Virtual scenes: renders N virtual grey frames at random poses (distance 400-1200 mm, tilt\n"
    "0-60 deg, any in-plane rotation, noise, blur, gradient, clutter) without and N with the\n"
    "thesis camera's lens distortion, detects and reconstructs the target in every contour mode\n"
    "and, at the same poses and effects, an ArUco marker (DICT_4X4_50, IPPE).\n"
    "Real scenes: the target over photographs (render --scene real and video's frames: stills,\n"
    "negatives without it, videos hiding it in the middle) through the default pipeline, each\n"
    "still alone and each video tracked, beside the same ArUco marker drawn in its place in the\n"
    "same frames and found by OpenCV's detector with its default, adaptive thresholds.\n"
    "The errors against the truth, the goals beside them, fill the measured places\n"
    "(<!--m:NAME-->...<!--/m-->) of the hand-written doc --template, written to --out: the places\n"
    "of the parts run (virtual.*, real.*, webcam.*; run.* always) take this run's values, the\n"
    "others keep their text. A place of a part run without a value, or a value without a place,\n"
    "is an error naming it.\n"
    "  --scene S          virtual, real or all (default all)\n"
    "  --frames N         virtual frames per distortion case (default 300)\n"
    "  --stills N         real-scene stills (default 400)\n"
    "  --negatives N      photographs without the target (default 100)\n"
    "  --videos N         real-scene videos, seeds S, S+1, ... (default 4)\n"
    "  --video-frames N   frames per video, 12 of them hidden (default 150, at least 24)\n"
    "  --backgrounds DIR  the photographs (default $IMAGEPRO_BACKGROUNDS or opencv-doc's)\n"
    "  --webcam-stills N  stills of the webcam set (render --scene real --webcam): occluders,\n"
    "                     glare and dim light through a wide lens (default 400; 0: none)\n"
    "  --webcam-negatives N  its photographs without the target (default 100)\n"
    "  --webcam-config FILE  its settings, read over --config's (default the data folder's\n"
    "                     webcam-1280x720.json)\n"
    "  --seed S           random poses, photographs and effects (default 1)\n"
    "  --template DOC     the doc to fill (default --out's FILE itself)\n"
    "  --out FILE         the report, written whole or not at all (default docs/accuracy.md)\n"
    "Without photographs --scene all fills the virtual part and says the real one was not measured.",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::studies
