#include "core/settings/target_set.h"

#include <gtest/gtest.h>

#include "core/settings/settings.h"

namespace imagepro {
namespace {

TargetSpec member(int id, const char* name, double offset_mm) {
  TargetSpec t;
  t.id = id;
  t.name = name;
  t.geometry.spot_offset_mm = offset_mm;  // R 50 mm, spots 6 mm
  return t;
}

// The issue's pair: offset spots at 0.4 and 0.6 of the radius.
const std::vector<TargetSpec> kPair{member(1, "link 1", 20.0), member(2, "link 2", 30.0)};

TEST(TargetSet, TheCodingIsTheOffsetSpotsShareOfTheRadius) {
  EXPECT_DOUBLE_EQ(codingFraction(TargetGeometry{}), 0.5);
  EXPECT_DOUBLE_EQ(codingFraction(kPair[0].geometry), 0.4);
}

TEST(TargetSet, AMeasuredCodingNamesTheMemberWithinHalfTheGap) {
  EXPECT_EQ(memberCodedAs(kPair, 0.41), 0);
  EXPECT_EQ(memberCodedAs(kPair, 0.36), 0);
  EXPECT_EQ(memberCodedAs(kPair, 0.63), 1);
  EXPECT_EQ(memberCodedAs(kPair, 0.5), -1) << "halfway between two codings names neither";
  EXPECT_EQ(memberCodedAs(kPair, 0.75), -1);
  EXPECT_EQ(memberCodedAs({}, 0.5), -1);
}

TEST(TargetSet, MembersThatCannotBeToldApartAreNamed) {
  EXPECT_EQ(targetSetProblem(kPair), "");
  EXPECT_EQ(targetSetProblem({}), "");
  std::vector<TargetSpec> twins = kPair;
  twins[1].id = 1;
  EXPECT_NE(targetSetProblem(twins).find("same id 1"), std::string::npos) << targetSetProblem(twins);
  std::vector<TargetSpec> close{member(1, "a", 20.0), member(7, "b", 24.0)};
  const std::string problem = targetSetProblem(close);
  EXPECT_NE(problem.find("id 1 (a)"), std::string::npos) << problem;
  EXPECT_NE(problem.find("id 7 (b)"), std::string::npos) << problem;
  EXPECT_NE(problem.find("cannot be told apart"), std::string::npos) << problem;
  // An offset spot on the centre spot or over the rim is no coding.
  EXPECT_NE(targetSetProblem({member(3, "c", 10.0)}).find("id 3 (c)"), std::string::npos);
  EXPECT_NE(targetSetProblem({member(3, "c", 45.0)}), "");
}

TEST(TargetSet, TheSearchReachesEveryMembersCoding) {
  const TargetSearch lone = targetSearch({}, TargetGeometry{}, 0.2);
  EXPECT_DOUBLE_EQ(lone.geometry.spot_offset_mm, 25.0);
  EXPECT_DOUBLE_EQ(lone.spot_tolerance, 0.2);
  const TargetSearch pair = targetSearch(kPair, TargetGeometry{}, 0.2);
  const double middle = codingFraction(pair.geometry);
  EXPECT_NEAR(middle, 0.5, 1e-12);
  EXPECT_NEAR(pair.geometry.spot_radius_mm / pair.geometry.radius_mm, 0.12, 1e-12);
  for (const TargetSpec& t : kPair)
    EXPECT_LE(std::abs(codingFraction(t.geometry) - middle) + 0.2, pair.spot_tolerance + 1e-12);
}

// The settings file's "targets": read, written back, and refused with the members named.
TEST(TargetSet, TheSettingsListRoundTripsAndIsLeftOutWhenEmpty) {
  Settings s;
  EXPECT_EQ(settingsToJson(s).find("\"targets\""), std::string::npos);
  s.targets = kPair;
  Settings back;
  std::string error;
  ASSERT_EQ(settingsFromJson(settingsToJson(s), back, error), Status::Ok) << error;
  ASSERT_EQ(back.targets.size(), 2u);
  EXPECT_EQ(back.targets[1].id, 2);
  EXPECT_EQ(back.targets[1].name, "link 2");
  EXPECT_DOUBLE_EQ(back.targets[1].geometry.spot_offset_mm, 30.0);
  EXPECT_DOUBLE_EQ(back.targets[1].geometry.radius_mm, 50.0) << "a missing key keeps its default";
}

TEST(TargetSet, AMalformedOrAmbiguousListIsRefusedNamingIt) {
  auto problem = [](const std::string& json) {
    Settings s;
    s.targets = kPair;
    std::string error;
    EXPECT_EQ(settingsFromJson(json, s, error), Status::InvalidSettings) << json;
    EXPECT_EQ(s.targets.size(), 2u) << "a refused file leaves the settings as they were";
    return error;
  };
  EXPECT_EQ(problem(R"({"targets": {"id": 1}})"), "targets: expected an array of objects");
  EXPECT_EQ(problem(R"({"targets": [{"id": 1}, 3]})"), "targets[1]: expected an object");
  EXPECT_EQ(problem(R"({"targets": [{"id": 1, "colour": "red"}]})"), "targets[0].colour: unknown key");
  EXPECT_NE(problem(R"({"targets": [{"id": -1}]})").find("targets[0].id"), std::string::npos);
  EXPECT_NE(problem(R"({"targets": [{"id": 1, "spot_offset_mm": 20}, {"id": 1, "spot_offset_mm": 30}]})")
                .find("same id 1"),
            std::string::npos);
  const std::string close =
      problem(R"({"targets": [{"id": 1, "name": "arm", "spot_offset_mm": 20}, {"id": 2, "name": "base", "spot_offset_mm": 22}]})");
  EXPECT_NE(close.find("id 1 (arm)"), std::string::npos) << close;
  EXPECT_NE(close.find("id 2 (base)"), std::string::npos) << close;
}

// The "frames" section: its ids must name targets of the file, and it round-trips.
TEST(TargetSet, FramesOfReferenceNameTargetsOfTheFile) {
  Settings s;
  std::string error;
  EXPECT_EQ(settingsFromJson(R"({"frames": {"reference_target": 2}})", s, error), Status::InvalidSettings);
  EXPECT_NE(error.find("frames.reference_target: 2 is not the id"), std::string::npos) << error;
  const std::string pair =
      R"({"targets": [{"id": 1, "spot_offset_mm": 20}, {"id": 2, "spot_offset_mm": 30}],
          "frames": {"reference_target": 2, "measured_targets": [1, 2], "origin_set": true,
                     "origin": {"rx_deg": 10, "tz_mm": 900}}})";
  ASSERT_EQ(settingsFromJson(pair, s, error), Status::Ok) << error;
  EXPECT_EQ(s.frames.reference_target, 2);
  EXPECT_EQ(s.frames.measured_targets[1], 2);
  EXPECT_TRUE(s.frames.origin_set);
  EXPECT_DOUBLE_EQ(s.frames.origin.tz_mm, 900.0);
  Settings back;
  ASSERT_EQ(settingsFromJson(settingsToJson(s), back, error), Status::Ok) << error;
  EXPECT_EQ(back.frames.reference_target, 2);
  EXPECT_EQ(back.frames.measured_targets, s.frames.measured_targets);
  EXPECT_TRUE(back.frames.origin_set);
  EXPECT_DOUBLE_EQ(back.frames.origin.rx_deg, 10.0);
  EXPECT_EQ(settingsFromJson(R"({"frames": {"measured_targets": [1]}})", s, error), Status::InvalidSettings);
}

}  // namespace
}  // namespace imagepro
