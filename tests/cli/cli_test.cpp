#include <gtest/gtest.h>
#include <signal.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/cli_run.h"
#include "core/common/atomic_file.h"
#include "core/common/version.h"
#include "support/test_dirs.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;
using test::cli;
using test::CliRun;
using test::freshDir;
using test::lines;

TEST(Cli, OverviewListsTheCommands) {
  const CliRun r = cli("--help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* c : {"reconstruct", "render", "threshold", "edges", "bench", "settings", "pendulum", "two-targets"})
    EXPECT_NE(r.out.find(c), std::string::npos) << c;
  // The studies are imagepro-studies' commands.
  for (const char* c :
       {"accuracy", "calibration-study", "track-study", "pendulum-study", "ellipse-library", "bench-peers",
        "distortion-figures"})
    EXPECT_EQ(r.out.find(std::string("  ") + c + " "), std::string::npos) << c;
}

TEST(Cli, EveryCommandHasHelp) {
  const CliRun overview = cli("--help");
  const std::vector<std::string> names = test::overviewCommands(overview.out);
  EXPECT_GE(names.size(), 15u);
  for (const std::string& name : names) {
    const CliRun r = cli(name + " --help");
    EXPECT_EQ(r.exit_code, 0) << name;
    EXPECT_NE(r.out.find("usage: imagepro-cli " + name), std::string::npos) << name;
  }
}

TEST(Cli, VersionIsTheProjects) {
  const CliRun r = cli("--version");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, std::string("imagepro-cli ") + kVersion + "\n");
  EXPECT_NE(cli("--help").out.find("--version"), std::string::npos);
}

TEST(Cli, DataDirFromTheBuildTreeIsTheSourcesData) {
  const CliRun r = cli("--data-dir");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  ASSERT_FALSE(r.out.empty());
  EXPECT_TRUE(fs::equivalent(r.out.substr(0, r.out.size() - 1), IMAGEPRO_DATA_DIR)) << r.out;
}

TEST(Cli, InstalledCopyFindsTheDataBesideIt) {
  // The install layout without the package: bin/imagepro-cli and share/imagepro.
  const fs::path prefix = freshDir("cli_installed") / "usr";
  fs::create_directories(prefix / "bin");
  fs::create_directories(prefix / "share/imagepro");
  fs::copy_file(IMAGEPRO_CLI, prefix / "bin/imagepro-cli");
  fs::copy_file(fs::path(IMAGEPRO_DATA_DIR) / "settings.json", prefix / "share/imagepro/settings.json");
  const CliRun r = test::runProgram((prefix / "bin/imagepro-cli").string(), "--data-dir");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, (prefix / "share/imagepro").string() + "\n");
}

TEST(Cli, MethodListsComeFromTheEnumTables) {
  // Each value by its key, then its display name and description from enum_names.cpp.
  const CliRun edges = cli("edges --help");
  EXPECT_NE(edges.out.find("laplace         Laplace: a white pixel"), std::string::npos) << edges.out;
  EXPECT_NE(edges.out.find("cn1  CN1: "), std::string::npos) << edges.out;
  EXPECT_NE(cli("detect --help").out.find("direct-fit  Direct fit: "), std::string::npos);
  const CliRun threshold = cli("threshold --help");
  EXPECT_NE(threshold.out.find("at-mod   AT-Mod: "), std::string::npos) << threshold.out;
  EXPECT_EQ(threshold.out.find("None: "), std::string::npos);  // no threshold to print
  const CliRun render = cli("render --help");
  EXPECT_NE(render.out.find("saw-tooth          Saw-tooth: "), std::string::npos) << render.out;
  EXPECT_NE(render.out.find("constant-velocity  Constant velocity: "), std::string::npos) << render.out;
  const CliRun md = cli("settings --methods-markdown");
  EXPECT_EQ(md.exit_code, 0);
  // The frame's threshold takes every method but the re-threshold's by-pass.
  EXPECT_NE(md.out.find("`pipeline.threshold.method` (not `none`), `pipeline.rethreshold.method`\n"), std::string::npos)
      << md.out;
  EXPECT_NE(md.out.find("| None | `none` | "), std::string::npos);
  EXPECT_NE(md.out.find("| AT-Mod | `at-mod` | The same minimum error criterion"), std::string::npos) << md.out;
  EXPECT_NE(md.out.find("| 8 points ORG | `8-points-org` | "), std::string::npos);
  EXPECT_EQ(cli("settings --methods-markdown --out x.json").exit_code, 2);
}

TEST(Cli, UsageErrorsAreOneLineAndExitTwo) {
  CliRun r = cli("frobnicate");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown command"), std::string::npos);
  r = cli("reconstruct --bogus 1 x.png");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--bogus"), std::string::npos);
  r = cli("reconstruct");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(lines(r.err).size(), 1u);
}

TEST(Cli, MalformedSettingsNameTheKey) {
  const fs::path dir = freshDir("cli_settings");
  std::string e;
  ASSERT_TRUE(writeFileAtomically((dir / "bad.json").string(), R"({"pipeline": {"threshold": {"method": "otsu"}}})", e));
  const CliRun r = cli("reconstruct --virtual --frames 1 --config " + (dir / "bad.json").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("pipeline.threshold.method"), std::string::npos) << r.err;
  EXPECT_EQ(cli("settings --config " + (dir / "missing.json").string()).exit_code, 1);
}

TEST(Cli, MissingCameraIsOneNamedLineAndExitOne) {
  const std::string device = "/dev/video-imagepro-missing";
  for (const std::string command : {"bench", "reconstruct"}) {
    const CliRun r = cli(command + " --camera " + device + " --size 320x240 --fps 30 --frames 20");
    EXPECT_EQ(r.exit_code, 1) << command;
    ASSERT_EQ(lines(r.err).size(), 1u) << command << ": " << r.err;
    EXPECT_NE(r.err.find(device + ": no camera device at that path"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << command << ": " << r.out;
  }
  // Settings that name the missing camera: the same from the device stored in them.
  const fs::path dir = freshDir("cli_camera");
  std::string e;
  ASSERT_TRUE(writeFileAtomically((dir / "camera.json").string(),
                                  R"({"camera_source": {"device": "/dev/video-imagepro-missing", "frame_rate_hz": 30}})", e));
  CliRun r = cli("bench --config " + (dir / "camera.json").string() + " --camera " + device);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(device), std::string::npos) << r.err;
  // Usage problems come before the device is touched.
  r = cli("bench --camera " + device + " --frames 3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--frames"), std::string::npos) << r.err;
  r = cli("bench --camera " + device + " --size big");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--size"), std::string::npos) << r.err;
  r = cli("bench --camera " + device + " --resolution 640x480");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--resolution"), std::string::npos) << r.err;
}

TEST(Cli, CaptureCardOptionsAreCheckedBeforeTheDevice) {
  const std::string device = "/dev/video-imagepro-missing";
  CliRun r = cli("reconstruct --camera " + device + " --input one");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--input"), std::string::npos) << r.err;
  r = cli("reconstruct --camera " + device + " --input -1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--input must be 0 or more"), std::string::npos) << r.err;
  r = cli("reconstruct --camera " + device + " --standard PAL-M");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--standard: \"PAL-M\" is not one of PAL, NTSC, SECAM"), std::string::npos) << r.err;
  r = cli("reconstruct --virtual --frames 1 --standard NTSC");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--standard goes with --camera"), std::string::npos) << r.err;
  // Well formed, in any case: the device is tried (and missing).
  r = cli("reconstruct --camera " + device + " --input 1 --standard pal --frames 1");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(device + ": no camera device at that path"), std::string::npos) << r.err;
}

// The command line's input picks the source whose camera model reconstructs: image files
// the File source's, --virtual the Virtual source's.
TEST(Cli, TheInputPicksItsSourcesCamera) {
  const fs::path dir = freshDir("cli_source_camera");
  CliRun r = cli("render --out " + dir.string() + " --frames 1 --mode binary");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string e;
  // The File source's image plane twice as far: the same image is a target twice as far away.
  ASSERT_TRUE(writeFileAtomically((dir / "cameras.json").string(),
                                  R"({"cameras": {"file": {"image_plane_distance_mm": 16.0}}})", e));
  const std::string config = " --config " + (dir / "cameras.json").string();
  const auto tz = [](const std::string& csv) {  // the 8th column
    std::string row = lines(csv).at(1);
    for (int k = 0; k < 7; ++k) row = row.substr(row.find(',') + 1);
    return std::stod(row.substr(0, row.find(',')));
  };
  r = cli("reconstruct" + config + " " + (dir / "frame_00000.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(tz(r.out), 1600.0, 8.0) << r.out;
  r = cli("reconstruct" + config + " --virtual --frames 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(tz(r.out), 800.0, 4.0) << r.out;
  // An older file's one camera is every source's.
  ASSERT_TRUE(writeFileAtomically((dir / "old.json").string(), R"({"camera": {"image_plane_distance_mm": 16.0}})", e));
  r = cli("reconstruct --config " + (dir / "old.json").string() + " --virtual --frames 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(tz(r.out), 800.0, 4.0) << r.out;  // rendered and reconstructed through the same camera
}

TEST(Cli, ReconstructWritesARowPerFrameEvenForBadFiles) {
  const fs::path dir = freshDir("cli_reconstruct");
  CliRun r = cli("render --out " + dir.string() + " --frames 2 --mode binary");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string e;
  ASSERT_TRUE(writeFileAtomically((dir / "corrupt.png").string(), "garbage", e));
  r = cli("reconstruct " + (dir / "frame_00000.png").string() + " " + (dir / "missing.png").string() + " " +
          (dir / "corrupt.png").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 4u) << r.out;
  EXPECT_EQ(rows[0], "frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm,rim_seen,target");
  EXPECT_NE(rows[1].find(",ok,"), std::string::npos) << rows[1];
  // A whole rim seen: its share is 1; the settings' one target, id 0.
  EXPECT_NE(rows[1].find(",1.000,0"), std::string::npos) << rows[1];
  EXPECT_EQ(rows[1].substr(rows[1].rfind(',')), ",0") << rows[1];
  EXPECT_NE(rows[2].find(",FileNotFound,,,,,,"), std::string::npos) << rows[2];
  EXPECT_NE(rows[3].find(",FileUnreadable,,,,,,"), std::string::npos) << rows[3];
}

TEST(Cli, ReconstructJson) {
  const CliRun r = cli("reconstruct --virtual --frames 2 --format json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  ASSERT_FALSE(r.out.empty()) << r.err;
  EXPECT_EQ(r.out.front(), '[');
  EXPECT_NE(r.out.find("\"Tz_mm\""), std::string::npos);
}

TEST(Cli, DataOutSurvivesAKill) {
  const fs::path dir = freshDir("cli_kill");
  const std::string data = (dir / "dataout.csv").string();
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int devnull = open("/dev/null", O_WRONLY);
    dup2(devnull, 1);
    dup2(devnull, 2);
    execl(IMAGEPRO_CLI, IMAGEPRO_CLI, "reconstruct", "--virtual", "--frames", "1000000", "--data-out", data.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  // Let it write for a while, then kill it without warning.
  for (int i = 0; i < 100 && (!fs::exists(data) || fs::file_size(data) < 2000); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  std::string text, e;
  ASSERT_TRUE(readWholeFile(data, text, e)) << e;
  const auto rows = lines(text);
  ASSERT_GE(rows.size(), 3u);
  EXPECT_EQ(rows[0].rfind("frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm,timestamp_s", 0), 0u);
  // Every complete row is whole: the same number of columns as the header.
  const auto columns = [](const std::string& l) { return std::count(l.begin(), l.end(), ','); };
  const bool last_complete = !text.empty() && text.back() == '\n';
  for (std::size_t i = 1; i + (last_complete ? 0 : 1) < rows.size(); ++i) EXPECT_EQ(columns(rows[i]), columns(rows[0])) << i;

  // Asked to write to the same file again, it refuses rather than overwrite.
  const CliRun again = cli("reconstruct --virtual --frames 1 --data-out " + data);
  EXPECT_EQ(again.exit_code, 1);
  std::string after;
  ASSERT_TRUE(readWholeFile(data, after, e));
  EXPECT_EQ(after, text);
}

}  // namespace
}  // namespace imagepro
