// imagepro-studies accuracy: docs/accuracy.md, measured. Its virtual part (virtual_accuracy.h)
// and its real-scene part (real_scene_accuracy.h), each with the ArUco reference beside the
// target; --scene chooses one or both.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli/command.h"
#include "core/common/atomic_file.h"
#include "core/common/data_directory.h"
#include "core/source/background_photos.h"
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
  args.rejectUnknown({"frames", "out", "seed", "scene", "stills", "negatives", "videos", "video-frames", "backgrounds",
                      "webcam-stills", "webcam-negatives", "webcam-config"});
  const int frames = count(args, "frames", 300, 1);
  const std::string out = args.valueOr("out", "docs/accuracy.md");
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

  std::string body;
  if (virtual_part) {
    double seconds = 0.0;
    body += virtualAccuracyReport(settings, frames, static_cast<std::uint64_t>(seed), seconds);
  }
  if (real_part) {
    RealSceneStudy study;
    std::string error;
    if (runRealSceneStudy(settings, real, study, error)) {
      body += realSceneSection(settings, real, study);
      if (webcam.stills > 0) {
        // The user's settings with the webcam's camera for every source.
        Settings webcam_settings = settings;
        if (!ok(loadSettings(webcam_config, webcam_settings, error))) throw InputError(error);
        RealSceneStudy webcam_study;
        if (!runRealSceneStudy(webcam_settings, webcam, webcam_study, error)) throw InputError(error);
        body += webcamSection(webcam_settings, std::filesystem::path(webcam_config).filename().string(), webcam,
                              webcam_study);
      }
    } else if (!virtual_part) {
      throw InputError(error + "; name a folder with --backgrounds or install Debian's opencv-doc");
    } else {
      // The virtual part still stands; the report says what it lacks.
      std::fprintf(stderr, "accuracy: %s: the real-scene part is left out\n", error.c_str());
      body += "## Real scenes: the target over photographs\n\nNot measured in this run: " + error +
              " (Debian's opencv-doc puts them in the default folder).\n\n";
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string md = "# Accuracy\n\n" +
                         format("Produced by `%s` (%.0f s on this machine); every figure below comes from that run.\n\n",
                                command.c_str(), seconds) +
                         body;
  std::string error;
  if (!writeFileAtomically(out, md, error)) throw InputError(error);
  std::fprintf(stderr, "wrote %s (%.0f s)\n", out.c_str(), seconds);
  return 0;
}

const CommandRegistration kRegistration{{
    "accuracy",
    "measure the pose's accuracy on virtual and real-scene frames against an ArUco marker (docs/accuracy.md)",
    "usage: imagepro-studies accuracy [--config FILE] [--scene virtual|real|all] [--frames N]\n"
    "                                 [--stills N] [--negatives N] [--videos N] [--video-frames N]\n"
    "                                 [--backgrounds DIR] [--seed S] [--out FILE]\n\n"
    "Virtual scenes: renders N virtual grey frames at random poses (distance 400-1200 mm, tilt\n"
    "0-60 deg, any in-plane rotation, noise, blur, gradient, clutter) without and N with the\n"
    "thesis camera's lens distortion, detects and reconstructs the target in every contour mode\n"
    "and, at the same poses and effects, an ArUco marker (DICT_4X4_50, IPPE).\n"
    "Real scenes: the target over photographs (render --scene real and video's frames: stills,\n"
    "negatives without it, videos hiding it in the middle) through the default pipeline, each\n"
    "still alone and each video tracked, beside the same ArUco marker drawn in its place in the\n"
    "same frames and found by OpenCV's detector with its default, adaptive thresholds.\n"
    "Writes the errors against the truth as Markdown, the goals beside them.\n"
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
    "  --out FILE         the report (default docs/accuracy.md)\n"
    "Without photographs --scene all writes the virtual part and says the real one is missing.",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::studies
