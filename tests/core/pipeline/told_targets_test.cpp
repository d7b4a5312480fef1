#include "core/pipeline/told_targets.h"

#include <gtest/gtest.h>

namespace imagepro {
namespace {

TargetSummary found(int id, double cx, Status status = Status::Ok) {
  TargetSummary t;
  t.ellipse = Ellipse{cx, 100.0, 30.0, 20.0, 0.0};
  t.target_id = id;
  t.status = status;
  if (ok(status)) t.pose = Pose{};
  return t;
}

std::vector<TargetSpec> setOfIds(std::initializer_list<int> ids) {
  std::vector<TargetSpec> set;
  for (const int id : ids) set.push_back(TargetSpec{id, "", {}});
  return set;
}

TEST(ToldTargets, ThePrintFoundAgainIsKeptOnceAndASecondPrintIsADuplicate) {
  std::vector<TargetSummary> told;
  addToldTarget(told, found(1, 100.0));
  addToldTarget(told, found(1, 105.0));  // the same print, found by another search
  ASSERT_EQ(told.size(), 1u);
  EXPECT_EQ(told[0].status, Status::Ok);
  addToldTarget(told, found(1, 400.0));  // another print of member 1
  ASSERT_EQ(told.size(), 2u);
  EXPECT_EQ(told[0].status, Status::DuplicateTarget);
  EXPECT_EQ(told[1].status, Status::DuplicateTarget);
  EXPECT_FALSE(memberTold(told, 1));
}

TEST(ToldTargets, AMemberToldReplacesAnUnknownTargetOnTheSamePrint) {
  std::vector<TargetSummary> told;
  addToldTarget(told, found(-1, 100.0, Status::UnknownTarget));
  addToldTarget(told, found(2, 102.0));
  ASSERT_EQ(told.size(), 1u);
  EXPECT_EQ(told[0].target_id, 2);
  addToldTarget(told, found(-1, 101.0, Status::UnknownTarget));
  EXPECT_EQ(told.size(), 1u);
  EXPECT_FALSE(isToldTarget(found(3, 0.0, Status::SpotsNotFound)));
  EXPECT_TRUE(isToldTarget(found(3, 0.0, Status::AmbiguousPose)));
}

TEST(ToldTargets, SortedInTheSetsOrderTheShownOneChosen) {
  const auto set = setOfIds({7, 3, 5});
  std::vector<TargetSummary> told{found(-1, 50.0, Status::UnknownTarget), found(5, 300.0), found(3, 200.0)};
  sortInSetOrder(told, set);
  EXPECT_EQ(told[0].target_id, 3);
  EXPECT_EQ(told[1].target_id, 5);
  EXPECT_EQ(told[2].status, Status::UnknownTarget);
  EXPECT_FALSE(everyMemberTold(told, set));
  EXPECT_EQ(shownTarget(told, set, 5), 1);
  EXPECT_EQ(shownTarget(told, set, 7), 0);  // not found: the first of the set found
  EXPECT_EQ(shownTarget({}, set, -1), -1);
  told.push_back(found(7, 10.0));
  EXPECT_TRUE(everyMemberTold(told, set));
}

}  // namespace
}  // namespace imagepro
