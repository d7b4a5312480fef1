// imagepro-cli render as a user runs it for real scenes (--scene real | video): frames
// and truth.csv over the photographs of --backgrounds, reproducible by seed, and the
// render's holes: options outside the settings file's ranges (or NaN, or
// infinite) refused, and a render killed mid-run leaving frames and truth.csv agreeing.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/cli_run.h"
#include "support/test_dirs.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;
using test::cli;
using test::CliRun;
using test::freshDir;
using test::lines;

std::string contents(const fs::path& path) {
  std::string text, e;
  readWholeFile(path.string(), text, e);
  return text;
}

// Two small photographs of shapes in a folder of their own.
fs::path photoFolder(const std::string& name) {
  const fs::path dir = freshDir(name);
  for (int i = 0; i < 2; ++i) {
    cv::Mat photo(300 + 60 * i, 400, CV_8UC1, cv::Scalar(90 + 40 * i));
    cv::circle(photo, {120, 150}, 50, cv::Scalar(230), -1);
    cv::rectangle(photo, cv::Rect(250, 60, 90, 160), cv::Scalar(20), -1);
    cv::imwrite((dir / ("photo" + std::to_string(i) + ".jpg")).string(), photo);
  }
  return dir;
}

// The file names of `dir` (no folders), sorted.
std::vector<std::string> filesIn(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(CliRenderReal, StillsAndNegativesWithTheirTruth) {
  const fs::path photos = photoFolder("cli_render_real_photos");
  const fs::path dir = freshDir("cli_render_real");
  const std::string common = " --scene real --frames 3 --negatives 2 --seed 5 --backgrounds " + photos.string();
  const CliRun r = cli("render --out " + dir.string() + common);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"frame_00000.png", "frame_00001.png", "frame_00002.png",
                                                    "negative_00000.png", "negative_00001.png", "truth.csv"}));
  const auto rows = lines(contents(dir / "truth.csv"));
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_EQ(rows[0],
            "frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm,in_view,background,white,black,light_shape,"
            "light_amplitude,light_gain,blur_px,motion_px,motion_deg,noise_sigma,jpeg_quality,occluder_mm,"
            "occluder_grey,glare_mm");
  for (int i = 1; i <= 3; ++i) {
    EXPECT_EQ(rows[i].rfind("frame_0000" + std::to_string(i - 1) + ".png,ok,", 0), 0u) << rows[i];
    EXPECT_NE(rows[i].find(",1,photo"), std::string::npos) << rows[i];
  }
  for (int i = 4; i <= 5; ++i) EXPECT_EQ(rows[i].rfind("negative_0000" + std::to_string(i - 4) + ".png,NoTarget,,,,,,,0,photo", 0), 0u) << rows[i];
  const cv::Mat frame = cv::imread((dir / "frame_00000.png").string(), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(frame.type(), CV_8UC1);
  EXPECT_EQ(frame.size(), cv::Size(640, 480));

  // The same seed, the same frames; another seed, other ones.
  const fs::path again = freshDir("cli_render_real_again");
  ASSERT_EQ(cli("render --out " + again.string() + common).exit_code, 0);
  EXPECT_EQ(contents(again / "truth.csv"), contents(dir / "truth.csv"));
  EXPECT_EQ(contents(again / "frame_00002.png"), contents(dir / "frame_00002.png"));
  const fs::path other = freshDir("cli_render_real_other");
  ASSERT_EQ(cli("render --out " + other.string() + " --scene real --seed 6 --backgrounds " + photos.string()).exit_code, 0);
  EXPECT_NE(lines(contents(other / "truth.csv"))[1], rows[1]);
}

TEST(CliRenderReal, VideoHidesTheTargetInTheMiddle) {
  const fs::path photos = photoFolder("cli_render_video_photos");
  const fs::path dir = freshDir("cli_render_video");
  const CliRun r = cli("render --out " + dir.string() + " --scene video --frames 20 --hidden 4 --seed 2 --backgrounds " +
                       photos.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(contents(dir / "truth.csv"));
  ASSERT_EQ(rows.size(), 21u);
  for (int i = 0; i < 20; ++i) {
    const bool hidden = i >= 8 && i < 12;
    EXPECT_NE(rows[i + 1].find(hidden ? ",NoTarget,,,,,,,0," : ",ok,"), std::string::npos) << rows[i + 1];
    EXPECT_NE(rows[i + 1].find(",75"), std::string::npos) << rows[i + 1];  // JPEG quality
  }
}

// A video of a set: each member on its own path, hidden in a window of its own (the
// first in the middle, the second hidden + 10 frames later), one truth row per member not
// hidden, its id and whether a nearer card covers it.
TEST(CliRenderReal, VideoOfASetHidesEachMemberInItsOwnWindow) {
  const fs::path photos = photoFolder("cli_render_set_video_photos");
  const fs::path dir = freshDir("cli_render_set_video");
  const fs::path config = freshDir("cli_render_set_video_config") / "pair.json";
  {
    std::ofstream f(config);
    f << R"({"targets": [{"id": 1, "radius_mm": 50, "spot_radius_mm": 6, "spot_offset_mm": 20},
                          {"id": 2, "radius_mm": 50, "spot_radius_mm": 6, "spot_offset_mm": 30}]})";
  }
  const CliRun r = cli("render --out " + dir.string() + " --config " + config.string() +
                       " --scene video --set --frames 40 --hidden 4 --seed 3 --backgrounds " + photos.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(contents(dir / "truth.csv"));
  ASSERT_GE(rows.size(), 2u);
  EXPECT_EQ(rows[0].substr(rows[0].size() - 15), ",target,covered");
  std::vector<std::vector<int>> members(40);
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const std::string& row = rows[k];
    ASSERT_EQ(row.rfind("frame_000", 0), 0u) << row;
    const int frame = std::stoi(row.substr(6, 5));
    ASSERT_NE(row.find(",ok,"), std::string::npos) << row;  // never a frame without a member here
    const std::size_t covered = row.rfind(','), id = row.rfind(',', covered - 1);
    EXPECT_TRUE(row.substr(covered + 1) == "0" || row.substr(covered + 1) == "1") << row;
    members[static_cast<std::size_t>(frame)].push_back(std::stoi(row.substr(id + 1, covered - id - 1)));
  }
  for (int i = 0; i < 40; ++i) {
    std::vector<int> expected;
    if (!(i >= 18 && i < 22)) expected.push_back(1);
    if (!(i >= 32 && i < 36)) expected.push_back(2);
    EXPECT_EQ(members[static_cast<std::size_t>(i)], expected) << "frame " << i;
  }
}

TEST(CliRenderReal, UsageAndInputErrors) {
  const fs::path photos = photoFolder("cli_render_errors_photos");
  const fs::path dir = freshDir("cli_render_errors");
  const std::string out = "render --out " + dir.string() + " ";
  const std::string bg = " --backgrounds " + photos.string();
  const struct {
    std::string args;
    int exit_code;
    std::string message;
  } cases[] = {
      {"--scene drawing", 2, "--scene"},
      {"--scene real --mode binary" + bg, 2, "--mode applies to --scene virtual only"},
      {"--scene real --hidden 3" + bg, 2, "--hidden applies to --scene video only"},
      {"--scene video --negatives 3" + bg, 2, "--negatives applies to --scene real only"},
      {"--negatives 3", 2, "--negatives applies to --scene real or video only"},
      {"--scene real --frames -1" + bg, 2, "--frames"},
      {"--scene real --frames 0" + bg, 2, "nothing to render"},
      {"--scene video --frames 10 --hidden 11" + bg, 2, "--hidden"},
      {"--scene real --backgrounds /no/such/folder", 1, "opencv-doc"},
      {"--scene real --occluders 1.5" + bg, 2, "--occluders must be 0..1"},
      {"--scene real --glare -0.1" + bg, 2, "--glare must be 0..1"},
      {"--scene video --webcam" + bg, 2, "--webcam applies to --scene real only"},
      {"--webcam", 2, "--webcam applies to --scene real or video only"},
  };
  for (const auto& c : cases) {
    const CliRun r = cli(out + c.args);
    EXPECT_EQ(r.exit_code, c.exit_code) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "truth.csv"));
  const CliRun help = cli("render --help");
  EXPECT_NE(help.out.find("--scene real"), std::string::npos);
  EXPECT_NE(help.out.find("--backgrounds DIR"), std::string::npos);
}

// The webcam set as a user makes it: the wide lens from the shipped settings, the rig's
// effects on their shares and in truth.csv, the same poses as without --webcam; and
// reconstruct, given the same settings, finds occluded targets and says how much of their
// rim it saw.
TEST(CliRenderReal, WebcamSetWithItsLensAndTheRigsEffects) {
  const fs::path photos = photoFolder("cli_render_webcam_photos");
  const fs::path webcam = freshDir("cli_render_webcam"), plain = freshDir("cli_render_webcam_plain");
  const std::string config = " --config " + std::string(IMAGEPRO_DATA_DIR) + "/webcam-1280x720.json";
  const std::string common = " --scene real --frames 16 --seed 9 --backgrounds " + photos.string() + config;
  CliRun r = cli("render --webcam --out " + webcam.string() + common);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = cli("render --out " + plain.string() + common);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(contents(webcam / "truth.csv")), plainRows = lines(contents(plain / "truth.csv"));
  ASSERT_EQ(rows.size(), 17u);
  ASSERT_EQ(plainRows.size(), 17u);
  EXPECT_EQ(cv::imread((webcam / "frame_00000.png").string(), cv::IMREAD_UNCHANGED).size(), cv::Size(1280, 720));
  auto fields = [](const std::string& row) {
    std::vector<std::string> out;
    std::stringstream in(row);
    for (std::string f; std::getline(in, f, ',');) out.push_back(f);
    return out;
  };
  int occluded = 0, glare = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto w = fields(rows[i]), p = fields(plainRows[i]);
    ASSERT_EQ(w.size(), 23u) << rows[i];
    for (int k = 0; k < 8; ++k) EXPECT_EQ(w[k], p[k]) << "the same pose: " << rows[i];
    EXPECT_EQ(p[20] + p[22], "00") << plainRows[i];
    occluded += w[20] != "0";
    glare += w[22] != "0";
    if (w[20] != "0") {
      EXPECT_GE(std::stod(w[20]), 10.0);
      EXPECT_LE(std::stod(w[20]), 25.0);
    }
  }
  EXPECT_GT(occluded, 3);
  EXPECT_GT(glare, 1);
  r = cli("reconstruct" + config + " " + webcam.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto poses = lines(r.out);
  ASSERT_EQ(poses.size(), 17u);
  EXPECT_EQ(poses[0], "frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm,rim_seen,target");
  int found = 0, partly = 0;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    const auto f = fields(poses[i]), t = fields(rows[i]);
    if (f[1] != "ok") continue;
    ++found;
    ASSERT_EQ(f.size(), 10u) << poses[i];  // the pose, rim_seen, target
    EXPECT_EQ(f[9], "0") << poses[i];
    const double seen = std::stod(f[8]);
    EXPECT_GT(seen, 0.5) << poses[i];
    EXPECT_LE(seen, 1.0) << poses[i];
    partly += t[20] != "0" && seen < 0.97;
  }
  EXPECT_GE(found, 12) << r.out;
  EXPECT_GE(partly, 2) << r.out;  // occluded rims said to be seen in part
}

// Options go through the settings file's checks: its ranges, and no NaN or infinity.
TEST(CliRenderReal, VirtualOptionsKeepToTheSettingsRanges) {
  const fs::path dir = freshDir("cli_render_ranges");
  const struct {
    std::string args, option, detail;
  } cases[] = {
      {"--clutter 2147483647", "--clutter", "[0, 1000]"},
      {"--clutter 1001", "--clutter", "virtual.clutter"},
      {"--pose nan,0,0,0,0,800", "--pose", "finite"},
      {"--pose 0,0,0,0,0,inf", "--pose", "finite"},
      {"--pose 0,400,0,0,0,800", "--pose", "virtual.pose.ry_deg"},
      {"--amplitude nan", "--amplitude", "finite"},
      {"--rate inf", "--rate", "finite"},
      {"--rate 2e6", "--rate", "virtual.frame_rate_hz"},
      {"--period inf", "--period", "finite"},
      {"--blur 51", "--blur", "virtual.blur_sigma_px"},
      {"--noise 300", "--noise", "virtual.noise_sigma"},
  };
  for (const auto& c : cases) {
    const auto start = std::chrono::steady_clock::now();
    const CliRun r = cli("render --out " + dir.string() + " " + c.args);
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10)) << c.args;
    EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.option + ":"), std::string::npos) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.detail), std::string::npos) << c.args << ": " << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "truth.csv"));
  EXPECT_EQ(cli("render --out " + dir.string() + " --clutter 1000 --mode binary").exit_code, 0);
}

// A render killed while it renders leaves the folder as it was: the old truth.csv with
// its own frames. The next render clears what the killed one left behind.
TEST(CliRenderReal, KilledRenderLeavesFramesAndTruthAgreeing) {
  const fs::path dir = freshDir("cli_render_kill");
  ASSERT_EQ(cli("render --out " + dir.string() + " --frames 2 --mode binary --pose 0,0,0,0,0,700").exit_code, 0);
  const std::string truth = contents(dir / "truth.csv");
  const std::string frame0 = contents(dir / "frame_00000.png");
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int devnull = open("/dev/null", O_WRONLY);
    dup2(devnull, 1);
    dup2(devnull, 2);
    execl(IMAGEPRO_CLI, IMAGEPRO_CLI, "render", "--out", dir.c_str(), "--frames", "100000", "--mode", "grey",
          "--pose", "10,20,30,0,0,900", static_cast<char*>(nullptr));
    _exit(127);
  }
  // Kill it without warning once it has written a few frames.
  const fs::path staging = dir / (".render-" + std::to_string(pid));
  const auto staged = [&] {
    std::error_code ec;
    int n = 0;
    for (fs::directory_iterator it(staging, ec), end; !ec && it != end; it.increment(ec)) ++n;
    return n;
  };
  for (int i = 0; i < 200 && staged() < 5; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_GE(staged(), 5);
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_EQ(contents(dir / "truth.csv"), truth);
  EXPECT_EQ(contents(dir / "frame_00000.png"), frame0);
  EXPECT_FALSE(fs::exists(dir / "frame_00002.png"));
  EXPECT_TRUE(fs::exists(staging));

  ASSERT_EQ(cli("render --out " + dir.string() + " --frames 3 --mode binary").exit_code, 0);
  EXPECT_FALSE(fs::exists(staging));
  EXPECT_EQ(lines(contents(dir / "truth.csv")).size(), 4u);
  EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"frame_00000.png", "frame_00001.png", "frame_00002.png", "truth.csv"}));
}

}  // namespace
}  // namespace imagepro
