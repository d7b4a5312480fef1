#pragma once
// The targets of a set told in one frame (FrameResult::set_of_targets): gathered from
// several searches of the frame (the stage chain's passes, each tracked target's region,
// the whole frame), each physical target once, and two prints coded as the same member
// both DuplicateTarget, so a second print never passes for the first.
#include <vector>

#include "core/pipeline/frame_result.h"
#include "core/settings/target_set.h"

namespace imagepro {

// Whether a search's target is a row of the frame: a member told (with a pose, or two:
// AmbiguousPose), a target of no member (UnknownTarget) or a duplicate.
bool isToldTarget(const TargetSummary& t);

// Adds `t` (isToldTarget) to `told` unless a target already there lies where it does (within
// half its rim's smaller semi-axis: the same print, found again by another search; a member
// told replaces an UnknownTarget there). A target
// elsewhere with the same id makes both DuplicateTarget.
void addToldTarget(std::vector<TargetSummary>& told, const TargetSummary& t);

// Whether `told` holds every member of `set` (a pose or AmbiguousPose).
bool everyMemberTold(const std::vector<TargetSummary>& told, const std::vector<TargetSpec>& set);

// Whether member `id` is in `told` with a pose (Ok) or AmbiguousPose.
bool memberTold(const std::vector<TargetSummary>& told, int id);

// Of `targets`, the one the frame's own fields show: member `shown` when it was told, else
// the first member of the set told with a pose, else the first told (isToldTarget); -1
// when none was told.
int shownTarget(const std::vector<TargetSummary>& targets, const std::vector<TargetSpec>& set, int shown);

// Sorts `told` in the set's order, targets of no member (and duplicates) last, left to right.
void sortInSetOrder(std::vector<TargetSummary>& told, const std::vector<TargetSpec>& set);

}  // namespace imagepro
