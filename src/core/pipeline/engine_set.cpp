// The engine's frame loop for a set of targets (settings "targets"): each member found in
// the last frame is searched for in its own tracked region, as the lone target is; the
// whole frame is searched, with every target reconstructed, whenever a member is missing
// and on a cadence; the targets told are gathered once each (told_targets.h).
#include <opencv2/core.hpp>

#include <algorithm>
#include <cstdint>

#include "core/pipeline/engine_impl.h"
#include "core/pipeline/told_targets.h"

namespace imagepro {

namespace {

void addTimes(const StageTimes& from, StageTimes& to) {
  for (Stage s : {Stage::Crop, Stage::Threshold, Stage::Edges, Stage::Connectivity, Stage::Ellipse,
                  Stage::Reconstruction})
    to[s] += from[s];
}

// The region search's one target, as a told target of the set (or nothing told).
bool toldInRegion(const FrameResult& search, cv::Rect region, TargetSummary& t) {
  if (search.targets.empty() || search.target_id < 0) return false;
  if (!ok(search.status) && search.status != Status::AmbiguousPose) return false;
  t = search.targets.front();
  t.status = search.status;
  t.pose = search.pose;
  t.target_id = search.target_id;
  t.search_region = region;
  t.rim_seen = search.rim_seen;
  t.spot_error_px = search.spot_error_px;
  t.rim_error_px = search.rim_error_px;
  t.spots = search.spots;
  return true;
}

const TargetSummary* toldMember(const std::vector<TargetSummary>& told, int id) {
  for (const TargetSummary& t : told)
    if (t.target_id == id && (ok(t.status) || t.status == Status::AmbiguousPose)) return &t;
  return nullptr;
}

}  // namespace

// The share of a rim's box that its card covers, about its centre: the card (130 mm) is
// 1.3 times the disk, and a steep view's card reaches further along the minor axis.
constexpr double kCardOverRimBox = 1.6;

void Engine::Impl::searchBehindTold(const cv::Mat& grey, StageTimes& spent) {
  // The whole-frame search with every target reconstructed skips what only the lone
  // target's search does (the ellipse stage's runners-up, a rim drawn from its spots), so a
  // far, blurred target beside a clear one, or alone, is missed there; with the members
  // told hidden under the frame's mean grey, the lone target's search finds it.
  const int missing = static_cast<int>(std::count_if(settings.targets.begin(), settings.targets.end(),
                                                     [&](const TargetSpec& m) { return !memberTold(told, m.id); }));
  for (int attempt = 0; attempt < missing; ++attempt) {
    grey.copyTo(masked);
    const auto fill = static_cast<std::uint8_t>(cv::mean(grey)[0]);
    const cv::Rect frame(0, 0, grey.cols, grey.rows);
    for (const TargetSummary& t : told) {
      // Only members told: a print the search could not tell (UnknownTarget) is searched
      // again, and the lone target's search may tell it.
      if (t.target_id < 0 || t.status == Status::UnknownTarget || t.status == Status::DuplicateTarget) continue;
      const double w = kCardOverRimBox * t.bbox.width, h = kCardOverRimBox * t.bbox.height;
      const cv::Rect card(static_cast<int>(t.ellipse.cx - 0.5 * w), static_cast<int>(t.ellipse.cy - 0.5 * h),
                          static_cast<int>(w) + 1, static_cast<int>(h) + 1);
      const cv::Rect hidden = card & frame;
      for (int y = hidden.y; y < hidden.y + hidden.height; ++y) {
        std::uint8_t* row = masked.ptr<std::uint8_t>(y);
        std::fill(row + hidden.x, row + hidden.x + hidden.width, fill);
      }
    }
    runStageChain(settings, masked, cv::Rect(), TargetsToReconstruct::Best, chain, masked_search);
    addTimes(masked_search.times, spent);
    TargetSummary t;
    if (!toldInRegion(masked_search, masked_search.search_region, t) || memberTold(told, t.target_id)) return;
    addToldTarget(told, t);
  }
}

void Engine::Impl::forgetTracks() {
  for (MemberTrack& m : members) {
    m.tracker.reset();
    m.last_pose.reset();
    m.found = false;
  }
}

void Engine::Impl::runSet(FrameResult& out, bool stream) {
  const PipelineOptions& o = settings.pipeline;
  const cv::Mat& grey = frame.image;
  // One track per member, rebuilt when the set's ids change.
  const bool same = members.size() == settings.targets.size() &&
                    std::equal(members.begin(), members.end(), settings.targets.begin(),
                               [](const MemberTrack& m, const TargetSpec& t) { return m.id == t.id; });
  if (!same) {
    members.assign(settings.targets.size(), MemberTrack{});
    for (std::size_t i = 0; i < members.size(); ++i) members[i].id = settings.targets[i].id;
  }
  if (!same || members_stale) {
    for (std::size_t i = 0; i < members.size(); ++i) {
      members[i].alone = settings;
      members[i].alone.targets = {settings.targets[i]};
    }
    members_stale = false;
  }
  const bool tracked = stream && reachesEllipse(o.level);
  if (!tracked) forgetTracks();

  told.clear();
  StageTimes spent{};
  cv::Rect searched;
  bool searchedAny = false;
  for (MemberTrack& m : members) {
    if (!tracked || !m.found) continue;
    const auto region = m.tracker.estimate(o.tracking, settings.camera(),
                                           geometryOf(settings.targets, m.id, settings.target), last_track_time,
                                           grey.size());
    if (!region) continue;
    runStageChain(m.alone, grey, *region, TargetsToReconstruct::Best, chain, search,
                  m.last_pose ? &*m.last_pose : nullptr);
    addTimes(search.times, spent);
    searched = searchedAny ? (searched | *region) : *region;
    searchedAny = true;
    TargetSummary t;
    if (toldInRegion(search, *region, t)) addToldTarget(told, t);
  }
  const bool wholeFrame = !tracked || !everyMemberTold(told, settings.targets) ||
                          ++frames_since_whole_search >= kWholeFrameEveryFrames;
  if (wholeFrame) {
    frames_since_whole_search = 0;
    runStageChain(settings, grey, cv::Rect(), TargetsToReconstruct::Every, chain, search);
    addTimes(search.times, spent);
    searched = search.search_region;
    for (TargetSummary& t : search.targets) {
      if (!isToldTarget(t)) continue;
      t.search_region = search.search_region;
      addToldTarget(told, t);
    }
    if (!everyMemberTold(told, settings.targets) && static_cast<int>(o.level) >= static_cast<int>(ApplicationLevel::Reconstruction))
      searchBehindTold(grey, spent);
  }

  // The last search's report is the frame's (its histogram, threshold, edges and the
  // buffers shown); its targets are those told by every search.
  std::swap(out.status, search.status);
  out.reached = search.reached;
  out.image_size = search.image_size;
  out.search_region = searched;
  out.threshold = search.threshold;
  std::swap(out.histogram, search.histogram);
  out.edge_pixels = search.edge_pixels;
  out.paths = search.paths;
  out.lens_inverse = search.lens_inverse;
  out.contour_points.clear();
  if (told.empty()) {
    std::swap(out.targets, search.targets);
  } else {
    sortInSetOrder(told, settings.targets);
    std::swap(out.targets, told);
  }
  for (Stage s : {Stage::Crop, Stage::Threshold, Stage::Edges, Stage::Connectivity, Stage::Ellipse,
                  Stage::Reconstruction})
    out.times[s] = spent[s];
  adoptShownTarget(settings, out);
  last_target_id = out.target_id;

  // Each member's tracker learns from its own target, found or missed.
  const auto start = EngineClock::now();
  for (MemberTrack& m : members) {
    const TargetSummary* t = tracked ? toldMember(out.targets, m.id) : nullptr;
    m.found = t != nullptr;
    if (t) {
      m.tracker.observe(last_track_time, cv::Rect2d(t->bbox), ok(t->status) ? t->pose : std::nullopt);
      m.last_pose = ok(t->status) ? t->pose : std::nullopt;
    } else {
      m.tracker.observeMiss();
      m.last_pose.reset();
    }
  }
  out.times[Stage::Tracking] = microsecondsSince(start);
}

}  // namespace imagepro
