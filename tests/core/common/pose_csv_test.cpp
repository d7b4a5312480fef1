#include "core/common/pose_csv.h"

#include <gtest/gtest.h>

namespace imagepro {
namespace {

TEST(PoseCsv, HeaderIsTheArchitectureFormat) {
  EXPECT_EQ(poseCsvHeader(), "frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm");
  EXPECT_EQ(poseCsvHeader("t_s"), "frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm,t_s");
}

TEST(PoseCsv, OkRowHasSixNumbers) {
  const Pose p{1, -2, 3.5, 10, 20, 900};
  EXPECT_EQ(poseCsvRow("a.png", Status::Ok, p),
            "a.png,ok,1.000000,-2.000000,3.500000,10.000000,20.000000,900.000000");
}

TEST(PoseCsv, ErrorRowHasEmptyPoseColumns) {
  EXPECT_EQ(poseCsvRow("7", Status::NoTarget, std::nullopt, "x"), "7,NoTarget,,,,,,,x");
  // Even with a pose at hand, a failed status writes no pose.
  EXPECT_EQ(poseCsvRow("7", Status::SpotsNotFound, Pose{}), "7,SpotsNotFound,,,,,,");
}

TEST(PoseCsv, FileNamesWithCommasAreQuoted) {
  EXPECT_EQ(csvField("a,b.png"), "\"a,b.png\"");
  EXPECT_EQ(csvField("say \"hi\""), "\"say \"\"hi\"\"\"");
}

}  // namespace
}  // namespace imagepro
