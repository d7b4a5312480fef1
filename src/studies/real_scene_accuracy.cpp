// The accuracy study's real-scene part: the frames, both detectors on them, and the values of
// docs/accuracy.md's real.* and webcam.* places; the prose around them lives in the doc.
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

// The sentence after a table of goals: met, or the measures whose goals the target missed.
std::string verdict(const std::vector<std::string>& missed) {
  if (missed.empty()) return "The target meets every goal here.";
  std::string out = "**Goals not met by the target:** ";
  for (std::size_t i = 0; i < missed.size(); ++i) out += (i ? "; " : "") + missed[i];
  return out + ".";
}

}  // namespace

void measureRealScenes(const Settings& settings, const RealSceneStudyOptions& o, const RealSceneStudy& study,
                       MeasuredValues& v) {
  const CameraModel& cam = settings.camera();
  const int seed = static_cast<int>(o.seed);
  v["real.stills"] = format("%d", o.stills);
  v["real.negatives"] = format("%d", o.negatives);
  v["real.videos"] = format("%d", o.videos);
  v["real.video_frames"] = format("%d", o.video_frames);
  v["real.hidden"] = format("%d", o.hidden);
  v["real.seconds"] = format("%.0f", study.seconds);
  v["real.stills_command"] =
      format("`imagepro-cli render --scene real --frames %d --negatives %d --seed %d`", o.stills, o.negatives, seed);
  v["real.videos_command"] =
      format("`imagepro-cli render --scene video --frames %d --hidden %d --seed N`", o.video_frames, o.hidden);
  v["real.first_seed"] = format("%d", seed);
  v["real.last_seed"] = format("%d", seed + std::max(o.videos, 1) - 1);
  v["real.disk_radius_mm"] = format("%.0f", settings.target.radius_mm);
  v["real.card_mm"] = format("%.0f", settings.virtual_scene.card_size_mm);
  v["real.image_size"] = format("%dx%d", cam.width, cam.height);
  v["real.d0_mm"] = format("%.1f", cam.image_plane_distance_mm);
  v["real.pixel_mm"] = format("%.3f", cam.pixel_size_mm[0]);
  v["real.lens"] = cam.distortion.isZero() ? "no lens distortion" : "with the settings' lens distortion";
  v["real.photos"] = format("%zu", study.photos);
  v["real.backgrounds"] = study.backgrounds;

  std::vector<std::string> missed;
  v["real.stills_table"] = table(stillRows(), study, missed);
  v["real.stills_verdict"] = verdict(missed);
  if (o.videos > 0) {
    missed.clear();
    std::vector<Row> rows = poseRows(&DetectorTally::video, "the visible frames");
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
    v["real.videos_table"] = table(rows, study, missed);
    v["real.videos_verdict"] = verdict(missed);
  } else {
    v["real.videos_table"] = "No videos in this run (--videos 0).";
    v["real.videos_verdict"] = "";
  }
}

void measureWebcamSet(const Settings& settings, const std::string& config, const RealSceneStudyOptions& o,
                      const RealSceneStudy& study, MeasuredValues& v) {
  const CameraModel& cam = settings.camera();
  v["webcam.stills"] = format("%d", o.stills);
  v["webcam.negatives"] = format("%d", o.negatives);
  v["webcam.seconds"] = format("%.0f", study.seconds);
  v["webcam.command"] = format("`imagepro-cli render --scene real --webcam --config %s --frames %d --negatives %d "
                               "--seed %d`",
                               config.c_str(), o.stills, o.negatives, static_cast<int>(o.seed));
  v["webcam.image_size"] = format("%dx%d", cam.width, cam.height);
  v["webcam.focal_px"] = format("%.0f", cam.fu());
  v["webcam.principal_point_px"] = format("%.1f, %.1f", cam.u0(), cam.v0());
  v["webcam.k1"] = format("%.3g", cam.distortion.k1);
  v["webcam.k2"] = format("%.3g", cam.distortion.k2);
  v["webcam.p1"] = format("%.3g", cam.distortion.p1);
  v["webcam.p2"] = format("%.3g", cam.distortion.p2);
  v["webcam.config"] = "`" + config + "`";
  v["webcam.occluder_percent"] = format("%.0f", 100.0 * o.rig.occluder_fraction);
  v["webcam.glare_percent"] = format("%.0f", 100.0 * o.rig.glare_fraction);
  v["webcam.dim_percent"] = format("%.0f", 100.0 * o.rig.dim_fraction);
  const double taylor = taylorInverseErrorPx(cam);
  v["webcam.taylor_error_px"] = format("%.3f", taylor);
  v["webcam.exact_inverse"] =
      taylor > kTaylorInverseLimitPx
          ? format(", over the %.2f px limit, so the exact inverse is used without being asked", kTaylorInverseLimitPx)
          : "";

  std::vector<std::string> missed;
  std::vector<Row> rows = stillRows();
  rows[1].goal = ">= 95 %";
  rows[1].met = [](const DetectorTally& d) { return d.stills.correct >= 0.95 * d.stills.frames; };
  v["webcam.stills_table"] = table(rows, study, missed);
  v["webcam.verdict"] = verdict(missed);
  std::string effects =
      "| effects | stills | correct pose | off by more than 5 deg | rotation error, median | statuses without a "
      "pose |\n| --- | ---: | ---: | ---: | ---: | --- |\n";
  for (const auto& [name, t] : study.target.by_effect)
    effects += format("| %s | %d | %s | %d | %s | %s |\n", name.c_str(), t.frames, share(t.correct, t.frames).c_str(),
                      t.wrong, figure(quantile(t.rotation_deg, 0.5), "deg").c_str(), statuses(t.misses).c_str());
  v["webcam.by_effect"] = effects;
}

}  // namespace imagepro::studies
