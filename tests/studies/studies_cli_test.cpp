// imagepro-studies run as a user would: its command list, each study's help, the
// accuracy study's report and the peers' bench on the smallest runs.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>

#include "core/common/atomic_file.h"
#include "support/cli_run.h"
#include "support/photographs.h"
#include "support/test_dirs.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;
using test::CliRun;
using test::freshDir;
using test::lines;
using test::studies;

TEST(Studies, OverviewListsTheStudiesAndEachHasHelp) {
  const CliRun r = studies("--help");
  ASSERT_EQ(r.exit_code, 0);
  for (const char* c :
       {"accuracy", "calibration-study", "track-study", "pendulum-study", "ellipse-library", "bench-peers",
        "distortion-figures"})
    EXPECT_NE(r.out.find(std::string("  ") + c + " "), std::string::npos) << c;
  const std::vector<std::string> names = test::overviewCommands(r.out);
  EXPECT_GE(names.size(), 7u);
  for (const std::string& name : names) {
    const CliRun help = studies(name + " --help");
    EXPECT_EQ(help.exit_code, 0) << name;
    EXPECT_NE(help.out.find("usage: imagepro-studies " + name), std::string::npos) << name;
  }
  const CliRun unknown = studies("reconstruct");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("imagepro-studies: unknown command \"reconstruct\""), std::string::npos) << unknown.err;
}

// pendulum-study prints only Markdown tables; a table it does not know is a usage error.
TEST(Studies, PendulumStudyPrintsTheAmplitudeTable) {
  const CliRun r = studies("pendulum-study --table amplitudes");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 6u) << r.out;  // header, rule, 5, 10, 15 and 25 deg
  EXPECT_EQ(rows[0], "| amplitude | length [mm] | period [s] (truth) | g [m/s^2] |");
  // The 15 deg row's length, against the virtual pendulum's 444 mm.
  ASSERT_EQ(rows[4].rfind("| 15 deg | ", 0), 0u) << rows[4];
  EXPECT_NEAR(std::stod(rows[4].substr(std::string("| 15 deg | ").size())), 444.0, 0.5) << rows[4];
  EXPECT_EQ(studies("pendulum-study --table sets").exit_code, 2);
}

// ellipse-library classifies the binary library as the thesis's direct fit must: every
// ellipse found, no rectangle accepted.
TEST(Studies, EllipseLibraryTheDefaultRuleClassifiesTheBinaryLibrary) {
  const CliRun r = studies("ellipse-library --table methods");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 8u) << r.out;  // header, rule, two thesis rows, four of ours
  EXPECT_EQ(rows[4], "| direct fit, E_rel ≤ 0.02 + trace (default) | 70 of 70 | 0 of 67 | this implementation |");
  EXPECT_EQ(studies("ellipse-library --table grey").exit_code, 2);
}

// ellipse-library --plots writes the thesis's per-image figures of the library as
// charts, and prints no table; --plots with --table is a usage error.
TEST(Studies, EllipseLibraryPlotsTheLibraryPerImage) {
  const fs::path dir = freshDir("studies_library_plots");
  const CliRun r = studies("ellipse-library --plots " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "");
  for (const char* name : {"edge-pixels", "symmetry", "score", "quality", "peak-share", "relative-error", "length",
                           "rotation", "aspect"}) {
    const cv::Mat chart = cv::imread((dir / (std::string("ellipse-library-") + name + ".png")).string());
    ASSERT_FALSE(chart.empty()) << name;
    EXPECT_EQ(chart.size(), cv::Size(900, 420)) << name;
    // Both shapes' dots are drawn: the rectangles' red and the ellipses' blue.
    cv::Mat red, blue;
    cv::inRange(chart, cv::Scalar(0, 50, 200), cv::Scalar(20, 70, 230), red);
    cv::inRange(chart, cv::Scalar(190, 70, 0), cv::Scalar(210, 90, 20), blue);
    EXPECT_GT(cv::countNonZero(red), 100) << name;
    EXPECT_GT(cv::countNonZero(blue), 100) << name;
  }
  EXPECT_EQ(studies("ellipse-library --plots " + dir.string() + " --table methods").exit_code, 2);
}

// track-study writes the tracking runs of thesis figs. 3.7-3.12 beside its report: one
// chart each, listed in a table whose largest errors are those of a working tracker.
TEST(Studies, TrackStudyWritesTheTrackingRuns) {
  const fs::path dir = freshDir("studies_track");
  const std::string doc = std::string(IMAGEPRO_SOURCE_DIR) + "/docs/tracking.md";
  const CliRun r = studies("track-study --frames 60 --template " + doc + " --out " + (dir / "tracking.md").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string md, e;
  ASSERT_TRUE(readWholeFile((dir / "tracking.md").string(), md, e)) << e;
  // The prose is the doc's; the run's own figures are filled in.
  EXPECT_NE(md.find("The default <!--m:default.min_r-->0.9<!--/m--> follows the thesis's rule"), std::string::npos);
  EXPECT_NE(md.find("--frames 60 --out " + (dir / "tracking.md").string()), std::string::npos);
  const CliRun missing = studies("track-study --frames 60 --out " + (dir / "none" / "tracking.md").string());
  EXPECT_EQ(missing.exit_code, 1) << missing.err;
  EXPECT_NE(missing.err.find("--template"), std::string::npos) << missing.err;
  const std::size_t section = md.find("## The tracking runs (thesis figs. 3.7-3.12)");
  ASSERT_NE(section, std::string::npos);
  std::vector<std::string> rows;
  for (const std::string& line : lines(md.substr(section)))
    if (line.rfind("| 3.", 0) == 0) rows.push_back(line);
  ASSERT_EQ(rows.size(), 6u) << md.substr(section);
  const char* files[] = {"tracking-sinusoid.png",     "tracking-sinusoid-3d.png",  "tracking-saw-tooth-2d.png",
                         "tracking-saw-tooth-3d.png", "tracking-pendulum-2d.png", "tracking-pendulum-3d.png"};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_NE(rows[i].find(std::string("`") + files[i] + "`"), std::string::npos) << rows[i];
    EXPECT_NE(md.find(std::string("](") + files[i] + ")"), std::string::npos) << files[i];
    const cv::Mat chart = cv::imread((dir / files[i]).string());
    ASSERT_FALSE(chart.empty()) << files[i];
    EXPECT_EQ(chart.size(), cv::Size(900, 420));
    // The largest error: the column before the plot's; the saw-tooth's turns cost most.
    std::vector<std::string> cells;
    std::istringstream row(rows[i]);
    for (std::string cell; std::getline(row, cell, '|');) cells.push_back(cell);
    ASSERT_GE(cells.size(), 7u) << rows[i];  // an empty cell before the first '|'
    const double largest = std::stod(cells[5]);
    EXPECT_GT(largest, 0.0) << rows[i];
    EXPECT_LT(largest, 20.0) << rows[i];
  }
  EXPECT_TRUE(fs::exists(dir / "tracking-critical-r.png"));
}

// distortion-figures: the table of the four lenses within the thesis's bounds for the
// Taylor inverse (4.5: 1 px for pure radial and for its camera, 6 px for composite), and
// with --plots the figures of 4.3-4.5 and 4.7-4.10 and the error chart.
TEST(Studies, DistortionFiguresTableAndPlots) {
  const fs::path dir = freshDir("studies_distortion");
  const CliRun r = studies("distortion-figures --plots " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 6u) << r.out;
  const std::pair<const char*, double> bounds[] = {
      {"| pure radial | 4.3, 4.7 |", 1.0}, {"| pure tangential | 4.4, 4.8 |", 1.0},
      {"| composite | 4.5, 4.9 |", 6.0}, {"| thesis camera | 4.10 |", 1.0}};
  for (std::size_t i = 0; i < 4; ++i) {
    ASSERT_EQ(rows[2 + i].rfind(bounds[i].first, 0), 0u) << rows[2 + i];
    std::vector<std::string> cells;
    std::istringstream row(rows[2 + i]);
    for (std::string cell; std::getline(row, cell, '|');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 10u) << rows[2 + i];
    const double displacement = std::stod(cells[7]), taylor = std::stod(cells[8]);
    EXPECT_GT(displacement, 15.0) << rows[2 + i];  // the lenses move pixels by tens of px
    EXPECT_GT(taylor, 0.0) << rows[2 + i];
    EXPECT_LE(taylor, bounds[i].second) << rows[2 + i];
  }
  EXPECT_EQ(rows[5], "| thesis camera | 4.10 | -2.05e-07 | -1.21e-13 | 3.39e-06 | 2.56e-06 | 18.7 | 0.030 | 0.0022 |");
  for (const char* name : {"radial-field", "tangential-field", "composite-field", "radial-correction",
                           "tangential-correction", "composite-correction", "thesis-camera-correction"}) {
    const cv::Mat figure = cv::imread((dir / (std::string("distortion-") + name + ".png")).string());
    ASSERT_FALSE(figure.empty()) << name;
    EXPECT_EQ(figure.size(), cv::Size(740, 620)) << name;
    cv::Mat green;  // the distorted grid or points
    cv::inRange(figure, cv::Scalar(0, 140, 0), cv::Scalar(40, 160, 40), green);
    EXPECT_GT(cv::countNonZero(green), 500) << name;
  }
  EXPECT_EQ(cv::imread((dir / "distortion-taylor-error.png").string()).size(), cv::Size(900, 420));
  // Without --plots: the table alone.
  const CliRun table = studies("distortion-figures");
  EXPECT_EQ(table.exit_code, 0);
  EXPECT_EQ(table.out, r.out);
}

// The repository's hand-written report, whose measured places the accuracy study fills.
std::string accuracyTemplate() { return std::string(IMAGEPRO_SOURCE_DIR) + "/docs/accuracy.md"; }

// The accuracy study's virtual part end to end on the smallest run: a complete report
// that names the command regenerating it, the real scenes' text left as the template has it
// (they are measured in real_scene_accuracy_test.cpp).
TEST(Studies, AccuracySmokeRunWritesItsReport) {
  const fs::path dir = freshDir("studies_accuracy");
  const fs::path out = dir / "accuracy.md";
  const CliRun r =
      studies("accuracy --scene virtual --frames 2 --seed 3 --template " + accuracyTemplate() + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string md, doc, e;
  ASSERT_TRUE(readWholeFile(out.string(), md, e)) << e;
  ASSERT_TRUE(readWholeFile(accuracyTemplate(), doc, e)) << e;
  EXPECT_EQ(md.rfind("# Accuracy\n", 0), 0u);
  for (const char* part :
       {"`imagepro-studies accuracy --scene virtual --frames 2 --seed 3`", "## Goals, thesis camera", "| detection, whole target visible |",
        "The same goals per tilt band", "## No lens distortion", "## Thesis camera's lens distortion, corrected",
        "| sub-pixel | 2 |", "| ArUco 4x4 (IPPE) | 2 |", "## The plane normal", "## Lens distortion correction",
        "| thesis camera x 1.0 |"})
    EXPECT_NE(md.find(part), std::string::npos) << part;
  const std::size_t real = md.find("## Real scenes"), templateReal = doc.find("## Real scenes");
  ASSERT_NE(real, std::string::npos);
  ASSERT_NE(templateReal, std::string::npos);
  EXPECT_EQ(md.substr(0, real).find("nan"), std::string::npos);
  EXPECT_EQ(md.substr(real), doc.substr(templateReal));
  const CliRun bad = studies("accuracy --frames 0");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("imagepro-studies accuracy: "), std::string::npos) << bad.err;
}

// A template that disagrees with the study is refused, naming the value, and --out is not
// written: a value without a place, or a place of the part run that the study does not know.
TEST(Studies, AccuracyRefusesATemplateWithoutAPlaceForAValue) {
  const fs::path dir = freshDir("studies_accuracy_template");
  const std::string doc = test::readText(accuracyTemplate());
  const std::string open = "<!--m:virtual.normal_ratios-->";
  const std::size_t at = doc.find(open);
  ASSERT_NE(at, std::string::npos);
  std::string lacking = doc;
  lacking.erase(at, open.size());
  lacking.erase(lacking.find("<!--/m-->", at), std::string("<!--/m-->").size());
  test::writeText(dir / "lacking.md", lacking);
  const fs::path out = dir / "accuracy.md";
  const CliRun r = studies("accuracy --scene virtual --frames 1 --template " + (dir / "lacking.md").string() +
                           " --out " + out.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("'virtual.normal_ratios'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("lacking.md"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));

  test::writeText(dir / "extra.md", doc + "\nAnd <!--m:virtual.unknown-->1<!--/m-->.\n");
  const CliRun extra = studies("accuracy --scene virtual --frames 1 --template " + (dir / "extra.md").string() +
                               " --out " + out.string());
  EXPECT_EQ(extra.exit_code, 1);
  EXPECT_NE(extra.err.find("no value for 'virtual.unknown'"), std::string::npos) << extra.err;
  EXPECT_FALSE(fs::exists(out));
}

// The peers on the same frames as the engine: every method finds the target in every
// frame of the bench scene, and the report carries each one's rate. Without photographs
// the real scenes, and ArUco with them, are left out.
TEST(Studies, BenchPeersTimesTheEngineAndBothPeers) {
  const fs::path empty = freshDir("studies_bench_no_photos");
  const CliRun r = studies("bench-peers --frames 10 --format json --backgrounds " + empty.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"full_frame_hz", "tracked_hz", "opencv_pipeline_hz", "apriltag_hz"})
    EXPECT_GT(j.at(key).get<double>(), 0.0) << key;
  const auto& res = j.at("resolutions").at(0);
  for (const char* key : {"full_frame_found", "tracked_found", "opencv_pipeline_found", "apriltag_found"})
    EXPECT_EQ(res.at(key).get<int>(), 10) << key;
  EXPECT_FALSE(j.contains("real_aruco_hz"));
  EXPECT_NE(r.err.find("real scenes: left out, no photographs in " + empty.string()), std::string::npos) << r.err;
  EXPECT_EQ(studies("bench-peers --frames 3").exit_code, 2);
}

// On real scenes the robust peer, ArUco, is timed on the very frames the engine was, its
// marker in the target's place, and the text gives the engine's ratios against it.
TEST(Studies, BenchPeersTimesArucoOnRealScenes) {
  if (const std::string why = test::missingPhotographs(); !why.empty()) GTEST_SKIP() << why;
  const CliRun json = studies("bench-peers --frames 10 --format json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  for (const char* key : {"real_full_frame_hz", "real_tracked_hz", "real_aruco_hz"})
    EXPECT_GT(j.at(key).get<double>(), 0.0) << key;
  const auto& res = j.at("resolutions").at(0);
  EXPECT_EQ(res.at("real_frames").get<int>(), 10);
  for (const char* key : {"real_full_frame_found", "real_tracked_found", "real_aruco_found"}) {
    EXPECT_GE(res.at(key).get<int>(), 8) << key;  // large, clear targets and markers
    EXPECT_LE(res.at(key).get<int>(), 10) << key;
  }
  const CliRun text = studies("bench-peers --frames 10");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  const std::size_t real = text.out.find("real scenes, 10 frames");
  ASSERT_NE(real, std::string::npos) << text.out;
  EXPECT_NE(text.out.find("ArUco 4x4 (OpenCV, IPPE)", real), std::string::npos);
  EXPECT_NE(text.out.find("ratios: full/ArUco ", real), std::string::npos);
  EXPECT_NE(text.out.find("tracked/ArUco ", real), std::string::npos);
}

}  // namespace
}  // namespace imagepro
