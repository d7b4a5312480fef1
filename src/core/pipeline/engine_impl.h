#pragma once
// The engine's state, shared by its two frame loops: one target (engine.cpp) and a set of
// targets, one tracker each (engine_set.cpp).
#include <chrono>
#include <optional>
#include <vector>

#include "core/pipeline/engine.h"
#include "core/pipeline/stage_chain.h"
#include "core/tracking/tracker.h"

namespace imagepro {

using EngineClock = std::chrono::steady_clock;

inline double microsecondsSince(EngineClock::time_point start) {
  return std::chrono::duration<double, std::micro>(EngineClock::now() - start).count();
}

// Whether the application level runs the stage that finds the target.
inline bool reachesEllipse(ApplicationLevel level) {
  return static_cast<int>(level) >= static_cast<int>(ApplicationLevel::Ellipse);
}

// One member of the settings' set as the engine follows it.
struct MemberTrack {
  int id = -1;
  RegionTracker tracker;
  std::optional<Pose> last_pose;  // decides between the rim's two circles, as the lone target's
  bool found = false;             // in the last frame
  // The settings with this member as the set's only one: its region is searched for it
  // alone, its coding only and one reconstruction (another member there is UnknownTarget,
  // and the whole frame is searched).
  Settings alone;
};

// With a set, the whole frame is searched on this cadence even while every member is
// tracked, so a second print of a member (DuplicateTarget) or a print of none
// (UnknownTarget) entering the scene is reported within this many frames.
inline constexpr int kWholeFrameEveryFrames = 30;

struct Engine::Impl {
  Settings settings;
  RegionTracker tracker;
  Frame frame;
  StageChain chain;
  double last_track_time = -1.0;
  // The last frame's pose in a stream, which decides between the rim's two circles where
  // the spots cannot; forgotten after a miss and on stills.
  std::optional<Pose> last_pose;
  // The settings' target the tracker follows (target_set.h): its size projects the region.
  int last_target_id = -1;

  // A set of targets (settings "targets"): one tracker per member, in the set's order.
  std::vector<MemberTrack> members;
  FrameResult search;                  // one search's result (a member's region, the whole frame)
  FrameResult masked_search;           // a search of the frame with the targets told hidden
  cv::Mat masked;                      // that frame
  std::vector<TargetSummary> told;     // the frame's targets told so far
  int frames_since_whole_search = 0;
  bool members_stale = true;  // the settings changed: each member's `alone` is rebuilt

  void run(FrameResult& out);
  // The frame with a set of targets: `stream` tells a tracked stream from stills.
  void runSet(FrameResult& out, bool stream);
  void forgetTracks();
  // Searches the frame again, as for the lone target, with every target told so far hidden,
  // once per member still missing or until a search tells none more.
  void searchBehindTold(const cv::Mat& grey, StageTimes& spent);
};

}  // namespace imagepro
