// Bad input as a new user gives it: settings with numbers JSON cannot hold or sizes no
// frame can have, a missing file for estimate-d0, cut-off images, and a library run
// that fails part-way. Each is one named error, never an abort or a silent success.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/cli_run.h"
#include "core/common/atomic_file.h"
#include "support/test_dirs.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;
using test::cli;
using test::CliRun;
using test::freshDir;
using test::lines;
using test::readText;
using test::writeText;

// 1e400 is beyond a double: exit 1 with one line naming the file and the key, for the
// settings command and for one that runs the pipeline.
TEST(CliRobustness, NumberJsonCannotHoldNamesTheFileAndKey) {
  const fs::path dir = freshDir("cli_robust_settings");
  const std::string config = (dir / "huge.json").string();
  writeText(config, R"({"camera": {"image_plane_distance_mm": 1e400}})");
  for (const std::string& command : {"settings --config " + config, "reconstruct --virtual --frames 1 --config " + config}) {
    const CliRun r = cli(command);
    EXPECT_EQ(r.exit_code, 1) << command << "\n" << r.err;
    ASSERT_EQ(lines(r.err).size(), 1u) << command << "\n" << r.err;
    EXPECT_NE(r.err.find(config + ": camera.image_plane_distance_mm: "), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  // A whole number past 64 bits is reported as written, not as the -1 it wraps to.
  writeText(config, R"({"camera": {"width": 18446744073709551615}})");
  const CliRun r = cli("settings --config " + config);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("camera.width: value 18446744073709551615 out of range"), std::string::npos) << r.err;
}

// A camera of 100000x100000 is refused at once, by the settings key or by --size.
TEST(CliRobustness, ImageSizeBeyondAFrameIsRefusedUpFront) {
  const fs::path dir = freshDir("cli_robust_size");
  const std::string config = (dir / "big.json").string();
  writeText(config, R"({"camera": {"width": 100000, "height": 100000}})");
  CliRun r = cli("reconstruct --virtual --frames 1 --config " + config);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("camera.width: value 100000 out of range [1, 16384]"), std::string::npos) << r.err;
  r = cli("reconstruct --camera /dev/video-imagepro-missing --size 100000x100000");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--size: 100000x100000 is more than 16384 pixels a side"), std::string::npos) << r.err;
}

// estimate-d0 without any estimate has failed: exit 1, the missing file named.
TEST(CliRobustness, EstimateD0OnAMissingFileFails) {
  const fs::path dir = freshDir("cli_robust_d0");
  const std::string missing = (dir / "missing.png").string();
  const CliRun r = cli("estimate-d0 --focal-length 8 " + missing);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find(missing + ": no such file"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no frame gave an estimate of d0"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find(",FileNotFound,"), std::string::npos) << r.out;
}

// A PNG or JPEG cut off part-way is its own named row, not a partly grey frame.
TEST(CliRobustness, CutOffImagesAreFileTruncated) {
  const fs::path dir = freshDir("cli_robust_truncated");
  ASSERT_EQ(cli("render --out " + dir.string() + " --frames 1 --mode grey").exit_code, 0);
  const cv::Mat frame = cv::imread((dir / "frame_00000.png").string(), cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(frame.empty());
  ASSERT_TRUE(cv::imwrite((dir / "whole.jpg").string(), frame));
  const std::string png = readText(dir / "frame_00000.png"), jpg = readText(dir / "whole.jpg");
  writeText(dir / "cut.png", png.substr(0, png.size() * 2 / 3));
  writeText(dir / "cut.jpg", jpg.substr(0, jpg.size() * 2 / 3));
  const CliRun r = cli("reconstruct " + (dir / "whole.jpg").string() + " " + (dir / "cut.png").string() + " " +
                       (dir / "cut.jpg").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 4u) << r.out;
  EXPECT_NE(rows[1].find(",ok,"), std::string::npos) << rows[1];
  EXPECT_NE(rows[2].find(",FileTruncated,"), std::string::npos) << rows[2];
  EXPECT_NE(rows[3].find(",FileTruncated,"), std::string::npos) << rows[3];
  EXPECT_NE(r.err.find((dir / "cut.jpg").string() + ": the file ends before its image does"), std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("Premature end"), std::string::npos) << r.err;  // libjpeg's own warning stays quiet
}

// library.csv is replaced whole or not at all: a run that fails part-way (an image's
// name taken by a folder) leaves the former library.csv as it was.
TEST(CliRobustness, LibraryCsvSurvivesAFailedRun) {
  const fs::path dir = freshDir("cli_robust_library");
  const std::string former = "file,shape\nformer,row\n";
  writeText(dir / "library.csv", former);
  fs::create_directories(dir / "ellipse_05.png");
  const CliRun r = cli("library " + dir.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("ellipse_05.png"), std::string::npos) << r.err;
  EXPECT_EQ(readText(dir / "library.csv"), former);
}

}  // namespace
}  // namespace imagepro
