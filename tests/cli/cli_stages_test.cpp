// The stage commands of the CLI run as a user runs them, checked against ground
// truth: render (frames and truth.csv), threshold, edges, library (thesis tables B.1
// and B.2) and detect, with their bad-input rows, stderr lines and exit codes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

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

const std::string kSamples = std::string(IMAGEPRO_DATA_DIR) + "/samples";

std::vector<std::string> fields(const std::string& row) {
  std::vector<std::string> out;
  std::istringstream in(row);
  for (std::string f; std::getline(in, f, ',');) out.push_back(f);
  if (!row.empty() && row.back() == ',') out.emplace_back();
  return out;
}

double number(const std::string& text) { return std::stod(text); }

std::string fileName(const std::string& path) { return fs::path(path).filename().string(); }

void writeFile(const fs::path& path, const std::string& bytes) {
  std::string e;
  ASSERT_TRUE(writeFileAtomically(path.string(), bytes, e)) << e;
}

std::string readFile(const fs::path& path) {
  std::string text, e;
  EXPECT_TRUE(readWholeFile(path.string(), text, e)) << e;
  return text;
}

std::vector<std::string> pngsIn(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".png") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// A rendered grey frame cut off half-way and a PGM whose pixel data stops early: both
// make the decoders print their own lines unless the CLI keeps them quiet.
void writeTruncatedImages(const fs::path& dir, const fs::path& png) {
  const std::string bytes = readFile(png);
  ASSERT_GT(bytes.size(), 1000u);
  writeFile(dir / "truncated.png", bytes.substr(0, bytes.size() / 2));
  writeFile(dir / "truncated.pgm", "P5\n640 480\n255\n" + std::string(640 * 100, '\x80'));
  writeFile(dir / "corrupt.png", "not an image at all");
}

// The stderr lines of a command: each one names its input and nothing else is there.
void expectOneLinePerBadInput(const std::string& command, const std::string& err,
                              const std::vector<std::string>& bad) {
  const auto errLines = lines(err);
  ASSERT_EQ(errLines.size(), bad.size()) << err;
  for (std::size_t i = 0; i < bad.size(); ++i) {
    EXPECT_EQ(errLines[i].rfind("imagepro-cli " + command + ": ", 0), 0u) << errLines[i];
    EXPECT_NE(errLines[i].find(bad[i]), std::string::npos) << errLines[i];
  }
}

// ---------------------------------------------------------------- render

TEST(CliRender, FramesAndTruthCsvAtTheAskedPose) {
  const fs::path dir = freshDir("cli_stages_render");
  const CliRun r = cli("render --out " + dir.string() +
                       " --frames 3 --mode binary --motion static --pose 0,0,20,30,-15,700");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(pngsIn(dir), (std::vector<std::string>{"frame_00000.png", "frame_00001.png", "frame_00002.png"}));

  const auto rows = lines(readFile(dir / "truth.csv"));
  ASSERT_EQ(rows.size(), 4u);
  // docs/conventions.md's pose CSV, then render's own column.
  EXPECT_EQ(rows[0], "frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm,in_view");
  const double asked[6] = {0, 0, 20, 30, -15, 700};
  for (int i = 0; i < 3; ++i) {
    const auto f = fields(rows[i + 1]);
    ASSERT_EQ(f.size(), 9u) << rows[i + 1];
    EXPECT_EQ(f[0], "frame_0000" + std::to_string(i) + ".png");
    EXPECT_EQ(f[1], "ok");
    for (int k = 0; k < 6; ++k) EXPECT_DOUBLE_EQ(number(f[2 + k]), asked[k]) << rows[i + 1];
    EXPECT_EQ(f[8], "1");

    const cv::Mat frame = cv::imread((dir / f[0]).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(frame.type(), CV_8UC1);
    EXPECT_EQ(frame.size(), cv::Size(640, 480));
  }

  // The frame shows the disk where the pose puts it: facing the camera it is a circle
  // centred on the projection of its centre (f = 8 mm / 0.01 mm = 800 px), radius
  // 800 * 50 / 700 px (the fit runs through the rim's inner pixels: up to 1 px less).
  const CliRun d = cli("detect " + (dir / "frame_00000.png").string());
  ASSERT_EQ(d.exit_code, 0) << d.err;
  const auto detected = lines(d.out);
  ASSERT_EQ(detected.size(), 2u) << d.out;
  const auto f = fields(detected[1]);
  ASSERT_EQ(f[1], "ok") << detected[1];
  EXPECT_NEAR(number(f[2]), 319.5 + 800.0 * 30.0 / 700.0, 0.5);
  EXPECT_NEAR(number(f[3]), 239.5 + 800.0 * -15.0 / 700.0, 0.5);
  const double radius = 800.0 * 50.0 / 700.0;
  for (int k : {4, 5}) {
    EXPECT_LE(number(f[k]), radius);
    EXPECT_GE(number(f[k]), radius - 1.0);
  }
}

TEST(CliRender, SinusoidTruthFollowsTheMotion) {
  const fs::path dir = freshDir("cli_stages_render_motion");
  const CliRun r = cli("render --out " + dir.string() +
                       " --frames 4 --mode binary --motion sinusoid --axis tx --amplitude 40 --period 1 --rate 8"
                       " --pose 0,0,0,0,0,800");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(readFile(dir / "truth.csv"));
  ASSERT_EQ(rows.size(), 5u);
  for (int i = 0; i < 4; ++i) {
    const auto f = fields(rows[i + 1]);
    // Frame i at t = i / 8 s: tx = 40 sin(2 pi t / 1 s).
    EXPECT_NEAR(number(f[5]), 40.0 * std::sin(2.0 * M_PI * i / 8.0), 1e-5) << rows[i + 1];
    EXPECT_DOUBLE_EQ(number(f[7]), 800.0);
  }
}

// ---------------------------------------------------------------- threshold

TEST(CliThreshold, AtOrigAndAtModAgreeOnEverySample) {
  const std::size_t samples = pngsIn(kSamples).size();
  ASSERT_GE(samples, 5u);
  const CliRun orig = cli("threshold --format csv --method at-orig " + kSamples);
  const CliRun mod = cli("threshold --format csv --method at-mod " + kSamples);
  ASSERT_EQ(orig.exit_code, 0) << orig.err;
  ASSERT_EQ(mod.exit_code, 0) << mod.err;
  EXPECT_TRUE(orig.err.empty()) << orig.err;
  const auto a = lines(orig.out), b = lines(mod.out);
  ASSERT_EQ(a.size(), samples + 1);  // a folder: one row per image in it
  EXPECT_EQ(a[0], "image,status,threshold");
  EXPECT_EQ(a, b);
  std::set<std::string> named;
  for (std::size_t i = 1; i < a.size(); ++i) {
    const auto f = fields(a[i]);
    ASSERT_EQ(f.size(), 3u) << a[i];
    EXPECT_EQ(f[1], "ok") << a[i];
    const int t = std::stoi(f[2]);
    EXPECT_GE(t, 0);
    EXPECT_LE(t, 255);
    named.insert(fileName(f[0]));
  }
  EXPECT_EQ(named.size(), samples);
}

TEST(CliThreshold, LiesBetweenTheRenderedBlackAndWhite) {
  const fs::path dir = freshDir("cli_stages_threshold_levels");
  // The target on its card, the scene around it at the card's black.
  ASSERT_EQ(cli("render --out " + dir.string() +
                " --frames 1 --mode grey --black 40 --white 200 --background 40 --clutter 0")
                .exit_code,
            0);
  const std::string frame = (dir / "frame_00000.png").string();
  // The settings' method (at-mod; at-orig gives the same, see above).
  const CliRun r = cli("threshold " + frame);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto out = lines(r.out);
  ASSERT_EQ(out.size(), 1u) << r.out;
  ASSERT_EQ(out[0].rfind(frame + ": ", 0), 0u) << out[0];
  const int t = std::stoi(out[0].substr(frame.size() + 2));
  // Binarization makes pixels above t white: black stays black, white becomes white.
  EXPECT_GE(t, 40);
  EXPECT_LT(t, 200);
}

TEST(CliThreshold, BadInputsAreNamedOnStderrAndExitOne) {
  const fs::path dir = freshDir("cli_stages_threshold_bad");
  fs::create_directories(dir / "empty");
  fs::create_directories(dir / "two");
  fs::copy_file(kSamples + "/sample01_facing.png", dir / "two" / "b10.png");
  fs::copy_file(kSamples + "/sample07_binary.png", dir / "two" / "b9.png");
  writeTruncatedImages(dir, kSamples + "/sample01_facing.png");
  writeFile(dir / "list.txt", "# a list\ntwo/b9.png\n\n" + kSamples + "/sample04_dim.png\n");
  const std::string good = kSamples + "/sample01_facing.png";

  const std::vector<std::string> bad = {(dir / "missing.png").string(), (dir / "truncated.png").string(),
                                        (dir / "truncated.pgm").string(), (dir / "corrupt.png").string(),
                                        (dir / "empty").string()};
  const std::string args = bad[0] + " " + good + " " + bad[1] + " " + bad[2] + " " + (dir / "two").string() + " " +
                           bad[3] + " " + (dir / "list.txt").string() + " " + bad[4];
  CliRun r = cli("threshold --format csv " + args);
  EXPECT_EQ(r.exit_code, 1);
  expectOneLinePerBadInput("threshold", r.err, bad);
  EXPECT_EQ(r.err.find("libpng"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("imdecode"), std::string::npos) << r.err;
  const auto rows = lines(r.out);
  // Every other input still processed, in order; folders and lists in natural / listed order.
  const std::vector<std::pair<std::string, std::string>> expected = {
      {bad[0], "FileNotFound"},  {good, "ok"},
      {bad[1], "FileTruncated"}, {bad[2], "FileUnreadable"},
      {(dir / "two" / "b9.png").string(), "ok"}, {(dir / "two" / "b10.png").string(), "ok"},
      {bad[3], "FileUnreadable"}, {(dir / "two" / "b9.png").string(), "ok"},
      {kSamples + "/sample04_dim.png", "ok"}, {bad[4], "FileNotFound"}};
  ASSERT_EQ(rows.size(), expected.size() + 1) << r.out;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const auto f = fields(rows[i + 1]);
    ASSERT_EQ(f.size(), 3u) << rows[i + 1];
    EXPECT_EQ(f[0], expected[i].first);
    EXPECT_EQ(f[1], expected[i].second) << rows[i + 1];
    EXPECT_EQ(f[2].empty(), expected[i].second != "ok") << rows[i + 1];
  }
  // The same image through a folder, a list and by name: the same threshold.
  EXPECT_EQ(fields(rows[5])[2], fields(rows[8])[2]);

  // Text format: a row per input too, the reason only on stderr.
  r = cli("threshold " + bad[0] + " " + good);
  EXPECT_EQ(r.exit_code, 1);
  expectOneLinePerBadInput("threshold", r.err, {bad[0]});
  EXPECT_NE(r.err.find("no such file"), std::string::npos) << r.err;
  const auto text = lines(r.out);
  ASSERT_EQ(text.size(), 2u) << r.out;
  EXPECT_EQ(text[0], bad[0] + ": FileNotFound");
  EXPECT_EQ(text[1].rfind(good + ": ", 0), 0u);

  // Readable images only (a folder of them): exit 0, nothing on stderr.
  r = cli("threshold " + (dir / "two").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_EQ(lines(r.out).size(), 2u);
  // Usage problems stay exit 2.
  EXPECT_EQ(cli("threshold --method otsu " + good).exit_code, 2);
}

// ---------------------------------------------------------------- edges

// Bennett on the samples: the target of every sample that has one, and no target in
// sample06, whose 67 x 8 px bar passes rules 1-3 but fits no ellipse (E_rel 0.043).
TEST(CliDetect, BennettFindsNoTargetInTheTargetFreeSample) {
  for (const char* method : {"bennett", "direct-fit"}) {
    const CliRun r = cli(std::string("detect --format csv --method ") + method + " " + kSamples);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto rows = lines(r.out);
    ASSERT_EQ(rows.size(), 1 + pngsIn(kSamples).size()) << r.out;
    for (std::size_t i = 1; i < rows.size(); ++i) {
      const auto f = fields(rows[i]);
      ASSERT_GE(f.size(), 2u) << rows[i];
      const bool target_free = fileName(f[0]) == "sample06_no_target.png";
      EXPECT_EQ(f[1], target_free ? "NoTarget" : "ok") << method << ": " << rows[i];
      ASSERT_EQ(f.size(), 12u) << rows[i];
      if (target_free) continue;
      EXPECT_LT(number(f[7]), 0.001) << rows[i];
      // The accumulator's score, quality and symmetry: Bennett's rows only.
      if (std::string(method) == "bennett") {
        EXPECT_GE(number(f[9]), 340.0) << rows[i];
        EXPECT_GT(number(f[10]), 0.0) << rows[i];
        EXPECT_GT(number(f[11]), 0.0) << rows[i];
      } else {
        EXPECT_EQ(f[9] + f[10] + f[11], "") << rows[i];
      }
    }
  }
  // The thesis's rules alone accept the bar.
  const fs::path dir = freshDir("cli_detect_bennett_thesis_rules");
  writeFile(dir / "rules.json", R"({"pipeline": {"ellipse": {"bennett_max_relative_error": 1e9}}})");
  const CliRun r = cli("detect --format csv --method bennett --config " + (dir / "rules.json").string() + " " +
                       kSamples + "/sample06_no_target.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 2u) << r.out;
  const auto f = fields(rows[1]);
  ASSERT_EQ(f[1], "ok") << rows[1];
  EXPECT_GT(number(f[7]), 0.02) << rows[1];
}

TEST(CliEdges, WritesTheStageImagesAndASummaryRow) {
  const fs::path dir = freshDir("cli_stages_edges");
  ASSERT_EQ(cli("render --out " + (dir / "in").string() + " --frames 1 --mode binary --pose 0,0,0,0,0,800").exit_code,
            0);
  const fs::path frameFile = dir / "in" / "frame_00000.png";
  const CliRun r = cli("edges --method laplace --connectivity cn1 --out " + (dir / "out").string() + " " +
                       frameFile.string() + " " + kSamples + "/sample02_clutter.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 3u) << r.out;
  EXPECT_EQ(rows[0], "frame,status,threshold,edge_pixels,paths,longest_path");
  EXPECT_EQ(pngsIn(dir / "out"),
            (std::vector<std::string>{"frame_00000_binary.png", "frame_00000_edges.png", "frame_00000_paths.png",
                                      "sample02_clutter_binary.png", "sample02_clutter_edges.png",
                                      "sample02_clutter_paths.png"}));

  const auto f = fields(rows[1]);
  ASSERT_EQ(f.size(), 6u) << rows[1];
  EXPECT_EQ(f[0], frameFile.string());
  EXPECT_EQ(f[1], "ok");
  const int t = std::stoi(f[2]), edgePixels = std::stoi(f[3]), paths = std::stoi(f[4]), longest = std::stoi(f[5]);
  // Facing the camera at 800 mm: the disk (R = 50 px) and its two spots (6 px) on a
  // black card, so three closed contours. An 8-connected digital circle of radius r has
  // about 4 sqrt(2) r pixels; the edge pixels lie half a pixel inside the disk's rim and
  // half a pixel outside each spot's.
  const double perRadius = 4.0 * std::sqrt(2.0);
  EXPECT_EQ(paths, 3);
  EXPECT_NEAR(longest, perRadius * 49.5, 0.05 * perRadius * 49.5);
  EXPECT_NEAR(edgePixels - longest, 2 * perRadius * 6.5, 0.1 * 2 * perRadius * 6.5);

  const cv::Mat grey = cv::imread(frameFile.string(), cv::IMREAD_UNCHANGED);
  const cv::Mat binary = cv::imread((dir / "out" / "frame_00000_binary.png").string(), cv::IMREAD_UNCHANGED);
  const cv::Mat edges = cv::imread((dir / "out" / "frame_00000_edges.png").string(), cv::IMREAD_UNCHANGED);
  const cv::Mat coloured = cv::imread((dir / "out" / "frame_00000_paths.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(binary.type(), CV_8UC1);
  ASSERT_EQ(edges.type(), CV_8UC1);
  ASSERT_EQ(coloured.type(), CV_8UC3);
  for (const cv::Mat* m : {&binary, &edges, &coloured}) EXPECT_EQ(m->size(), grey.size());
  // Eq. 2.1: white where the grey level is above t.
  const cv::Mat expectedBinary = grey > t;
  EXPECT_EQ(cv::countNonZero(binary != expectedBinary), 0);
  // Eq. 2.25: an edge pixel is a white pixel with a black 4-neighbour; the image border is no edge.
  int mismatches = 0;
  std::set<std::tuple<int, int, int>> colours;
  for (int y = 0; y < binary.rows; ++y)
    for (int x = 0; x < binary.cols; ++x) {
      const bool inside = x > 0 && y > 0 && x < binary.cols - 1 && y < binary.rows - 1;
      const bool edge = inside && binary.at<uchar>(y, x) && (!binary.at<uchar>(y - 1, x) || !binary.at<uchar>(y + 1, x) ||
                                                           !binary.at<uchar>(y, x - 1) || !binary.at<uchar>(y, x + 1));
      mismatches += edge != (edges.at<uchar>(y, x) == 255);
      const cv::Vec3b c = coloured.at<cv::Vec3b>(y, x);
      // Every edge pixel is in a path, coloured; nothing else is.
      mismatches += edge != (c != cv::Vec3b(0, 0, 0));
      if (edge) colours.insert({c[0], c[1], c[2]});
    }
  EXPECT_EQ(mismatches, 0);
  EXPECT_EQ(cv::countNonZero(edges), edgePixels);
  EXPECT_EQ(static_cast<int>(colours.size()), paths);

  // The cluttered sample: more paths than the target's three, longest within the count.
  const auto g = fields(rows[2]);
  EXPECT_EQ(g[1], "ok");
  EXPECT_GT(std::stoi(g[4]), 3);
  EXPECT_LE(std::stoi(g[5]), std::stoi(g[3]));
}

TEST(CliEdges, BadInputsAndRepeatedNames) {
  const fs::path dir = freshDir("cli_stages_edges_bad");
  for (const char* sub : {"a", "b"}) {
    fs::create_directories(dir / sub);
    fs::copy_file(kSamples + "/sample01_facing.png", dir / sub / "frame.png");
  }
  writeTruncatedImages(dir, kSamples + "/sample01_facing.png");
  const std::string missing = (dir / "missing.png").string();
  const CliRun r = cli("edges --out " + (dir / "out").string() + " " + missing + " " + (dir / "a").string() + " " +
                       (dir / "truncated.png").string() + " " + (dir / "b").string() + " " +
                       (dir / "truncated.pgm").string());
  EXPECT_EQ(r.exit_code, 1);
  expectOneLinePerBadInput("edges", r.err, {missing, "truncated.png", "truncated.pgm"});
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 6u) << r.out;
  EXPECT_EQ(rows[1], missing + ",FileNotFound,,,,");
  EXPECT_EQ(fields(rows[2])[1], "ok");
  EXPECT_EQ(rows[3], (dir / "truncated.png").string() + ",FileTruncated,,,,");
  EXPECT_EQ(fields(rows[4])[1], "ok");
  EXPECT_EQ(rows[5], (dir / "truncated.pgm").string() + ",FileUnreadable,,,,");
  // Both frame.png files have their images: the second with _2.
  EXPECT_EQ(pngsIn(dir / "out"),
            (std::vector<std::string>{"frame_2_binary.png", "frame_2_edges.png", "frame_2_paths.png",
                                      "frame_binary.png", "frame_edges.png", "frame_paths.png"}));

  // A PNG that cannot be written (a folder has its name): named too, exit 1.
  fs::create_directories(dir / "blocked" / "frame_edges.png");
  const CliRun blocked = cli("edges --out " + (dir / "blocked").string() + " " + (dir / "a" / "frame.png").string());
  EXPECT_EQ(blocked.exit_code, 1);
  expectOneLinePerBadInput("edges", blocked.err, {"FileNotWritable: " + (dir / "a" / "frame.png").string()});
  ASSERT_EQ(lines(blocked.out).size(), 2u) << blocked.out;
  EXPECT_EQ(fields(lines(blocked.out)[1])[1], "FileNotWritable");

  const CliRun empty = cli("edges " + (dir / "out" / "nothing.txt").string());
  EXPECT_EQ(empty.exit_code, 1);
  expectOneLinePerBadInput("edges", empty.err, {"nothing.txt"});
  EXPECT_EQ(cli("edges --method canny " + missing).exit_code, 2);
}

// ---------------------------------------------------------------- library and detect

// Rows of thesis tables B.1 (rectangles) and B.2 (ellipses): number, length (width or
// major length, px), rotation (degrees), aspect (width / height, major / minor).
struct TableRow {
  const char* shape;
  int number;
  double length, rotation, aspect;
};
const TableRow kRectangleRows[] = {
    {"rectangle", 1, 30, 0, 1}, {"rectangle", 14, 70, 45, 2}, {"rectangle", 33, 70, 30, 4},
    {"rectangle", 55, 70, 50, 16}, {"rectangle", 64, 110, 0, 1}, {"rectangle", 67, 110, 80, 2}};
const TableRow kEllipseRows[] = {
    {"ellipse", 11, 50, 45, 2}, {"ellipse", 21, 70, 30, 3}, {"ellipse", 33, 70, 50, 4},
    {"ellipse", 38, 70, 0, 5},  {"ellipse", 59, 89, 0, 2},  {"ellipse", 65, 110, 0, 1},
    {"ellipse", 70, 110, 80, 2}};

std::string libraryFile(const TableRow& row) {
  char name[32];
  std::snprintf(name, sizeof name, "%s_%02d.png", row.shape, row.number);
  return name;
}

class CliLibrary : public ::testing::Test {
 protected:
  // The library is written once for every test of this group run in one process; ctest
  // runs each test in a process of its own, in parallel, so each process has its folder.
  static void SetUpTestSuite() {
    dir_ = freshDir("cli_stages_library_" + std::to_string(getpid()));
    run_ = cli("library " + dir_.string());
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static fs::path dir_;
  static CliRun run_;
};
fs::path CliLibrary::dir_;
CliRun CliLibrary::run_;

TEST_F(CliLibrary, WritesTheTablesImagesAndCsv) {
  ASSERT_EQ(run_.exit_code, 0) << run_.err;
  const auto pngs = pngsIn(dir_);
  ASSERT_EQ(pngs.size(), 137u);
  EXPECT_EQ(std::count_if(pngs.begin(), pngs.end(), [](const std::string& n) { return n.rfind("rectangle_", 0) == 0; }), 67);
  EXPECT_EQ(std::count_if(pngs.begin(), pngs.end(), [](const std::string& n) { return n.rfind("ellipse_", 0) == 0; }), 70);

  const auto rows = lines(readFile(dir_ / "library.csv"));
  ASSERT_EQ(rows.size(), 138u);
  EXPECT_EQ(rows[0], "file,shape,number,length_px,rotation_deg,aspect,centre_u,centre_v,semi_major_px,semi_minor_px");
  std::map<std::string, std::vector<std::string>> byFile;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    auto f = fields(rows[i]);
    ASSERT_EQ(f.size(), 10u) << rows[i];
    EXPECT_TRUE(fs::exists(dir_ / f[0])) << f[0];
    byFile[f[0]] = std::move(f);
  }
  EXPECT_EQ(byFile.size(), 137u);

  std::vector<TableRow> checked(std::begin(kRectangleRows), std::end(kRectangleRows));
  checked.insert(checked.end(), std::begin(kEllipseRows), std::end(kEllipseRows));
  for (const TableRow& t : checked) {
    const std::string name = libraryFile(t);
    ASSERT_TRUE(byFile.count(name)) << name;
    const auto& f = byFile[name];
    EXPECT_EQ(f[1], t.shape);
    EXPECT_EQ(std::stoi(f[2]), t.number);
    EXPECT_DOUBLE_EQ(number(f[3]), t.length) << name;
    EXPECT_DOUBLE_EQ(number(f[4]), t.rotation) << name;
    EXPECT_DOUBLE_EQ(number(f[5]), t.aspect) << name;
    EXPECT_DOUBLE_EQ(number(f[6]), 319.5);
    EXPECT_DOUBLE_EQ(number(f[7]), 239.5);
    EXPECT_NEAR(number(f[8]), t.length / 2.0, 1e-4) << name;
    EXPECT_NEAR(number(f[9]), t.length / 2.0 / t.aspect, 1e-4) << name;

    // The image: binary 640x480, the shape centred, as long as the table says along
    // its rotation (at 0 degrees: the white columns span the length, +-1 px).
    const cv::Mat image = cv::imread((dir_ / name).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(image.type(), CV_8UC1) << name;
    EXPECT_EQ(image.size(), cv::Size(640, 480));
    EXPECT_EQ(cv::countNonZero((image != 0) & (image != 255)), 0) << name;
    cv::Mat white;
    cv::findNonZero(image, white);
    const cv::Rect box = cv::boundingRect(white);
    EXPECT_NEAR(box.x + (box.width - 1) / 2.0, 319.5, 0.5) << name;
    EXPECT_NEAR(box.y + (box.height - 1) / 2.0, 239.5, 0.5) << name;
    if (t.rotation == 0.0) {
      EXPECT_NEAR(box.width, t.length, 1.0) << name;
      EXPECT_NEAR(box.height, t.length / t.aspect, 1.0) << name;
    }
  }
}

TEST_F(CliLibrary, DetectFindsTheEllipsesAndRejectsTheRectangles) {
  ASSERT_EQ(run_.exit_code, 0) << run_.err;
  std::string args;
  for (const TableRow& t : kEllipseRows) args += " " + (dir_ / libraryFile(t)).string();
  for (const TableRow& t : kRectangleRows) args += " " + (dir_ / libraryFile(t)).string();
  const std::string missing = (dir_ / "ellipse_99.png").string();
  const CliRun r = cli("detect --format csv" + args + " " + missing);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(r.out);
  const std::size_t ellipses = std::size(kEllipseRows), rectangles = std::size(kRectangleRows);
  ASSERT_EQ(rows.size(), 1 + ellipses + rectangles + 1) << r.out;
  EXPECT_EQ(rows[0], "frame,status,cx,cy,a,b,angle_deg,fit_error,method,bennett_score,bennett_quality,bennett_symmetry_px");
  for (std::size_t i = 0; i < ellipses; ++i) {
    const TableRow& t = kEllipseRows[i];
    const auto f = fields(rows[1 + i]);
    ASSERT_EQ(f.size(), 12u) << rows[1 + i];
    EXPECT_EQ(fileName(f[0]), libraryFile(t));
    ASSERT_EQ(f[1], "ok") << rows[1 + i];
    EXPECT_NEAR(number(f[2]), 319.5, 1.0) << rows[1 + i];
    EXPECT_NEAR(number(f[3]), 239.5, 1.0) << rows[1 + i];
    // The edge pixels are the shape's white rim pixels, on average half a pixel inside
    // its outline; at the pointed ends of a thin ellipse (aspect 4 and more) up to one
    // and a half pixels inside along the major axis.
    const double axisTolerance = t.aspect <= 3.0 ? 1.0 : 1.5;
    EXPECT_NEAR(number(f[4]), t.length / 2.0, axisTolerance) << rows[1 + i];
    EXPECT_NEAR(number(f[5]), t.length / 2.0 / t.aspect, axisTolerance) << rows[1 + i];
    EXPECT_LE(number(f[4]), t.length / 2.0) << rows[1 + i];
    if (t.aspect > 1.0) {  // a circle has no major axis to turn
      const double turn = std::remainder(number(f[6]) - t.rotation, 180.0);
      EXPECT_NEAR(turn, 0.0, 1.0) << rows[1 + i];
    }
    EXPECT_LT(number(f[7]), 0.02);  // E_rel under the thesis's threshold (default accept rule)
    EXPECT_EQ(f[8], "direct-fit");
  }
  for (std::size_t i = 0; i < rectangles; ++i) {
    const auto f = fields(rows[1 + ellipses + i]);
    EXPECT_EQ(fileName(f[0]), libraryFile(kRectangleRows[i]));
    EXPECT_NE(f[1], "ok") << rows[1 + ellipses + i];
    EXPECT_NE(f[1], "AmbiguousTarget") << rows[1 + ellipses + i];
    EXPECT_EQ(f[2], "") << rows[1 + ellipses + i];
  }
  EXPECT_EQ(rows.back(), missing + ",FileNotFound,,,,,,,direct-fit,,,");
}

TEST_F(CliLibrary, DetectFoldersListsAndOverlays) {
  ASSERT_EQ(run_.exit_code, 0) << run_.err;
  const fs::path dir = freshDir("cli_stages_detect");
  // Two folders with the same file names: one ellipse each, and one rectangle.
  for (const char* sub : {"a", "b"}) {
    fs::create_directories(dir / sub);
    fs::copy_file(dir_ / "ellipse_21.png", dir / sub / "shape.png");
  }
  fs::copy_file(dir_ / "rectangle_14.png", dir / "b" / "box.png");
  fs::create_directories(dir / "empty");
  writeTruncatedImages(dir, dir_ / "ellipse_21.png");
  writeFile(dir / "list.txt", "a/shape.png\n");

  const CliRun r = cli("detect --overlay " + (dir / "overlays").string() + " " + (dir / "a").string() + " " +
                       (dir / "b").string() + " " + (dir / "list.txt").string() + " " + (dir / "empty").string() +
                       " " + (dir / "truncated.png").string() + " " + (dir / "truncated.pgm").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  // Each image that could not be read is named on stderr with its reason, once; the
  // decoders' own lines stay out.
  const auto errors = lines(r.err);
  ASSERT_EQ(errors.size(), 3u) << r.err;
  EXPECT_EQ(errors[0], "imagepro-cli detect: FileNotFound: " + (dir / "empty").string() + ": no image files in the folder");
  // The cut-off PNG is named as such; OpenCV cannot decode the cut-off PGM at all.
  EXPECT_EQ(errors[1], "imagepro-cli detect: FileTruncated: " + (dir / "truncated.png").string() +
                           ": the file ends before its image does (" +
                           std::to_string(fs::file_size(dir / "truncated.png")) + " bytes; cut off in a copy or a download?)");
  EXPECT_EQ(errors[2].rfind("imagepro-cli detect: FileUnreadable: " + (dir / "truncated.pgm").string(), 0), 0u) << errors[2];
  EXPECT_NE(errors[2].find("not a readable image"), std::string::npos) << errors[2];
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 8u) << r.out;
  const std::vector<std::pair<std::string, std::string>> expected = {
      {(dir / "a" / "shape.png").string(), "ok"},
      {(dir / "b" / "box.png").string(), ""},  // not ok; its name depends on the detector
      {(dir / "b" / "shape.png").string(), "ok"},
      {(dir / "a" / "shape.png").string(), "ok"},
      {(dir / "empty").string(), "FileNotFound"},
      {(dir / "truncated.png").string(), "FileTruncated"},
      {(dir / "truncated.pgm").string(), "FileUnreadable"}};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const auto f = fields(rows[1 + i]);
    EXPECT_EQ(f[0], expected[i].first);
    if (expected[i].second.empty()) EXPECT_NE(f[1], "ok") << rows[1 + i];
    else EXPECT_EQ(f[1], expected[i].second) << rows[1 + i];
  }
  // One overlay per image read, none replacing another.
  EXPECT_EQ(pngsIn(dir / "overlays"),
            (std::vector<std::string>{"box.png", "shape.png", "shape_2.png", "shape_3.png"}));
  const cv::Mat overlay = cv::imread((dir / "overlays" / "shape_2.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(overlay.type(), CV_8UC3);
  EXPECT_EQ(overlay.size(), cv::Size(640, 480));
  // The target drawn in green over the grey image: some pixels are no longer grey.
  std::vector<cv::Mat> bgr;
  cv::split(overlay, bgr);
  EXPECT_GT(cv::countNonZero(bgr[1] != bgr[0]), 100);

  // Text format, and the help names the overlay rule.
  const CliRun text = cli("detect --format text " + (dir / "a" / "shape.png").string());
  EXPECT_EQ(text.exit_code, 0);
  EXPECT_NE(text.out.find(": ok centre (319.50, 239.50)"), std::string::npos) << text.out;
  EXPECT_NE(cli("detect --help").out.find("_2, _3"), std::string::npos);
}

// detect --accumulators: Bennett's accumulators as pictures (thesis figs. 2.17-2.23).
// The image-sized picture peaks at the ellipse's centre and is black outside the
// path's box; each shown path gets an enlarged picture with the centre marked in red.
TEST_F(CliLibrary, DetectWritesBennettsAccumulators) {
  ASSERT_EQ(run_.exit_code, 0) << run_.err;
  const fs::path dir = freshDir("cli_stages_accumulators");
  const std::string ellipse = (dir_ / "ellipse_21.png").string(), rectangle = (dir_ / "rectangle_14.png").string();
  const CliRun r = cli("detect --accumulators " + (dir / "acc").string() + " " + ellipse + " " + rectangle);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto files = pngsIn(dir / "acc");
  ASSERT_EQ(files.size(), 4u) << ::testing::PrintToString(files);
  EXPECT_EQ(files[0], "ellipse_21_accumulator.png");
  EXPECT_EQ(files[1].rfind("ellipse_21_path", 0), 0u) << files[1];
  EXPECT_EQ(files[2], "rectangle_14_accumulator.png");
  EXPECT_EQ(files[3].rfind("rectangle_14_path", 0), 0u) << files[3];  // none accepted: the highest score

  const cv::Mat all = cv::imread((dir / "acc" / files[0]).string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(all.type(), CV_8UC1);
  EXPECT_EQ(all.size(), cv::Size(640, 480));
  double peak = 0.0;
  cv::Point at;
  cv::minMaxLoc(all, nullptr, &peak, nullptr, &at);
  EXPECT_EQ(peak, 255.0);
  EXPECT_NEAR(at.x, 319.5, 2.0);
  EXPECT_NEAR(at.y, 239.5, 2.0);
  EXPECT_EQ(all.at<std::uint8_t>(0, 0), 0);
  EXPECT_EQ(all.at<std::uint8_t>(479, 639), 0);

  const cv::Mat path = cv::imread((dir / "acc" / files[1]).string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(path.type(), CV_8UC3);
  EXPECT_GE(std::max(path.cols, path.rows), 160);  // enlarged from the ellipse's box
  cv::Mat red_pixels;
  cv::inRange(path, cv::Scalar(0, 0, 255), cv::Scalar(0, 0, 255), red_pixels);
  ASSERT_GT(cv::countNonZero(red_pixels), 0);
  const cv::Rect marked = cv::boundingRect(red_pixels);
  EXPECT_NEAR((marked.x + marked.br().x) / 2.0, path.cols / 2.0, path.cols * 0.05);
  EXPECT_NEAR((marked.y + marked.br().y) / 2.0, path.rows / 2.0, path.rows * 0.05);

  // A folder that cannot be made is the command line's error.
  writeFile(dir / "file", "x");
  const CliRun bad = cli("detect --accumulators " + (dir / "file" / "sub").string() + " " + ellipse);
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("--accumulators: cannot create folder"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace imagepro
