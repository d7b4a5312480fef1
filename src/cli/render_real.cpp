#include "cli/render_real.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "cli/render_output.h"
#include "core/common/pose_csv.h"
#include "core/source/real_scene_video.h"
#include "core/source/target_set_scene.h"

namespace imagepro::cli {

const std::vector<std::string> kRealSceneOptions = {"backgrounds", "negatives", "hidden", "webcam", "occluders", "glare",
                                                     "dim", "set"};
const std::vector<std::string> kVirtualOnlyOptions = {"mode",  "motion", "axis",  "amplitude",  "period",
                                                      "noise", "blur",   "clutter", "gradient", "white",
                                                      "black", "background", "rate", "pose",   "pattern",
                                                      "name",  "append"};

namespace {

namespace fs = std::filesystem;

int count(const Args& args, const std::string& key, int fallback, int most) {
  const int n = args.integer(key, fallback);
  if (n < 0 || n > most) throw UsageError("--" + key + " must be 0.." + std::to_string(most));
  return n;
}

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

// truth.csv's columns after the pose: what the frame shows and how it was degraded.
const char* kColumns = "in_view,background,white,black,light_shape,light_amplitude,light_gain,blur_px,motion_px,"
                       "motion_deg,noise_sigma,jpeg_quality,occluder_mm,occluder_grey,glare_mm";

std::string extraColumns(const RealSceneFrame& f) {
  const SceneConditions& c = f.conditions;
  return std::string(f.truth ? "1" : "0") + "," + csvField(fs::path(f.background).filename().string()) + "," +
         std::to_string(f.look.white) + "," + std::to_string(f.look.black) + "," +
         (c.light_shape == LightShape::Ramp ? "ramp" : "vignette") + "," + number(c.light_amplitude) + "," +
         number(c.light_gain) + "," + number(c.blur_sigma_px) + "," + number(c.motion_blur_px) + "," +
         number(c.motion_direction_deg) + "," + number(c.noise_sigma) + "," + std::to_string(c.jpeg_quality) + "," +
         number(f.rig.occluder.present ? f.rig.occluder.width_mm : 0.0) + "," +
         std::to_string(f.rig.occluder.present ? f.rig.occluder.level : 0) + "," +
         number(f.rig.glare.present ? f.rig.glare.diameter_mm : 0.0);
}

double fraction(const Args& args, const std::string& key, double fallback) {
  const double v = args.number(key, fallback);
  if (!(v >= 0.0 && v <= 1.0)) throw UsageError("--" + key + " must be 0..1 (the share of stills)");
  return v;
}

// --webcam sets the webcam set's shares; --occluders, --glare and --dim each override one.
RigEffects rigEffects(const Args& args) {
  const RigEffects base = args.has("webcam") ? kWebcamRigEffects : RigEffects{};
  return {fraction(args, "occluders", base.occluder_fraction), fraction(args, "glare", base.glare_fraction),
          fraction(args, "dim", base.dim_fraction)};
}

std::string frameName(const char* stem, int i) {
  char file[64];
  std::snprintf(file, sizeof file, "%s_%05d.png", stem, i);
  return file;
}

// A real-scene still of every member of the settings' set (--set): the first member at the
// still's own pose, each other one at a pose of its own drawn like a still's (0.4-2.5 m,
// tilted 0-60 deg, its card in the frame), its card's image clear of every card drawn
// before it by a tenth of the larger card; a member that finds no such place in 200
// draws is left out of the still (and of its truth).
struct SetPoses {
  std::vector<TargetGeometry> geometry;
  std::vector<Pose> poses;
  std::vector<int> ids;
};

cv::Rect2d cardBox(const CameraModel& cam, double card_mm, const Pose& pose) {
  const Eigen::Matrix3d R = rotationMatrix(pose);
  const Eigen::Vector3d T = translation(pose);
  double u0 = 1e18, v0 = 1e18, u1 = -1e18, v1 = -1e18;
  for (const double x : {-0.5, 0.5})
    for (const double y : {-0.5, 0.5}) {
      const Eigen::Vector2d p = projectIdeal(cam, R * Eigen::Vector3d(x * card_mm, y * card_mm, 0.0) + T);
      u0 = std::min(u0, p.x());
      v0 = std::min(v0, p.y());
      u1 = std::max(u1, p.x());
      v1 = std::max(v1, p.y());
    }
  return {u0, v0, u1 - u0, v1 - v0};
}

SetPoses setPoses(const Settings& settings, const Pose& first, std::uint64_t seed, int index) {
  const CameraModel& cam = settings.camera();
  const double card = settings.virtual_scene.card_size_mm;
  SetPoses out;
  std::vector<cv::Rect2d> boxes;
  cv::RNG rng(0x5e75e7ULL ^ (seed * 1000003ULL + static_cast<std::uint64_t>(index)));
  for (std::size_t m = 0; m < settings.targets.size(); ++m) {
    std::optional<Pose> at;
    for (int attempt = 0; attempt < (m == 0 ? 1 : 200) && !at; ++attempt) {
      const Pose pose = m == 0 ? first
                               : poseAlongRay(cam, Eigen::Vector2d(rng.uniform(0.0, cam.width - 1.0),
                                                                   rng.uniform(0.0, cam.height - 1.0)),
                                              rng.uniform(RealScenes::kMinDistanceMm, RealScenes::kMaxDistanceMm),
                                              rng.uniform(0.0, RealScenes::kMaxTiltDeg), rng.uniform(0.0, 360.0),
                                              rng.uniform(-180.0, 180.0));
      if (m > 0 && !cardInFrame(cam, settings.targets[m].geometry, card, pose, 4.0)) continue;
      const cv::Rect2d box = cardBox(cam, card, pose);
      const bool clear = std::none_of(boxes.begin(), boxes.end(), [&](const cv::Rect2d& b) {
        const double margin = 0.1 * std::max({b.width, b.height, box.width, box.height});
        const cv::Rect2d grown(b.x - margin, b.y - margin, b.width + 2 * margin, b.height + 2 * margin);
        return (grown & box).area() > 0.0;
      });
      if (clear) at = pose;
    }
    if (!at) continue;
    boxes.push_back(cardBox(cam, card, *at));
    out.geometry.push_back(settings.targets[m].geometry);
    out.poses.push_back(*at);
    out.ids.push_back(settings.targets[m].id);
  }
  return out;
}

// A real-scene video of every member of the settings' set (--scene video --set): the first
// member on the video's own path, member m on the path of the video of seed (seed, m), each
// hidden for `hidden` frames of its own, member m's window m * (hidden + 10) frames after
// the first's (and wrapped round the video), so that each member leaves and comes back
// while the others stay in view. The paths are independent, so cards cross: they are drawn
// far to near, and a member whose disk's image box meets a nearer card's is marked covered
// in its truth row (it may be partly or wholly out of sight).
struct SetVideo {
  std::vector<RealSceneVideo> paths;  // paths[0] is the video's own, without a hidden window
  int frames = 0, hidden = 0;

  bool hiddenAt(std::size_t m, int i) const {
    if (hidden <= 0 || frames <= 0) return false;
    const int begin = ((frames - hidden) / 2 + static_cast<int>(m) * (hidden + 10)) % frames;
    const int k = ((i - begin) % frames + frames) % frames;
    return k < hidden;
  }
};

}  // namespace

int renderRealScenes(const Args& args, const Settings& settings, bool video) {
  for (const auto& key : kVirtualOnlyOptions)
    if (args.has(key)) throw UsageError("--" + key + " applies to --scene virtual only");
  if (video && args.has("negatives")) throw UsageError("--negatives applies to --scene real only");
  if (!video && args.has("hidden")) throw UsageError("--hidden applies to --scene video only");
  for (const char* key : {"webcam", "occluders", "glare", "dim"})
    if (video && args.has(key)) throw UsageError(std::string("--") + key + " applies to --scene real only");
  const auto out_dir = args.value("out");
  if (!out_dir || out_dir->empty()) throw UsageError("--out DIR is required");
  const int frames = count(args, "frames", video ? 150 : 1, 100000);
  const int negatives = count(args, "negatives", 0, 100000);
  const int hidden = video ? count(args, "hidden", std::min(12, frames), frames) : 0;
  if (frames + negatives == 0) throw UsageError("nothing to render: --frames and --negatives are both 0");
  const int seed = args.integer("seed", static_cast<int>(settings.virtual_scene.seed));
  if (seed < 0) throw UsageError("--seed must be 0 or more");

  const std::string dir = args.valueOr("backgrounds", defaultBackgroundsDir());
  std::vector<std::string> photos = listBackgrounds(dir);
  if (photos.empty())
    throw InputError(dir + ": no photographs (JPEG or PNG) there; name a folder with --backgrounds or install " +
                     "Debian's opencv-doc (tools/setup.sh does)");
  const RealScenes scenes(settings, std::move(photos), rigEffects(args));

  const bool set = args.has("set");
  if (set && settings.targets.empty())
    throw UsageError("--set draws the settings' \"targets\" set, and these settings list none");
  // A set video's rows say too whether a nearer card covers the member (1) or not (0).
  const std::string columns =
      set ? std::string(kColumns) + (video ? ",target,covered" : ",target") : std::string(kColumns);
  RenderOutput out(*out_dir, false, poseCsvHeader(columns));
  const auto start = std::chrono::steady_clock::now();
  const RealSceneVideo sequence(scenes, static_cast<std::uint64_t>(seed), video ? frames : 0, set ? 0 : hidden);
  SetVideo setVideo{{}, frames, hidden};
  if (video && set) {
    setVideo.paths.reserve(settings.targets.size());
    setVideo.paths.emplace_back(scenes, static_cast<std::uint64_t>(seed), frames, 0);
    for (std::size_t m = 1; m < settings.targets.size(); ++m)
      setVideo.paths.emplace_back(scenes, static_cast<std::uint64_t>(seed) * 1000003ULL + m, frames, 0);
  }
  RealSceneFrame frame;
  std::string error;
  const int total = frames + negatives;
  for (int i = 0; i < total; ++i) {
    bool made = false;
    std::string name;
    if (video && set) {
      // The members not hidden at frame i, each on its own path, far to near.
      std::vector<std::size_t> shown;
      for (std::size_t m = 0; m < settings.targets.size(); ++m)
        if (!setVideo.hiddenAt(m, i)) shown.push_back(m);
      std::vector<Pose> at(settings.targets.size());
      for (const std::size_t m : shown) at[m] = setVideo.paths[m].poseAt(i);
      std::sort(shown.begin(), shown.end(), [&](std::size_t a, std::size_t b) { return at[a].tz_mm > at[b].tz_mm; });
      std::vector<TargetGeometry> geometry;
      std::vector<Pose> poses;
      for (const std::size_t m : shown) {
        geometry.push_back(settings.targets[m].geometry);
        poses.push_back(at[m]);
      }
      // Covered: a nearer card (drawn after it) meets its disk's image box.
      std::vector<std::pair<std::size_t, bool>> rows;
      const double card = settings.virtual_scene.card_size_mm;
      for (std::size_t k = 0; k < shown.size(); ++k) {
        const TargetGeometry& g = settings.targets[shown[k]].geometry;
        const cv::Rect2d disk = cardBox(settings.camera(), 2.0 * g.radius_mm, at[shown[k]]);
        bool covered = false;
        for (std::size_t j = k + 1; j < shown.size(); ++j)
          covered = covered || (cardBox(settings.camera(), card, at[shown[j]]) & disk).area() > 0.0;
        rows.emplace_back(shown[k], covered);
      }
      std::sort(rows.begin(), rows.end());
      const ScenePainter painter = [&](const cv::Mat& background, const Pose&, const TargetLook& look, cv::Mat& scene) {
        if (poses.empty()) {
          background.convertTo(scene, CV_32F);
          return;
        }
        cv::Mat drawn;
        composeTargets(background, settings.camera(), std::vector<TargetGeometry>(geometry.begin(), geometry.end() - 1),
                       look, std::vector<Pose>(poses.begin(), poses.end() - 1), drawn);
        composeTarget(drawn, settings.camera(), geometry.back(), look, poses.back(), scene);
      };
      made = sequence.frame(i, frame, error, painter);
      name = frameName("frame", i);
      if (!made) throw InputError("frame " + std::to_string(i) + ": " + error);
      if (rows.empty()) out.write(name, frame.image, poseCsvRow(name, Status::NoTarget, std::nullopt, extraColumns(frame) + ",,"));
      for (const auto& [m, covered] : rows)
        out.write(name, frame.image,
                  poseCsvRow(name, Status::Ok, at[m],
                             extraColumns(frame) + "," + std::to_string(settings.targets[m].id) + (covered ? ",1" : ",0")));
      continue;
    } else if (video) {
      made = sequence.frame(i, frame, error);
      name = frameName("frame", i);
    } else if (i < frames && set) {
      const SetPoses members = setPoses(settings, scenes.stillPose(static_cast<std::uint64_t>(seed), i),
                                        static_cast<std::uint64_t>(seed), i);
      const ScenePainter painter = [&](const cv::Mat& background, const Pose&, const TargetLook& look, cv::Mat& scene) {
        cv::Mat drawn;
        std::vector<Pose> rest(members.poses.begin() + 1, members.poses.end());
        std::vector<TargetGeometry> restGeometry(members.geometry.begin() + 1, members.geometry.end());
        composeTargets(background, settings.camera(), restGeometry, look, rest, drawn);
        composeTarget(drawn, settings.camera(), members.geometry.front(), look, members.poses.front(), scene);
      };
      made = scenes.still(static_cast<std::uint64_t>(seed), i, true, frame, error, painter);
      name = frameName("frame", i);
      if (!made) throw InputError("frame " + std::to_string(i) + ": " + error);
      for (std::size_t m = 0; m < members.poses.size(); ++m) {
        frame.truth = members.poses[m];
        out.write(name, frame.image,  // the same still under each of its targets' rows
                 
                  poseCsvRow(name, Status::Ok, frame.truth, extraColumns(frame) + "," + std::to_string(members.ids[m])));
      }
      continue;
    } else if (i < frames) {
      made = scenes.still(static_cast<std::uint64_t>(seed), i, true, frame, error);
      name = frameName("frame", i);
    } else {  // negatives continue the stills' draws, so they show other photographs
      made = scenes.still(static_cast<std::uint64_t>(seed), i, false, frame, error);
      name = frameName("negative", i - frames);
    }
    if (!made) throw InputError("frame " + std::to_string(i) + ": " + error);
    out.write(name, frame.image,
              poseCsvRow(name, frame.truth ? Status::Ok : Status::NoTarget, frame.truth, extraColumns(frame)));
  }
  out.commit();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr, "render: wrote %d frame%s over photographs of %s and %s in %.1f s\n", total,
               total == 1 ? "" : "s", dir.c_str(), out.truthPath().c_str(), seconds);
  return 0;
}

}  // namespace imagepro::cli
