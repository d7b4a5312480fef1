// imagepro-cli pendulum and two-targets as a user would run them: where they write
// (plots only where asked, the CSV whole or not at all) and what a missing input says.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "core/common/atomic_file.h"
#include "support/cli_run.h"
#include "support/test_dirs.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;
using test::cli;
using test::CliRun;
using test::freshDir;
using test::lines;
using test::readText;

TEST(CliPendulum, WritesPlotsOnlyWhereAsked) {
  const fs::path dir = freshDir("cli_pendulum_plots");
  CliRun r = test::runProgram(IMAGEPRO_CLI, "pendulum --virtual --frames 100 --format json", dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_empty(dir)) << "wrote into the current folder unasked";

  r = test::runProgram(IMAGEPRO_CLI, "pendulum --virtual --frames 100 --plots plots", dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name : {"pendulum-translations.png", "pendulum-rotations.png"}) {
    EXPECT_GT(fs::file_size(dir / "plots" / name), 1000u) << name;
    EXPECT_NE(r.err.find(name), std::string::npos) << r.err;
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);  // the plots folder only
  EXPECT_EQ(cli("pendulum --virtual --frames 100 --plot pendulum").exit_code, 2);  // the old prefix option is gone
}

TEST(CliPendulum, MissingInputNamesTheFileAndTheReason) {
  const fs::path dir = freshDir("cli_pendulum_missing");
  for (const std::string name : {"swing.png", "swing.csv", "frames.txt"}) {
    const std::string path = (dir / name).string();
    const CliRun r = cli("pendulum " + path);
    EXPECT_EQ(r.exit_code, 1) << name;
    ASSERT_EQ(lines(r.err).size(), 1u) << r.err;
    EXPECT_NE(r.err.find(path + ": no such file"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("TooFewFrames"), std::string::npos) << r.err;
  }
}

// Several runs in one table (thesis table 5.3): a row each, the mean and the spread; a
// run that fails names its error in its row and stays out of the mean.
TEST(CliPendulum, RunsTableAndStillSwingUsage) {
  const CliRun r = cli("pendulum --virtual --frames 100 --still-positions 5 --still-frames 1 --runs 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 6u) << r.out;
  EXPECT_EQ(rows[2].rfind("| seed 1 | 44", 0), 0u) << rows[2];
  EXPECT_EQ(rows[4].rfind("| mean of 2 | ", 0), 0u) << rows[4];
  EXPECT_EQ(rows[5].rfind("| standard deviation | ", 0), 0u) << rows[5];

  const fs::path dir = freshDir("cli_pendulum_runs");
  const std::string missing = (dir / "none.csv").string();
  const CliRun failed = cli("pendulum --still " + missing + "," + missing + " --swing " + missing + "," + missing);
  EXPECT_EQ(failed.exit_code, 1) << failed.out;  // no run gives an answer
  EXPECT_NE(failed.out.find("| 1 | still: FileNotFound"), std::string::npos) << failed.out;

  for (const std::string args : {"--still a.csv", "--swing a.csv", "--still a.csv,b.csv --swing c.csv",
                                 "--still a.csv --swing b.csv --virtual", "--interlaced a.csv",
                                 "--virtual --still-frames 2", "--virtual --period-method peaks"})
    EXPECT_EQ(cli("pendulum " + args).exit_code, 2) << args;
}

TEST(CliTwoTargets, CsvReplacesTheOldFileWhole) {
  const fs::path dir = freshDir("cli_two_targets_csv");
  const fs::path csv = dir / "two.csv", other_name = dir / "kept.csv";
  std::string e;
  ASSERT_TRUE(writeFileAtomically(csv.string(), "old content\n", e)) << e;
  // A second name of the old file: a file truncated and written in place would change under it too.
  fs::create_hard_link(csv, other_name);
  const CliRun r = cli("two-targets --virtual --frames 2 --position 1 --csv " + csv.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(readText(csv));
  ASSERT_EQ(rows.size(), 5u);  // header, 2 frames x 2 corrections
  EXPECT_EQ(rows[0], "frame,position,lighting,correction,status,distance_mm,angle_deg,distance_error_mm,angle_error_deg");
  EXPECT_EQ(rows[1].rfind("0,1,natural,on,ok,", 0), 0u) << rows[1];
  EXPECT_EQ(readText(other_name), "old content\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);  // no temporary file left

  // A CSV that cannot be written: one line naming it, exit 1.
  const std::string unwritable = (dir / "no-such-folder" / "two.csv").string();
  const CliRun bad = cli("two-targets --virtual --frames 2 --position 1 --csv " + unwritable);
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find(unwritable), std::string::npos) << bad.err;
}

// The Markdown table docs/case-studies.md shows: a header, a rule and one row per position
// and correction, the same figures as the text summary's.
TEST(CliTwoTargets, MarkdownFormatIsTheDocsTable) {
  const CliRun md = cli("two-targets --virtual --frames 2 --position 1 --format markdown");
  ASSERT_EQ(md.exit_code, 0) << md.err;
  const auto rows = lines(md.out);
  ASSERT_EQ(rows.size(), 4u) << md.out;
  EXPECT_EQ(rows[0], "| position | correction | distance error mean / std / max [mm] | angle error mean / std / max [deg] |");
  EXPECT_EQ(rows[1], "|---|---|---|---|");
  EXPECT_EQ(rows[2].rfind("| 1 | on | ", 0), 0u) << rows[2];
  EXPECT_EQ(rows[3].rfind("| 1 | off | ", 0), 0u) << rows[3];
  const CliRun text = cli("two-targets --virtual --frames 2 --position 1");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  // The text row "1 on 2/2 MEAN ..." gives the Markdown row's first figure.
  std::string mean;
  for (const std::string& row : lines(text.out)) {
    std::string position, correction, measured;
    std::istringstream(row) >> position >> correction >> measured;
    if (position == "1" && correction == "on") std::istringstream(row) >> position >> correction >> measured >> mean;
  }
  ASSERT_FALSE(mean.empty()) << text.out;
  EXPECT_EQ(rows[2].rfind("| 1 | on | " + mean + " / ", 0), 0u) << rows[2] << "\n" << text.out;
  EXPECT_EQ(cli("two-targets --virtual --frames 2 --format html").exit_code, 2);
}

}  // namespace
}  // namespace imagepro
