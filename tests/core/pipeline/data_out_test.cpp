#include "core/pipeline/data_out.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/common/atomic_file.h"
#include "support/test_dirs.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;

using test::freshDir;

std::string slurp(const fs::path& p) {
  std::string s, err;
  EXPECT_TRUE(readWholeFile(p.string(), s, err)) << err;
  return s;
}

FrameResult okFrame(std::int64_t i) {
  FrameResult r;
  r.index = i;
  r.timestamp_s = 0.04 * i;
  r.status = Status::Ok;
  r.pose = Pose{1, 2, 3, 4, 5, 600};
  r.search_region = {10, 20, 30, 40};
  r.detected_region = {12, 22, 20, 30};
  return r;
}

TEST(DataOut, HeaderStartsWithTheArchitectureColumns) {
  EXPECT_EQ(DataOut::header().rfind("frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm,timestamp_s,", 0), 0u);
}

TEST(DataOut, WritesOneFlushedRowPerFrame) {
  const fs::path dir = freshDir("dataout_rows");
  DataOut out;
  std::string err;
  ASSERT_EQ(out.open((dir / "d.csv").string(), ExistingFile::Fail, err), Status::Ok) << err;
  ASSERT_TRUE(out.write(okFrame(0), err));
  FrameResult miss;
  miss.index = 1;
  miss.status = Status::NoTarget;
  ASSERT_TRUE(out.write(miss, err));
  // Flushed: readable before close.
  std::istringstream lines(slurp(dir / "d.csv"));
  std::string header, row0, row1;
  std::getline(lines, header);
  std::getline(lines, row0);
  std::getline(lines, row1);
  EXPECT_EQ(row0.rfind("0,ok,1.000000,2.000000,3.000000,4.000000,5.000000,600.000000,0.000000,10,20,30,40,12,22,20,30", 0), 0u);
  EXPECT_EQ(row1.rfind("1,NoTarget,,,,,,,", 0), 0u);
}

TEST(DataOut, NeverOverwritesAnExistingFile) {
  const fs::path dir = freshDir("dataout_existing");
  const fs::path p = dir / "d.csv";
  std::string err;
  ASSERT_TRUE(writeFileAtomically(p.string(), "precious\n", err));
  DataOut out;
  EXPECT_EQ(out.open(p.string(), ExistingFile::Fail, err), Status::FileNotWritable);
  EXPECT_NE(err.find("exists"), std::string::npos);
  EXPECT_EQ(slurp(p), "precious\n");

  ASSERT_EQ(out.open(p.string(), ExistingFile::NewName, err), Status::Ok);
  EXPECT_EQ(fs::path(out.path()).filename(), "d-1.csv");
  out.close();

  const std::string earlier = DataOut::header() + "\n" + DataOut::row(okFrame(2)) + "\n";
  ASSERT_TRUE(writeFileAtomically(p.string(), earlier, err));
  ASSERT_EQ(out.open(p.string(), ExistingFile::Append, err), Status::Ok) << err;
  ASSERT_TRUE(out.write(okFrame(3), err));
  out.close();
  EXPECT_EQ(slurp(p), earlier + DataOut::row(okFrame(3)) + "\n");  // appended, no second header
}

// Rows are appended only under today's header: a file an older version wrote (without
// the last column), or another program's, is refused with the difference named, and left
// as it was, byte for byte.
TEST(DataOut, AppendUnderAnotherHeaderIsRefused) {
  const fs::path dir = freshDir("dataout_other_header");
  const fs::path p = dir / "d.csv";
  const std::string today = DataOut::header();
  const std::string older = today.substr(0, today.rfind(','));
  struct Case {
    std::string content, named;
  };
  for (const Case& c : {Case{older + "\n" + "0,ok,1,2,3,4,5,6\n", "from \"pair_angle_deg\" on"},
                        Case{"precious\n", "column 1 is \"precious\" where ImagePro writes \"frame\""},
                        Case{today + ",note\n", "\"note\" and on are not written"},
                        Case{"frame,status,X", "column 3 is \"X\""}}) {
    SCOPED_TRACE(c.content);
    std::string err;
    ASSERT_TRUE(writeFileAtomically(p.string(), c.content, err));
    DataOut out;
    EXPECT_EQ(out.open(p.string(), ExistingFile::Append, err), Status::FileNotWritable);
    EXPECT_FALSE(out.isOpen());
    EXPECT_NE(err.find("d.csv: not appended to"), std::string::npos) << err;
    EXPECT_NE(err.find(c.named), std::string::npos) << err;
    EXPECT_EQ(slurp(p), c.content);
    // A new numbered file beside it takes the rows instead.
    ASSERT_EQ(out.open(p.string(), ExistingFile::NewName, err), Status::Ok) << err;
    EXPECT_EQ(fs::path(out.path()).filename(), "d-1.csv");
    out.close();
    fs::remove(out.path());
  }
}

// A run killed while writing a row leaves the file without a final line end. Appending
// to it starts on a new line, so the next row is whole and readable, and the cut-off
// row is counted lost; a whole file is appended to as it stands, with nothing lost.
TEST(DataOut, AppendAfterACutOffRowStartsOnANewLine) {
  const fs::path dir = freshDir("dataout_cut");
  const fs::path p = dir / "d.csv";
  const std::string header = DataOut::header() + "\n";
  const std::string whole = DataOut::row(okFrame(0)) + "\n";
  const std::string cut = DataOut::row(okFrame(1)).substr(0, 20);
  std::string err;
  ASSERT_TRUE(writeFileAtomically(p.string(), header + whole + cut, err));
  DataOut out;
  ASSERT_EQ(out.open(p.string(), ExistingFile::Append, err), Status::Ok) << err;
  EXPECT_EQ(out.lostRows(), 1);
  EXPECT_NE(out.notice().find("d.csv: its last row was cut off"), std::string::npos) << out.notice();
  ASSERT_TRUE(out.write(okFrame(2), err));
  out.close();
  EXPECT_EQ(slurp(p), header + whole + cut + "\n" + DataOut::row(okFrame(2)) + "\n");

  // Appended again, the file now ends whole: nothing more is lost.
  ASSERT_EQ(out.open(p.string(), ExistingFile::Append, err), Status::Ok) << err;
  EXPECT_EQ(out.lostRows(), 0);
  EXPECT_TRUE(out.notice().empty());
  ASSERT_TRUE(out.write(okFrame(3), err));
  out.close();
  EXPECT_EQ(slurp(p), header + whole + cut + "\n" + DataOut::row(okFrame(2)) + "\n" + DataOut::row(okFrame(3)) + "\n");
}

// Killed while writing even the header: the header is written again, whole, on a line
// of its own, so the rows below it have their column names.
TEST(DataOut, AppendAfterACutOffHeaderWritesItAgain) {
  const fs::path dir = freshDir("dataout_cut_header");
  const fs::path p = dir / "d.csv";
  const std::string cut = DataOut::header().substr(0, 15);
  std::string err;
  ASSERT_TRUE(writeFileAtomically(p.string(), cut, err));
  DataOut out;
  ASSERT_EQ(out.open(p.string(), ExistingFile::Append, err), Status::Ok) << err;
  EXPECT_EQ(out.lostRows(), 0);
  EXPECT_NE(out.notice().find("header was cut off"), std::string::npos) << out.notice();
  ASSERT_TRUE(out.write(okFrame(0), err));
  out.close();
  EXPECT_EQ(slurp(p), cut + "\n" + DataOut::header() + "\n" + DataOut::row(okFrame(0)) + "\n");
}

TEST(DataOut, UnwritableFolderIsANamedError) {
  DataOut out;
  std::string err;
  EXPECT_EQ(out.open("/nonexistent-folder/d.csv", ExistingFile::Fail, err), Status::FileNotWritable);
  EXPECT_NE(err.find("/nonexistent-folder/d.csv"), std::string::npos);
  EXPECT_FALSE(out.write(okFrame(0), err));
}

}  // namespace
}  // namespace imagepro
