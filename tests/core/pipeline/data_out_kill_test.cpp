// kill -9 while data out is written: every row written before the kill is in the file,
// whole and in order; at most the row in flight is lost, and the next run appending to
// the file says so and starts on a new line.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <sstream>
#include <string>

#include "core/common/atomic_file.h"
#include "core/pipeline/data_out.h"
#include "support/kill_loop.h"
#include "support/test_dirs.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;

FrameResult frame(long i) {
  FrameResult r;
  r.index = i;
  r.timestamp_s = 0.04 * static_cast<double>(i);
  r.status = i % 3 ? Status::Ok : Status::NoTarget;
  if (r.status == Status::Ok) r.pose = Pose{1.0 * static_cast<double>(i), 2, 3, 4, 5, 600};
  r.search_region = {10, 20, 30, 40};
  r.detected_region = {12, 22, 20, 30};
  return r;
}

TEST(DataOutKill, AKilledRunLosesAtMostTheRowInFlight) {
  const fs::path dir = test::freshDir("dataout_kill");
  const std::string path = (dir / "dataout.csv").string();
  const std::string header = DataOut::header();
  constexpr int kKills = 25;
  int lost_reported = 0, cut_lines = 0;
  for (int k = 0; k < kKills; ++k) {
    // Each run appends to the file the killed runs before it left.
    std::unique_ptr<DataOut> out;
    const auto write = [&](long i) {
      std::string e;
      if (i == 0) {
        out = std::make_unique<DataOut>();
        if (out->open(path, ExistingFile::Append, e) != Status::Ok) return false;
      }
      return out->write(frame(i), e);
    };
    ASSERT_TRUE(test::runThenKill(write, test::killDelay(k, kKills))) << "a write failed, run " << k;
    DataOut reopen;
    std::string error;
    if (!fs::exists(path)) continue;  // killed before it opened the file
    ASSERT_EQ(reopen.open(path, ExistingFile::Append, error), Status::Ok) << error;
    EXPECT_LE(reopen.lostRows(), 1);
    lost_reported += reopen.lostRows();
  }
  // Each run's rows: a header (when it was the first to write), then rows 0, 1, 2 ...
  // whole; a line that is neither is a row cut off by the kill, counted lost above.
  std::string text, error;
  ASSERT_TRUE(readWholeFile(path, text, error)) << error;
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  std::istringstream lines(text);
  long next = 0;
  int rows = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line == header) continue;
    if (line == DataOut::row(frame(next))) {
      ++next, ++rows;
    } else if (line == DataOut::row(frame(0))) {  // a new run starts again at frame 0
      next = 1, ++rows;
    } else {
      ++cut_lines;
      EXPECT_EQ(line, DataOut::row(frame(next)).substr(0, line.size())) << "not a cut-off row";
      next = 0;  // the run ends with its cut row
    }
  }
  // A row whose line end alone was cut reads whole again once the next run ends it.
  EXPECT_LE(cut_lines, lost_reported);
  EXPECT_GT(rows, 100);
}

}  // namespace
}  // namespace imagepro
