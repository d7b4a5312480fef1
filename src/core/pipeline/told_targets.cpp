#include "core/pipeline/told_targets.h"

#include <algorithm>
#include <cmath>

namespace imagepro {

namespace {

bool givesAPose(Status s) { return s == Status::Ok || s == Status::AmbiguousPose; }

bool samePrint(const TargetSummary& a, const TargetSummary& b) {
  const double reach = 0.5 * std::min(std::min(a.ellipse.a, a.ellipse.b), std::min(b.ellipse.a, b.ellipse.b));
  return std::hypot(a.ellipse.cx - b.ellipse.cx, a.ellipse.cy - b.ellipse.cy) <= reach;
}

int setIndex(const std::vector<TargetSpec>& set, const TargetSummary& t) {
  if (t.status == Status::UnknownTarget || t.status == Status::DuplicateTarget) return static_cast<int>(set.size());
  for (std::size_t i = 0; i < set.size(); ++i)
    if (set[i].id == t.target_id) return static_cast<int>(i);
  return static_cast<int>(set.size());
}

}  // namespace

bool isToldTarget(const TargetSummary& t) {
  if (t.status == Status::UnknownTarget || t.status == Status::DuplicateTarget) return true;
  return t.target_id >= 0 && givesAPose(t.status);
}

void addToldTarget(std::vector<TargetSummary>& told, const TargetSummary& t) {
  for (std::size_t i = 0; i < told.size(); ++i) {
    if (!samePrint(told[i], t)) continue;
    // The same print: a later search that tells its member wins over one that could not.
    if (told[i].status != Status::UnknownTarget || t.status == Status::UnknownTarget) return;
    told.erase(told.begin() + static_cast<std::ptrdiff_t>(i));
    break;
  }
  bool duplicate = false;
  for (TargetSummary& k : told) {
    if (t.target_id < 0 || k.target_id != t.target_id) continue;
    k.status = Status::DuplicateTarget;
    duplicate = true;
  }
  told.push_back(t);
  if (duplicate) told.back().status = Status::DuplicateTarget;
}

bool memberTold(const std::vector<TargetSummary>& told, int id) {
  return std::any_of(told.begin(), told.end(),
                     [&](const TargetSummary& t) { return t.target_id == id && givesAPose(t.status); });
}

bool everyMemberTold(const std::vector<TargetSummary>& told, const std::vector<TargetSpec>& set) {
  return std::all_of(set.begin(), set.end(), [&](const TargetSpec& m) { return memberTold(told, m.id); });
}

int shownTarget(const std::vector<TargetSummary>& targets, const std::vector<TargetSpec>& set, int shown) {
  for (std::size_t i = 0; i < targets.size(); ++i)
    if (shown >= 0 && targets[i].target_id == shown && targets[i].status != Status::DuplicateTarget &&
        isToldTarget(targets[i]))
      return static_cast<int>(i);
  for (const TargetSpec& m : set)
    for (std::size_t i = 0; i < targets.size(); ++i)
      if (targets[i].target_id == m.id && ok(targets[i].status)) return static_cast<int>(i);
  for (std::size_t i = 0; i < targets.size(); ++i)
    if (isToldTarget(targets[i])) return static_cast<int>(i);
  return -1;
}

void sortInSetOrder(std::vector<TargetSummary>& told, const std::vector<TargetSpec>& set) {
  // Insertion sort: a set is small, and std::stable_sort may allocate.
  for (std::size_t i = 1; i < told.size(); ++i)
    for (std::size_t j = i; j > 0; --j) {
      const TargetSummary& a = told[j - 1];
      const TargetSummary& b = told[j];
      const int ia = setIndex(set, a), ib = setIndex(set, b);
      if (ia < ib || (ia == ib && a.ellipse.cx <= b.ellipse.cx)) break;
      std::swap(told[j - 1], told[j]);
    }
}

}  // namespace imagepro
