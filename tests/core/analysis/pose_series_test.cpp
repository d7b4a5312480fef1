// Reading a reconstructed sequence back from pose CSV files (data out, reconstruct).
#include "core/analysis/pose_series.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/pipeline/data_out.h"
#include "support/test_dirs.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;

using test::freshDir;

void writeText(const fs::path& p, const std::string& text) {
  std::ofstream out(p);
  out << text;
}

TEST(PoseSeries, ReadsDataOutWithItsTimestamps) {
  const fs::path dir = freshDir("pose_series_data_out");
  const std::string path = (dir / "data.csv").string();
  DataOut out;
  std::string error;
  ASSERT_EQ(out.open(path, ExistingFile::Fail, error), Status::Ok) << error;
  for (int i = 0; i < 5; ++i) {
    FrameResult r;
    r.index = i;
    r.timestamp_s = 0.5 + 0.04 * i;
    r.status = i == 2 ? Status::SpotsNotFound : Status::Ok;
    if (i != 2) r.pose = Pose{1.0 * i, -2.5, 3.25, 10.0 * i, 20.125, 800.5};
    ASSERT_TRUE(out.write(r, error)) << error;
  }
  out.close();
  std::vector<PoseSample> s;
  ASSERT_EQ(readPoseSeries(path, 0.0, s, error), Status::Ok) << error;
  ASSERT_EQ(s.size(), 5u);
  EXPECT_FALSE(s[2].valid);
  EXPECT_TRUE(s[3].valid);
  EXPECT_NEAR(s[3].t_s, 0.62, 1e-9);
  EXPECT_DOUBLE_EQ(s[3].pose.rx_deg, 3.0);
  EXPECT_DOUBLE_EQ(s[3].pose.ry_deg, -2.5);
  EXPECT_DOUBLE_EQ(s[3].pose.rz_deg, 3.25);
  EXPECT_DOUBLE_EQ(s[3].pose.tx_mm, 30.0);
  EXPECT_DOUBLE_EQ(s[3].pose.ty_mm, 20.125);
  EXPECT_DOUBLE_EQ(s[3].pose.tz_mm, 800.5);
}

TEST(PoseSeries, WithoutTimestampsTheFrameRateGivesTheTimes) {
  const fs::path dir = freshDir("pose_series_plain");
  // reconstruct's output for files: quoted names with commas, no timestamps.
  writeText(dir / "named.csv",
            "frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm\n"
            "\"a,1.png\",ok,0,0,0,1,2,700\n"
            "b.png,NoTarget,,,,,,\n"
            "c.png,ok,0,0,0,3,4,700\r\n");
  std::vector<PoseSample> s;
  std::string error;
  EXPECT_EQ(readPoseSeries((dir / "named.csv").string(), 0.0, s, error), Status::InvalidSettings);
  ASSERT_EQ(readPoseSeries((dir / "named.csv").string(), 20.0, s, error), Status::Ok) << error;
  ASSERT_EQ(s.size(), 3u);
  EXPECT_DOUBLE_EQ(s[2].t_s, 0.1);
  EXPECT_DOUBLE_EQ(s[2].pose.tz_mm, 700.0);
  // Numeric frames are indices: a gap in them is a gap in time.
  writeText(dir / "indexed.csv",
            "frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm\n"
            "10,ok,0,0,0,1,2,700\n"
            "15,ok,0,0,0,1,2,700\n");
  ASSERT_EQ(readPoseSeries((dir / "indexed.csv").string(), 25.0, s, error), Status::Ok) << error;
  EXPECT_DOUBLE_EQ(s[1].t_s, 0.6);
}

TEST(PoseSeries, BadFilesAreNamed) {
  const fs::path dir = freshDir("pose_series_bad");
  std::vector<PoseSample> s;
  std::string error;
  EXPECT_EQ(readPoseSeries((dir / "missing.csv").string(), 25.0, s, error), Status::FileNotFound);
  EXPECT_NE(error.find("missing.csv"), std::string::npos);
  writeText(dir / "columns.csv", "frame,status,Rx_deg,Ry_deg\n1,ok,0,0\n");
  EXPECT_EQ(readPoseSeries((dir / "columns.csv").string(), 25.0, s, error), Status::FileUnreadable);
  EXPECT_NE(error.find("Rz_deg"), std::string::npos);
  writeText(dir / "number.csv",
            "frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm\n0,ok,0,0,0,1,2,700\n1,ok,0,0,0,x,2,700\n");
  EXPECT_EQ(readPoseSeries((dir / "number.csv").string(), 25.0, s, error), Status::FileUnreadable);
  EXPECT_NE(error.find("line 3"), std::string::npos);
  EXPECT_TRUE(s.empty());
  writeText(dir / "empty.csv", "");
  EXPECT_EQ(readPoseSeries((dir / "empty.csv").string(), 25.0, s, error), Status::FileUnreadable);
}

TEST(PoseSeries, SplitsQuotedFields) {
  EXPECT_EQ(splitCsvLine("a,\"b,c\",\"d\"\"e\",,f"), (std::vector<std::string>{"a", "b,c", "d\"e", "", "f"}));
}

}  // namespace
}  // namespace imagepro
