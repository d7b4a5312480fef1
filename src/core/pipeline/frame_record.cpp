#include "core/pipeline/frame_record.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/common/pose_csv.h"
#include "core/pipeline/told_targets.h"

namespace imagepro {

namespace {

FieldValue none() { return {}; }
FieldValue number(double v) { return {FieldValue::Kind::Number, v, {}}; }
FieldValue text(std::string t) { return {FieldValue::Kind::Text, 0.0, std::move(t)}; }

FieldValue frameLabelOf(const FrameResult& r, int) { return text(frameLabel(r)); }
FieldValue frameIndexOf(const FrameResult& r, int) { return number(static_cast<double>(r.index)); }
FieldValue statusOf(const FrameResult& r, int) { return text(std::string(statusName(r.status))); }
FieldValue poseOf(const FrameResult& r, int k) {
  return ok(r.status) && r.pose ? number(poseColumnValues(*r.pose)[static_cast<std::size_t>(k)]) : none();
}
FieldValue truthOf(const FrameResult& r, int k) {
  return r.truth ? number(poseColumnValues(*r.truth)[static_cast<std::size_t>(k)]) : none();
}
FieldValue timestampOf(const FrameResult& r, int) { return number(r.timestamp_s); }
FieldValue rectSide(const cv::Rect& box, int k) {
  if (box.empty()) return none();
  const std::array<int, 4> sides{box.x, box.y, box.width, box.height};
  return number(sides[static_cast<std::size_t>(k)]);
}
FieldValue searchOf(const FrameResult& r, int k) { return rectSide(r.search_region, k); }
FieldValue detectedOf(const FrameResult& r, int k) { return rectSide(r.detected_region, k); }
FieldValue stageTimeOf(const FrameResult& r, int s) { return number(r.times.us[static_cast<std::size_t>(s)]); }
FieldValue rimSeenOf(const FrameResult& r, int) { return r.rim_seen > 0.0 ? number(r.rim_seen) : none(); }
FieldValue spotErrorOf(const FrameResult& r, int) { return r.spot_error_px >= 0.0 ? number(r.spot_error_px) : none(); }
FieldValue rimErrorOf(const FrameResult& r, int) { return r.rim_error_px >= 0.0 ? number(r.rim_error_px) : none(); }
FieldValue lensInverseOf(const FrameResult& r, int) {
  return r.reached == ApplicationLevel::Reconstruction ? text(std::string(lensInverseName(r.lens_inverse))) : none();
}
FieldValue targetIdOf(const FrameResult& r, int) {
  return r.target_id >= 0 ? number(static_cast<double>(r.target_id)) : none();
}
FieldValue nameOf(const FrameResult& r, int) { return r.name.empty() ? none() : text(r.name); }
FieldValue inReferenceOf(const FrameResult& r, int k) {
  return ok(r.status) && r.pose_in_reference ? number(poseColumnValues(*r.pose_in_reference)[static_cast<std::size_t>(k)])
                                             : none();
}
FieldValue inWorldOf(const FrameResult& r, int k) {
  return ok(r.status) && r.pose_in_world ? number(poseColumnValues(*r.pose_in_world)[static_cast<std::size_t>(k)])
                                         : none();
}
FieldValue pairOf(const FrameResult& r, int k) {
  if (!r.measured_pair) return none();
  return number(k == 0 ? r.measured_pair->distance_mm : r.measured_pair->angle_deg);
}

constexpr std::uint16_t kCsvAndJson = kDataOutCsv | kReconstructCsv | kReconstructJson;
constexpr std::uint16_t kEveryOutput = kCsvAndJson | kStreamJson;
// The poses in the chosen frames and the pair's readout: reconstruct's CSV keeps its
// columns (a pose per row); data out, the JSON, the stream and Python carry them.
constexpr std::uint16_t kFramesOutputs = kDataOutCsv | kReconstructJson | kStreamJson | kPython;

std::vector<FrameField> buildFields() {
  // Names that are built (a truth column, a stage's time) live here, for the views below.
  static const std::array<std::string, 6> truthNames = [] {
    std::array<std::string, 6> names;
    for (std::size_t k = 0; k < 6; ++k) names[k] = "true_" + std::string(kPoseColumnNames[k]);
    return names;
  }();
  static const std::array<std::string, kStageCount> stageNames = [] {
    std::array<std::string, kStageCount> names;
    for (std::size_t s = 0; s < kStageCount; ++s) names[s] = std::string(stageName(static_cast<Stage>(s))) + "_us";
    return names;
  }();
  std::vector<FrameField> f;
  f.push_back({"frame", "", "", "the file name for file input, else the frame's index", 0, kCsvAndJson, frameLabelOf});
  f.push_back({"frame", "", "", "the frame's index", 0, kStreamJson, frameIndexOf});
  f.push_back({"status", "", "", "ok, or the name of the first stage's failure", 0, kEveryOutput, statusOf});
  for (int k = 0; k < 6; ++k)
    f.push_back({kPoseColumnNames[static_cast<std::size_t>(k)], k < 3 ? "deg" : "mm", "",
                 "the pose (docs/conventions.md); none unless the status is ok", 6, kEveryOutput, poseOf, k});
  for (int k = 0; k < 6; ++k)
    f.push_back({truthNames[static_cast<std::size_t>(k)], k < 3 ? "deg" : "mm", "", "the ground-truth pose (virtual frames)",
                 6, kTruthCsv, truthOf, k});
  f.push_back({"timestamp_s", "s", "", "the frame's time", 6, kDataOutCsv | kStreamJson | kPython, timestampOf});
  static constexpr std::array<std::string_view, 4> kSearch{"search_x", "search_y", "search_w", "search_h"};
  static constexpr std::array<std::string_view, 4> kDetected{"target_x", "target_y", "target_w", "target_h"};
  for (int k = 0; k < 4; ++k)
    f.push_back({kSearch[static_cast<std::size_t>(k)], "px", "", "the searched region (thesis: green)", 0, kDataOutCsv,
                 searchOf, k});
  for (int k = 0; k < 4; ++k)
    f.push_back({kDetected[static_cast<std::size_t>(k)], "px", "", "the target's box (thesis: blue)", 0, kDataOutCsv,
                 detectedOf, k});
  for (int s = 0; s < static_cast<int>(kStageCount); ++s)
    f.push_back({stageNames[static_cast<std::size_t>(s)], "us", "", "the stage's wall time", 1, kDataOutCsv, stageTimeOf, s});
  f.push_back({"rim_seen", "", "Rim seen",
               "the share of the rim the pose was fitted to (0..1; less where an occluder hides part of it), "
               "none without a fitted rim",
               3, kEveryOutput | kPython | kResultsText, rimSeenOf});
  f.push_back({"target", "", "Target id",
               "the id of the settings' target the frame's target is (0 for the one target of \"target\", "
               "else its \"targets\" entry's), none when no target was told (UnknownTarget: a target whose "
               "offset spot codes none)",
               0, kEveryOutput | kPython | kResultsText, targetIdOf});
  f.push_back({"spot_error_px", "px", "Spot err",
               "the self-check: how far the pose puts a spot's image from where it was found (the larger of "
               "the two; PoseInconsistent beyond max_spot_error_px, or with the rim error when both pass 0.5 of "
               "their limits), none when no pose was checked",
               3, kReconstructJson | kPython | kResultsText, spotErrorOf});
  f.push_back({"rim_error_px", "px", "Rim err",
               "the self-check: the RMS distance of the rim's contour points from the pose's rim "
               "(PoseInconsistent beyond max_rim_error_px, or with the spot error when both pass 0.5 of their "
               "limits), none when no pose was checked",
               3, kReconstructJson | kPython | kResultsText, rimErrorOf});
  f.push_back({"lens_inverse", "", "Lens",
               "which inverse of the lens model corrected the features: none, taylor, exact, exact-wide-lens; "
               "none before the reconstruction stage",
               0, kReconstructJson | kPython | kResultsText, lensInverseOf});
  static const std::array<std::array<std::string, 6>, 2> framedNames = [] {
    std::array<std::array<std::string, 6>, 2> names;
    for (std::size_t k = 0; k < 6; ++k) {
      names[0][k] = "world_" + std::string(kPoseColumnNames[k]);
      names[1][k] = "ref_" + std::string(kPoseColumnNames[k]);
    }
    return names;
  }();
  for (int k = 0; k < 6; ++k)
    f.push_back({framedNames[0][static_cast<std::size_t>(k)], k < 3 ? "deg" : "mm", "",
                 "the pose in the world frame \"Set origin\" stored (settings frames.origin); none without one",
                 6, kFramesOutputs, inWorldOf, k});
  for (int k = 0; k < 6; ++k)
    f.push_back({framedNames[1][static_cast<std::size_t>(k)], k < 3 ? "deg" : "mm", "",
                 "the pose in the reference target's frame (settings frames.reference_target); none for the "
                 "reference itself, or when it was not found",
                 6, kFramesOutputs, inReferenceOf, k});
  f.push_back({"pair_distance_mm", "mm", "Pair distance",
               "the distance between the centres of the two targets of settings frames.measured_targets, when "
               "both were found",
               3, kFramesOutputs | kResultsText, pairOf, 0});
  f.push_back({"pair_angle_deg", "deg", "Pair angle",
               "the angle between the normals of the two targets of settings frames.measured_targets, when both "
               "were found",
               3, kFramesOutputs | kResultsText, pairOf, 1});
  f.push_back({"name", "", "", "the file name, for file input", 0, kStreamJson, nameOf});
  return f;
}

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

}  // namespace

std::span<const FrameField> frameFields() {
  static const std::vector<FrameField> fields = buildFields();
  return fields;
}

std::string fieldCsv(const FrameField& field, const FieldValue& value) {
  switch (value.kind) {
    case FieldValue::Kind::None: return {};
    case FieldValue::Kind::Number: return fixed(value.number, field.decimals);
    case FieldValue::Kind::Text: return csvField(value.text);
  }
  return {};
}

std::string fieldJson(const FrameField& field, const FieldValue& value) {
  switch (value.kind) {
    case FieldValue::Kind::None: return "null";
    // JSON has no NaN or infinity: such a value is null, never invalid JSON.
    case FieldValue::Kind::Number: return std::isfinite(value.number) ? fixed(value.number, field.decimals) : "null";
    case FieldValue::Kind::Text:
      // The library escapes it; bytes that are not UTF-8 become U+FFFD.
      return nlohmann::json(value.text).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  }
  return "null";
}

std::string recordCsvHeader(std::uint16_t output) {
  std::string header;
  for (const FrameField& f : frameFields()) {
    if (!(f.outputs & output)) continue;
    if (!header.empty()) header += ',';
    header += f.name;
  }
  return header;
}

std::string recordCsvRow(const FrameResult& result, std::uint16_t output) {
  std::string row;
  bool first = true;
  for (const FrameField& f : frameFields()) {
    if (!(f.outputs & output)) continue;
    if (!first) row += ',';
    first = false;
    row += fieldCsv(f, f.value(result, f.arg));
  }
  return row;
}

std::size_t recordRowCount(const FrameResult& frame) {
  if (!frame.set_of_targets) return 1;
  std::size_t n = 0;
  for (const TargetSummary& t : frame.targets) n += isToldTarget(t) ? 1 : 0;
  return std::max<std::size_t>(n, 1);
}

void recordRow(const FrameResult& frame, std::size_t k, FrameResult& row) {
  row.index = frame.index;
  row.timestamp_s = frame.timestamp_s;
  row.name = frame.name;
  row.status = frame.status;
  row.reached = frame.reached;
  row.image_size = frame.image_size;
  row.search_region = frame.search_region;
  row.detected_region = frame.detected_region;
  row.threshold = frame.threshold;
  row.pose = frame.pose;
  row.target_id = frame.target_id;
  row.truth = frame.truth;
  row.pose_in_reference = frame.pose_in_reference;
  row.pose_in_world = frame.pose_in_world;
  row.measured_pair = frame.measured_pair;
  row.set_of_targets = frame.set_of_targets;
  row.rim_seen = frame.rim_seen;
  row.spot_error_px = frame.spot_error_px;
  row.rim_error_px = frame.rim_error_px;
  row.lens_inverse = frame.lens_inverse;
  row.times = frame.times;
  if (!frame.set_of_targets) return;
  std::size_t seen = 0;
  for (const TargetSummary& t : frame.targets) {
    if (!isToldTarget(t) || seen++ != k) continue;
    row.status = t.status;
    row.pose = t.pose;
    row.target_id = t.target_id;  // a DuplicateTarget row names the id found twice
    row.search_region = t.search_region;
    row.detected_region = t.bbox;
    row.rim_seen = t.rim_seen;
    row.spot_error_px = t.spot_error_px;
    row.rim_error_px = t.rim_error_px;
    row.pose_in_reference = t.pose_in_reference;
    row.pose_in_world = t.pose_in_world;
    return;
  }
}

std::string recordCsvRows(const FrameResult& frame, std::uint16_t output) {
  if (!frame.set_of_targets) return recordCsvRow(frame, output);
  std::string rows;
  FrameResult row;
  for (std::size_t k = 0; k < recordRowCount(frame); ++k) {
    recordRow(frame, k, row);
    if (k) rows += '\n';
    rows += recordCsvRow(row, output);
  }
  return rows;
}

std::string recordJsonMembers(const FrameResult& result, FrameOutput output) {
  std::string members;
  for (const FrameField& f : frameFields()) {
    if (!(f.outputs & output)) continue;
    const FieldValue v = f.value(result, f.arg);
    if (v.kind == FieldValue::Kind::None && output == kReconstructJson) continue;
    if (!members.empty()) members += ',';
    members += '"';
    members += f.name;
    members += "\":";
    members += fieldJson(f, v);
  }
  return members;
}

std::string poseJsonMembers(const Pose* pose) {
  std::string members;
  const auto values = pose ? poseColumnValues(*pose) : std::array<double, 6>{};
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (k) members += ',';
    members += '"';
    members += kPoseColumnNames[k];
    members += "\":";
    members += pose && std::isfinite(values[k]) ? fixed(values[k], 6) : std::string("null");
  }
  return members;
}

}  // namespace imagepro
