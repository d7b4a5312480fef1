#pragma once
// The accuracy study's real-scene part (docs/accuracy.md, "Real scenes"): the target drawn
// over photographs by the core's generator (core/source/real_scene.h) in stills, negatives
// and videos, and the reference ArUco marker drawn in its place in the same frames
// (marker_scene.h). Each still goes through the default pipeline alone (tracking reset),
// each video is tracked frame to frame; the marker is found in every frame alone by
// OpenCV's detector with its default, adaptive thresholds. The prose around the measured
// values lives in docs/accuracy.md.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/common/geometry.h"
#include "core/common/status.h"
#include "core/settings/settings.h"
#include "core/source/rig_effects.h"
#include "studies/measured_doc.h"

namespace imagepro::studies {

struct RealSceneStudyOptions {
  int stills = 400;
  int negatives = 100;
  int videos = 4;  // seeds seed, seed + 1, ...
  int video_frames = 150;
  int hidden = 12;  // frames without the target in the middle of each video
  std::uint64_t seed = 1;
  std::string backgrounds;  // the photographs' folder
  RigEffects rig;           // occluders, glare, dim light on the stills (the webcam set)
};

// A pose within this rotation error of the truth is correct.
inline constexpr double kCorrectRotationDeg = 5.0;

// One detector on frames that show its object.
struct PoseTally {
  int frames = 0, posed = 0, correct = 0, wrong = 0;
  std::vector<double> rotation_deg, position_percent;  // of every pose, correct or not
  std::map<std::string, int> misses;                   // status name -> frames without a pose

  void add(Status status, const std::optional<Pose>& pose, const Pose& truth);
};

// One detector over the whole study.
struct DetectorTally {
  PoseTally stills;
  int negatives = 0, false_detections = 0;  // a pose on a photograph without the object
  PoseTally video;                          // the videos' visible frames
  std::map<std::string, PoseTally> by_effect;  // the stills by the rig effects they show (webcam set)
  int hidden = 0, found_in_hiding = 0;
  // Per video: frames from the target's reappearance to its first correct pose (0: at
  // once), -1 when none came.
  std::vector<int> reacquired_after;
};

struct RealSceneStudy {
  std::string backgrounds;
  std::size_t photos = 0;
  DetectorTally target, marker;
  double seconds = 0.0;
};

// Renders and measures every frame of `options` with `settings` (target, camera, pipeline).
// False with `error` when the photographs' folder holds none or one cannot be read.
bool runRealSceneStudy(const Settings& settings, const RealSceneStudyOptions& options, RealSceneStudy& out,
                       std::string& error);

// The values of docs/accuracy.md's real.* places: how the frames were made, then the stills'
// and the videos' tables, target and marker side by side against the goals, each with its
// verdict.
void measureRealScenes(const Settings& settings, const RealSceneStudyOptions& options, const RealSceneStudy& study,
                       MeasuredValues& values);

// The values of the webcam set's places (webcam.*): stills and negatives with options.rig's
// effects seen through `settings`' camera (a wide lens), target and marker side by side, and
// the stills' misses by effect. `config` names the settings file the command was given.
void measureWebcamSet(const Settings& settings, const std::string& config, const RealSceneStudyOptions& options,
                      const RealSceneStudy& study, MeasuredValues& values);

}  // namespace imagepro::studies
