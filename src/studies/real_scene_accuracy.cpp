#include "studies/real_scene_accuracy.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>

#include "core/pipeline/engine.h"
#include "core/reconstruction/undistort.h"
#include "core/source/real_scene_video.h"
#include "studies/marker_scene.h"
#include "studies/report.h"

namespace imagepro::studies {

void PoseTally::add(Status status, const std::optional<Pose>& pose, const Pose& truth) {
  ++frames;
  if (status != Status::Ok || !pose) {
    ++misses[std::string(statusName(status))];
    return;
  }
  ++posed;
  const double rotation = rotationAngleBetweenDeg(rotationMatrix(truth), rotationMatrix(*pose));
  rotation_deg.push_back(rotation);
  position_percent.push_back(100.0 * (translation(*pose) - translation(truth)).norm() / translation(truth).norm());
  (rotation <= kCorrectRotationDeg ? correct : wrong)++;
}

namespace {

// The two detectors, each on its own twin of a frame.
class Detectors {
 public:
  explicit Detectors(const Settings& settings)
      : settings_(settings),
        engine_(settings),
        marker_(markerLikeTarget(settings.target, settings.virtual_scene.card_size_mm)) {}

  // The pipeline on `image`: a still (searched alone) when `name` is given, else the
  // next frame of a tracked stream at `index`.
  Status target(const cv::Mat& image, std::int64_t index, const std::string& name, std::optional<Pose>& pose) {
    Frame frame;
    frame.image = image;
    frame.index = index;
    frame.name = name;
    frame.timestamp_s = name.empty() ? index / RealSceneVideo::kFrameRateHz : 0.0;
    if (!name.empty()) engine_.resetTracking();
    engine_.process(frame, result_);
    pose = result_.pose;
    return result_.status;
  }

  Status marker(const cv::Mat& image, std::optional<Pose>& pose) {
    Pose found;
    const Status s = estimateMarkerPose(settings_.camera(), marker_, image, found);
    pose = ok(s) ? std::optional<Pose>(found) : std::nullopt;
    return s;
  }

  void resetTracking() { engine_.resetTracking(); }
  const MarkerGeometry& markerGeometry() const { return marker_; }

 private:
  const Settings& settings_;
  Engine engine_;
  FrameResult result_;
  MarkerGeometry marker_;
};

bool posed(Status s, const std::optional<Pose>& pose) { return s == Status::Ok && pose.has_value(); }

// The effects a still shows, for the table of misses by effect.
std::string effectName(const RigDraw& rig) {
  std::string name;
  if (rig.occluder.present) name += rig.occluder.level < 65 ? "dark occluder" : "grey occluder";
  if (rig.glare.present) name += std::string(name.empty() ? "" : " + ") + "glare";
  if (rig.dim) name += std::string(name.empty() ? "" : " + ") + "dim";
  return name.empty() ? "none" : name;
}

bool runStills(const RealScenes& scenes, const RealSceneStudyOptions& o, Detectors& d, const ScenePainter& marker,
               RealSceneStudy& out, std::string& error) {
  RealSceneFrame f, twin;
  std::optional<Pose> pose;
  const int total = o.stills + o.negatives;
  std::fprintf(stderr, "real scenes: %d stills, %d negatives\n", o.stills, o.negatives);
  for (int i = 0; i < total; ++i) {
    // Negatives continue the stills' draws (as render --scene real numbers them).
    const bool with_target = i < o.stills;
    if (!scenes.still(o.seed, i, with_target, f, error)) return false;
    const std::string name = (with_target ? "frame_" : "negative_") + std::to_string(i) + ".png";
    const Status ts = d.target(f.image, i, name, pose);
    if (with_target) {
      out.target.stills.add(ts, pose, *f.truth);
      if (o.rig.any()) out.target.by_effect[effectName(f.rig)].add(ts, pose, *f.truth);
      if (!scenes.still(o.seed, i, true, twin, error, marker)) return false;
      const Status ms = d.marker(twin.image, pose);
      out.marker.stills.add(ms, pose, *twin.truth);
    } else {
      // A negative shows neither object: both detectors search the very same frame.
      ++out.target.negatives;
      ++out.marker.negatives;
      out.target.false_detections += posed(ts, pose);
      const Status ms = d.marker(f.image, pose);
      out.marker.false_detections += posed(ms, pose);
    }
  }
  return true;
}

// The frames from the video's reappearance to the first correct pose (-1: none).
struct Reacquisition {
  int after = -1;
  void note(const RealSceneVideo& video, int index, bool correct) {
    if (after < 0 && correct && index >= video.hiddenEnd()) after = index - video.hiddenEnd();
  }
};

bool runVideo(const RealScenes& scenes, const RealSceneStudyOptions& o, int k, Detectors& d,
              const ScenePainter& marker, RealSceneStudy& out, std::string& error) {
  const RealSceneVideo video(scenes, o.seed + static_cast<std::uint64_t>(k), o.video_frames, o.hidden);
  std::fprintf(stderr, "real scenes: video %d of %d, %d frames\n", k + 1, o.videos, video.frames());
  d.resetTracking();
  Reacquisition target_back, marker_back;
  RealSceneFrame f, twin;
  std::optional<Pose> pose;
  for (int i = 0; i < video.frames(); ++i) {
    if (!video.frame(i, f, error)) return false;
    const Status ts = d.target(f.image, i, "", pose);
    if (!f.truth) {
      ++out.target.hidden;
      ++out.marker.hidden;
      out.target.found_in_hiding += posed(ts, pose);
      const Status ms = d.marker(f.image, pose);
      out.marker.found_in_hiding += posed(ms, pose);
      continue;
    }
    const int target_correct = out.target.video.correct;
    out.target.video.add(ts, pose, *f.truth);
    target_back.note(video, i, out.target.video.correct > target_correct);
    if (!video.frame(i, twin, error, marker)) return false;
    const int marker_correct = out.marker.video.correct;
    const Status ms = d.marker(twin.image, pose);
    out.marker.video.add(ms, pose, *twin.truth);
    marker_back.note(video, i, out.marker.video.correct > marker_correct);
  }
  out.target.reacquired_after.push_back(video.hiddenEnd() < video.frames() ? target_back.after : -1);
  out.marker.reacquired_after.push_back(video.hiddenEnd() < video.frames() ? marker_back.after : -1);
  return true;
}

}  // namespace

bool runRealSceneStudy(const Settings& settings, const RealSceneStudyOptions& options, RealSceneStudy& out,
                       std::string& error) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::string> photos = listBackgrounds(options.backgrounds);
  if (photos.empty()) {
    error = options.backgrounds + ": no photographs (JPEG or PNG) there";
    return false;
  }
  out = RealSceneStudy{};
  out.backgrounds = options.backgrounds;
  out.photos = photos.size();
  const RealScenes scenes(settings, std::move(photos), options.rig);
  Detectors detectors(settings);
  const ScenePainter marker = markerPainter(settings.camera(), detectors.markerGeometry());
  if (!runStills(scenes, options, detectors, marker, out, error)) return false;
  for (int k = 0; k < options.videos; ++k)
    if (!runVideo(scenes, options, k, detectors, marker, out, error)) return false;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

namespace {

std::string share(int n, int of) { return format("%d of %d (%.1f %%)", n, of, of ? 100.0 * n / of : 0.0); }

std::string figure(double v, const char* unit) {
  return std::isnan(v) ? std::string("-") : format(v < 10 ? "%.3f %s" : "%.1f %s", v, unit);
}

std::string statuses(const std::map<std::string, int>& misses) {
  if (misses.empty()) return "none";
  std::vector<std::pair<std::string, int>> v(misses.begin(), misses.end());
  std::stable_sort(v.begin(), v.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  std::string out;
  for (const auto& [name, n] : v) out += format("%s%s %d", out.empty() ? "" : ", ", name.c_str(), n);
  return out;
}

std::string reacquisitions(const std::vector<int>& after) {
  if (after.empty()) return "-";
  std::string out;
  for (int a : after) out += (out.empty() ? "" : ", ") + (a < 0 ? std::string("never") : std::to_string(a));
  return out;
}

// A row of the two tables: the measure, its goal, the target's cell and the marker's, and
// whether the target's figure meets the goal (no mark without a goal).
struct Row {
  std::string measure, goal;
  std::function<std::string(const DetectorTally&)> cell;
  std::function<bool(const DetectorTally&)> met;
};

std::string table(const std::vector<Row>& rows, const RealSceneStudy& study, std::vector<std::string>& missed) {
  std::string md = "| measure | goal | target (default pipeline) | ArUco 4x4 marker |\n| --- | --- | ---: | ---: |\n";
  for (const Row& r : rows) {
    const bool miss = r.met && !r.met(study.target);
    if (miss) missed.push_back(r.measure);
    md += "| " + r.measure + " | " + r.goal + " | " + r.cell(study.target) + (miss ? " (missed)" : "") + " | " +
          r.cell(study.marker) + " |\n";
  }
  return md;
}

// The rows every set of frames with a target has: poses, correct, wrong, errors, misses.
std::vector<Row> poseRows(PoseTally DetectorTally::*set, const char* of) {
  auto t = [set](const DetectorTally& d) -> const PoseTally& { return d.*set; };
  return {
      {format("frames with a pose (of %s)", of), "", [t](const DetectorTally& d) {
         return share(t(d).posed, t(d).frames);
       }, {}},
      {format("frames with a correct pose (rotation error <= %.0f deg)", kCorrectRotationDeg), ">= 98 %",
       [t](const DetectorTally& d) { return share(t(d).correct, t(d).frames); },
       [t](const DetectorTally& d) { return t(d).correct >= 0.98 * t(d).frames; }},
      {format("poses reported but off by more than %.0f deg (of the poses)", kCorrectRotationDeg), "<= 0.5 %",
       [t](const DetectorTally& d) { return share(t(d).wrong, t(d).posed); },
       [t](const DetectorTally& d) { return t(d).wrong <= 0.005 * t(d).posed; }},
      {"rotation error, median", "<= 0.2 deg",
       [t](const DetectorTally& d) { return figure(quantile(t(d).rotation_deg, 0.5), "deg"); },
       [t](const DetectorTally& d) { return quantile(t(d).rotation_deg, 0.5) <= 0.2; }},
      {"rotation error, 95th percentile", "<= 2 deg",
       [t](const DetectorTally& d) { return figure(quantile(t(d).rotation_deg, 0.95), "deg"); },
       [t](const DetectorTally& d) { return quantile(t(d).rotation_deg, 0.95) <= 2.0; }},
      {"position error, median (of the distance)", "<= 0.15 %",
       [t](const DetectorTally& d) { return figure(quantile(t(d).position_percent, 0.5), "%"); },
       [t](const DetectorTally& d) { return quantile(t(d).position_percent, 0.5) <= 0.15; }},
      {"position error, 95th percentile", "",
       [t](const DetectorTally& d) { return figure(quantile(t(d).position_percent, 0.95), "%"); }, {}},
      {"statuses of the frames without a pose", "", [t](const DetectorTally& d) { return statuses(t(d).misses); },
       {}},
  };
}

// The stills' rows, with the false detections on the negatives after the wrong poses.
std::vector<Row> stillRows() {
  std::vector<Row> rows = poseRows(&DetectorTally::stills, "the stills");
  rows.insert(rows.begin() + 3,
              Row{"false detections on the negatives", "0",
                  [](const DetectorTally& d) { return format("%d of %d", d.false_detections, d.negatives); },
                  [](const DetectorTally& d) { return d.false_detections == 0; }});
  return rows;
}

std::string missedLine(const std::vector<std::string>& missed) {
  if (missed.empty()) return "The target meets every goal here.\n\n";
  std::string out = "**Goals not met by the target:** ";
  for (std::size_t i = 0; i < missed.size(); ++i) out += (i ? "; " : "") + missed[i];
  return out + ".\n\n";
}

}  // namespace

std::string realSceneSection(const Settings& settings, const RealSceneStudyOptions& o, const RealSceneStudy& study) {
  const CameraModel& cam = settings.camera();
  std::string md = "## Real scenes: the target over photographs\n\n";
  md += format(
      "%d stills, %d negatives and %d videos of %d frames (the target hidden for %d frames in the middle of each), "
      "%.0f s. `imagepro-cli render --scene real --frames %d --negatives %d --seed %d` writes the same stills and "
      "negatives, `imagepro-cli render --scene video --frames %d --hidden %d --seed N` the videos (N = %d to %d); "
      "the user manual describes them. The settings' target (disk R = %.0f mm on a %.0f mm black card) and camera "
      "(%dx%d, d0 = %.1f mm, pixel %.3f mm%s) over the %zu photographs of %s. Stills: the target 0.4-2.5 m away, "
      "tilted 0-60 deg, paper white 170-235 and card black 10-40, light +-40 %% (a ramp or a vignette), optical blur "
      "0.5-1.6 px, motion blur 2-6 px on a third of them, noise sigma 1-6, JPEG quality 40-95; a negative is a still's "
      "photograph and conditions without the target. Videos: one photograph each, the target moving at 0.4-1.4 m, "
      "light drifting +-30 %%, blur 0.8 px, noise sigma 2, JPEG 75.\n\n",
      o.stills, o.negatives, o.videos, o.video_frames, o.hidden, study.seconds, o.stills, o.negatives,
      static_cast<int>(o.seed), o.video_frames, o.hidden, static_cast<int>(o.seed),
      static_cast<int>(o.seed) + std::max(o.videos, 1) - 1, settings.target.radius_mm,
      settings.virtual_scene.card_size_mm, cam.width, cam.height, cam.image_plane_distance_mm, cam.pixel_size_mm[0],
      cam.distortion.isZero() ? ", no lens distortion" : ", with the settings' lens distortion", study.photos,
      study.backgrounds.c_str());
  md += "Each still goes through the default pipeline alone (tracking reset); each video is tracked frame to frame, "
        "as a camera's stream. The reference is the ArUco marker of the sections above (DICT_4X4_50, its black "
        "square as wide as the disk, on a white card of the target card's size), drawn by the same generator in the "
        "target's place: the same pose, photograph, paper and ink, light, blur, motion blur, noise and JPEG, frame "
        "by frame. It is found in every frame alone by `cv::aruco::detectMarkers` with its default parameters "
        "(adaptive thresholds over windows of 3-23 px) and sub-pixel corner refinement, and solved by IPPE. A pose "
        "is correct when its rotation error (the angle of R_true^-1 R_est) is at most 5 deg; medians and 95th "
        "percentiles are over every pose reported, correct or not. The goals are the target's. The evaluation "
        "test (`ctest -R RealScenes`) holds the default pipeline to floors on 120 stills and one video of seed 1: "
        "with that seed, this report's first 120 stills and its first video.\n\n";

  std::vector<std::string> missed;
  md += "### Stills and negatives\n\n";
  std::vector<Row> rows = stillRows();
  md += table(rows, study, missed) + "\n";
  md += missedLine(missed);

  if (o.videos > 0) {
    missed.clear();
    md += "### Videos\n\n";
    rows = poseRows(&DetectorTally::video, "the visible frames");
    rows.insert(rows.begin() + 3,
                Row{"poses while the target is hidden", "0",
                    [](const DetectorTally& d) { return format("%d of %d", d.found_in_hiding, d.hidden); },
                    [](const DetectorTally& d) { return d.found_in_hiding == 0; }});
    rows.push_back(Row{"first correct pose after the target reappears, frames later (each video)", "<= 3",
                       [](const DetectorTally& d) { return reacquisitions(d.reacquired_after); },
                       [](const DetectorTally& d) {
                         return std::all_of(d.reacquired_after.begin(), d.reacquired_after.end(),
                                            [](int a) { return a >= 0 && a <= 3; });
                       }});
    md += table(rows, study, missed) + "\n";
    md += missedLine(missed);
  }
  return md;
}

std::string webcamSection(const Settings& settings, const std::string& config, const RealSceneStudyOptions& o,
                          const RealSceneStudy& study) {
  const CameraModel& cam = settings.camera();
  std::string md = "## The webcam set: occluders, glare, dim light and a wide lens\n\n";
  md += format(
      "%d stills and %d negatives, %.0f s. `imagepro-cli render --scene real --webcam --config %s --frames %d "
      "--negatives %d --seed %d` writes the same frames. The real-scene stills above (the same ranges of distance, "
      "tilt, light, blur, motion blur, noise and JPEG, over the same photographs) seen through a webcam's wide lens: "
      "%dx%d, focal length %.0f px, principal point (%.1f, %.1f), k1 = %.3g px^-2, k2 = %.3g px^-4, p1 = %.3g, p2 = "
      "%.3g px^-1 (the settings file `%s`), and touched by the rig: a flat occluder 10-25 mm wide across the rim on "
      "%.0f %% of the stills (tape across the disk or a clamp reaching in, dark or grey, clear of the spots), a "
      "saturating glare 4-12 mm across on the paper on %.0f %%, a dim room (paper at grey 70-120) on %.0f %%. The "
      "ArUco marker is drawn in the target's place with the same occluder and glare in the same places of its plane. "
      "The thesis's Taylor inverse of this lens errs by up to %.3f px inside the frame%s.\n\n",
      o.stills, o.negatives, study.seconds, config.c_str(), o.stills, o.negatives, static_cast<int>(o.seed), cam.width,
      cam.height, cam.fu(), cam.u0(), cam.v0(), cam.distortion.k1, cam.distortion.k2, cam.distortion.p1,
      cam.distortion.p2, config.c_str(), 100.0 * o.rig.occluder_fraction, 100.0 * o.rig.glare_fraction,
      100.0 * o.rig.dim_fraction, taylorInverseErrorPx(cam),
      taylorInverseErrorPx(cam) > kTaylorInverseLimitPx
          ? format(", over the %.2f px limit, so the exact inverse is used without being asked", kTaylorInverseLimitPx)
                .c_str()
          : "");
  std::vector<std::string> missed;
  std::vector<Row> rows = stillRows();
  rows[1].goal = ">= 95 %";
  rows[1].met = [](const DetectorTally& d) { return d.stills.correct >= 0.95 * d.stills.frames; };
  md += table(rows, study, missed) + "\n";
  md += missedLine(missed);
  md += "### The target's stills by what the rig did to them\n\n"
        "| effects | stills | correct pose | off by more than 5 deg | rotation error, median | statuses without a "
        "pose |\n| --- | ---: | ---: | ---: | ---: | --- |\n";
  for (const auto& [name, t] : study.target.by_effect)
    md += format("| %s | %d | %s | %d | %s | %s |\n", name.c_str(), t.frames, share(t.correct, t.frames).c_str(),
                 t.wrong, figure(quantile(t.rotation_deg, 0.5), "deg").c_str(), statuses(t.misses).c_str());
  return md + "\n";
}

}  // namespace imagepro::studies
