#pragma once
// What one pass of the pipeline produced for one frame: the status in words, what
// each stage found, the pose, and how long each stage took. The GUI and the CLI
// show it; data out writes it.
#include <opencv2/core.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/common/geometry.h"
#include "core/common/status.h"
#include "core/ellipse/ellipse.h"
#include "core/reconstruction/undistort.h"
#include "core/segmentation/histogram.h"
#include "core/settings/options.h"

namespace imagepro {

// Per-stage wall times of one frame in microseconds (thesis figure 5.1 stages).
enum class Stage : std::uint8_t { Grab, Crop, Threshold, Edges, Connectivity, Ellipse, Reconstruction, Tracking, kCount };
inline constexpr std::size_t kStageCount = static_cast<std::size_t>(Stage::kCount);
const char* stageName(Stage s);

struct StageTimes {
  std::array<double, kStageCount> us{};
  double& operator[](Stage s) { return us[static_cast<std::size_t>(s)]; }
  double operator[](Stage s) const { return us[static_cast<std::size_t>(s)]; }
  double total() const;
};

// One target found in the frame, in full-image pixel coordinates.
struct TargetSummary {
  Ellipse ellipse;
  double fit_error = 0.0;       // E_rel (direct fit) or 0
  double sampson_px = 0.0;      // mean Sampson distance of the path to the ellipse
  double bennett_score = 0.0, bennett_quality = 0.0, bennett_symmetry = 0.0;
  cv::Rect bbox;
  // When every target of the frame is reconstructed (stage_chain.h): its own outcome.
  Status status = Status::Stopped;
  std::optional<Pose> pose;
  int target_id = -1;  // the member of the settings' set it is (target_set.h); -1: none
  // With a set (FrameResult::set_of_targets), what FrameResult says of its one target, for
  // this one: where it was searched for, the self-check, its spots, its pose in the
  // reference target's frame and in the world frame (settings "frames").
  cv::Rect search_region;
  double rim_seen = 0.0, spot_error_px = -1.0, rim_error_px = -1.0;
  std::array<cv::Point2f, 2> spots{};
  std::optional<Pose> pose_in_reference, pose_in_world;
};

// The live readout between the two targets of settings frames.measured_targets.
struct TargetPairMeasure {
  double distance_mm = 0.0;  // between the two disks' centres
  double angle_deg = 0.0;    // between their normals
};

struct FrameResult {
  std::int64_t index = 0;
  double timestamp_s = 0.0;
  std::string name;                 // file name for file input
  Status status = Status::Ok;       // the first stage that failed, or Ok
  ApplicationLevel reached = ApplicationLevel::Source;  // last stage that ran
  cv::Size image_size;
  cv::Rect search_region;           // estimated region (thesis: green), whole frame if untracked
  cv::Rect detected_region;         // smallest box containing the target (thesis: blue)
  int threshold = -1;
  Histogram histogram{};            // of the searched region (a tracked region's on sampled rows)
  std::size_t edge_pixels = 0;
  std::size_t paths = 0;
  std::vector<TargetSummary> targets;
  std::optional<Pose> pose;
  // Which target of the settings' set (target_set.h) the reconstructed one is: its id
  // (kLoneTargetId without a set); -1 when none was told (no rim and spots, UnknownTarget).
  int target_id = -1;
  // The rim's two circles as poses, the one fitting the spots better first, when the spots
  // could not tell them apart: AmbiguousPose, or Ok with `pose` halfway between them.
  std::optional<std::array<Pose, 2>> ambiguous_poses;
  std::optional<Pose> truth;        // virtual frames
  // The pose in the reference target's frame and in the world frame (settings "frames",
  // docs/conventions.md); none when that frame is not chosen, or its target not found.
  std::optional<Pose> pose_in_reference, pose_in_world;
  std::optional<TargetPairMeasure> measured_pair;
  // True when the settings list a set of targets: every target told (targets, with its
  // id) is an output row of its own, and the fields above are the shown target's.
  bool set_of_targets = false;
  // Undistorted features the pose was computed from, for display (full-image pixels).
  std::vector<cv::Point2f> contour_points;
  std::array<cv::Point2f, 2> spots{};  // centre, offset
  // The share of the rim seen (reconstruction/rim_fit.h), 0..1; 0 when no rim was fitted.
  // Less than 1 where an occluder hides part of it; contour_points holds only the rim's.
  double rim_seen = 0.0;
  // The self-check's measures of the pose kept (docs/reconstruction.md): how far it puts a
  // spot's image from where it was found, and its rim's (RMS) from the contour points, in
  // px; negative when no pose was checked.
  double spot_error_px = -1.0, rim_error_px = -1.0;
  // Which inverse of the lens model corrected the features (undistort.h).
  LensInverse lens_inverse = LensInverse::None;
  StageTimes times;
};

// The frame's "frame" column (docs/conventions.md): the file name for file input, the index otherwise.
std::string frameLabel(const FrameResult& result);

}  // namespace imagepro
