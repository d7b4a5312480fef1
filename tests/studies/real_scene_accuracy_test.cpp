// imagepro-studies accuracy --scene real run as a user would, on a handful of frames: the
// report's two columns (target and ArUco marker) in both tables, figures that add up, and
// the target's figures equal to what the engine gives on the same frames, run here. The
// report is the repository's docs/accuracy.md with its measured places filled.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/common/atomic_file.h"
#include "core/pipeline/engine.h"
#include "core/source/real_scene_video.h"
#include "support/cli_run.h"
#include "support/photographs.h"
#include "support/test_dirs.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;
using test::freshDir;
using test::lines;
using test::studies;

constexpr int kSeed = 5, kStills = 12, kNegatives = 4, kVideoFrames = 30, kHidden = 12, kWebcamStills = 10;

std::string accuracyTemplate() { return std::string(IMAGEPRO_SOURCE_DIR) + "/docs/accuracy.md"; }

// The text between the first `from` and the first `to` after it.
std::string between(const std::string& md, const std::string& from, const std::string& to) {
  const std::size_t a = md.find(from);
  if (a == std::string::npos) return {};
  return md.substr(a, md.find(to, a) - a);
}

// The cells of the table row that starts with `measure`, in the section that starts at
// `heading`: measure, goal, target, marker.
std::vector<std::string> row(const std::string& md, const std::string& heading, const std::string& measure) {
  const std::size_t from = md.find(heading);
  if (from == std::string::npos) return {};
  for (const std::string& line : lines(md.substr(from))) {
    if (line.rfind("| " + measure + " |", 0) != 0) continue;
    std::vector<std::string> cells;
    std::size_t at = 1;
    for (std::size_t bar; (bar = line.find('|', at)) != std::string::npos; at = bar + 1) {
      std::string c = line.substr(at, bar - at);
      c.erase(0, c.find_first_not_of(' '));
      c.erase(c.find_last_not_of(' ') + 1);
      cells.push_back(c);
    }
    return cells;
  }
  return {};
}

// "n of m ..." -> (n, m); (-1, -1) when the cell says something else.
std::pair<int, int> counted(const std::string& cell) {
  int n = -1, m = -1;
  if (std::sscanf(cell.c_str(), "%d of %d", &n, &m) != 2) return {-1, -1};
  return {n, m};
}

double number(const std::string& cell) { return cell == "-" ? NAN : std::stod(cell); }

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

bool hasPose(const FrameResult& r) { return r.status == Status::Ok && r.pose.has_value(); }

// Frame `index` through `engine`: a still when it has a `name`, else a video's frame.
FrameResult process(Engine& engine, const RealSceneFrame& f, int index, const std::string& name) {
  Frame frame;
  frame.image = f.image;
  frame.index = index;
  frame.name = name;
  frame.timestamp_s = name.empty() ? index / RealSceneVideo::kFrameRateHz : 0.0;
  FrameResult result;
  engine.process(frame, result);
  return result;
}

// What the engine gives on a set of frames with the target.
struct EngineFigures {
  int frames = 0, posed = 0, correct = 0, wrong = 0;
  std::vector<double> rotation_deg;
  void add(const FrameResult& r, const Pose& truth) {
    ++frames;
    if (!hasPose(r)) return;
    ++posed;
    rotation_deg.push_back(rotationAngleBetweenDeg(rotationMatrix(truth), rotationMatrix(*r.pose)));
    (rotation_deg.back() <= 5.0 ? correct : wrong)++;
  }
};

// The report's target or marker column for `figures`' rows in `heading`'s table.
void expectColumn(const std::string& md, const std::string& heading, const std::string& frames_row, int column,
                  int frames, const EngineFigures* engine) {
  const auto posed = counted(row(md, heading, frames_row).at(column));
  const auto correct = counted(row(md, heading, "frames with a correct pose (rotation error <= 5 deg)").at(column));
  const auto wrong =
      counted(row(md, heading, "poses reported but off by more than 5 deg (of the poses)").at(column));
  EXPECT_EQ(posed.second, frames) << heading << column;
  EXPECT_EQ(correct.second, frames) << heading << column;
  EXPECT_GE(posed.first, 0);
  EXPECT_LE(posed.first, frames);
  EXPECT_EQ(correct.first + wrong.first, posed.first) << heading << column;
  EXPECT_EQ(wrong.second, posed.first) << heading << column;
  const std::vector<std::string> median_row = row(md, heading, "rotation error, median");
  const std::vector<std::string> p95_row = row(md, heading, "rotation error, 95th percentile");
  if (posed.first > 0) {
    EXPECT_LE(number(median_row.at(column)), number(p95_row.at(column))) << heading << column;
  }
  if (!engine) return;
  EXPECT_EQ(posed.first, engine->posed) << heading;
  EXPECT_EQ(correct.first, engine->correct) << heading;
  EXPECT_EQ(wrong.first, engine->wrong) << heading;
  // Printed to 3 decimals below 10 deg, to 1 above.
  const double m = median(engine->rotation_deg);
  if (engine->posed > 0) {
    EXPECT_NEAR(number(median_row.at(column)), m, m < 10 ? 6e-4 : 0.06) << heading;
  }
}

TEST(StudiesRealScenes, TargetBesideTheMarkerAsTheEngineGivesIt) {
  if (const std::string why = test::missingPhotographs(); !why.empty()) GTEST_SKIP() << why;
  std::vector<std::string> photos = listBackgrounds(defaultBackgroundsDir());
  const fs::path out = freshDir("studies_real_accuracy") / "accuracy.md";
  const std::string options = "--stills " + std::to_string(kStills) + " --negatives " + std::to_string(kNegatives) +
                              " --videos 1 --video-frames " + std::to_string(kVideoFrames) + " --webcam-stills " +
                              std::to_string(kWebcamStills) + " --webcam-negatives 2 --seed " + std::to_string(kSeed);
  const test::CliRun r =
      studies("accuracy --scene real " + options + " --template " + accuracyTemplate() + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string md, e;
  ASSERT_TRUE(readWholeFile(out.string(), md, e)) << e;
  EXPECT_NE(md.find("`imagepro-studies accuracy --scene real " + options + "`"), std::string::npos);
  // The virtual part is not asked for: its text stays as the template has it.
  const std::string virtual_part = between(md, "\nVirtual grey ", "## Real scenes");
  EXPECT_FALSE(virtual_part.empty());
  EXPECT_EQ(virtual_part, between(test::readText(accuracyTemplate()), "\nVirtual grey ", "## Real scenes"));
  EXPECT_EQ(md.find("nan"), std::string::npos);
  const std::string header = "| measure | goal | target (default pipeline) | ArUco 4x4 marker |";
  const std::size_t first = md.find(header);
  ASSERT_NE(first, std::string::npos);
  EXPECT_NE(md.find(header, first + 1), std::string::npos) << "the videos' table";

  // The same frames through the engine here: each still alone, the video tracked.
  const Settings settings;
  const RealScenes scenes(settings, std::move(photos));
  Engine engine(settings);
  EngineFigures stills, video;
  int false_detections = 0, found_in_hiding = 0;
  std::string error;
  for (int i = 0; i < kStills + kNegatives; ++i) {
    RealSceneFrame f;
    ASSERT_TRUE(scenes.still(kSeed, i, i < kStills, f, error)) << error;
    engine.resetTracking();
    const FrameResult result = process(engine, f, i, "still_" + std::to_string(i) + ".png");
    if (f.truth)
      stills.add(result, *f.truth);
    else
      false_detections += hasPose(result);
  }
  const RealSceneVideo sequence(scenes, kSeed, kVideoFrames, kHidden);
  engine.resetTracking();
  for (int i = 0; i < sequence.frames(); ++i) {
    RealSceneFrame f;
    ASSERT_TRUE(sequence.frame(i, f, error)) << error;
    const FrameResult result = process(engine, f, i, "");
    if (f.truth)
      video.add(result, *f.truth);
    else
      found_in_hiding += hasPose(result);
  }

  const std::string still_table = "### Stills and negatives", video_table = "### Videos";
  expectColumn(md, still_table, "frames with a pose (of the stills)", 2, kStills, &stills);
  expectColumn(md, still_table, "frames with a pose (of the stills)", 3, kStills, nullptr);
  expectColumn(md, video_table, "frames with a pose (of the visible frames)", 2, kVideoFrames - kHidden, &video);
  expectColumn(md, video_table, "frames with a pose (of the visible frames)", 3, kVideoFrames - kHidden, nullptr);
  const auto negatives = row(md, still_table, "false detections on the negatives");
  EXPECT_EQ(counted(negatives.at(2)), std::make_pair(false_detections, kNegatives));
  EXPECT_EQ(counted(negatives.at(3)).second, kNegatives);
  const auto hiding = row(md, video_table, "poses while the target is hidden");
  EXPECT_EQ(counted(hiding.at(2)), std::make_pair(found_in_hiding, kHidden));
  // The statuses of the target's misses account for every still without a pose.
  int missed = 0;
  const std::string statuses = row(md, still_table, "statuses of the frames without a pose").at(2);
  for (std::size_t at = 0; (at = statuses.find_first_of("0123456789", at)) != std::string::npos;) {
    std::size_t used = 0;
    missed += std::stoi(statuses.substr(at), &used);
    at += used;
  }
  EXPECT_EQ(missed, kStills - stills.posed) << statuses;
  // The marker, large and clear in the video, is found and right most of the time.
  EXPECT_GE(counted(row(md, video_table, "frames with a correct pose (rotation error <= 5 deg)").at(3)).first,
            (kVideoFrames - kHidden) / 2);

  // The webcam set: its stills through the engine with the shipped wide lens and the rig's
  // effects, as the report counts them, and every still in the table by effect.
  Settings webcam;
  ASSERT_EQ(loadSettings(std::string(IMAGEPRO_DATA_DIR) + "/webcam-1280x720.json", webcam, error), Status::Ok) << error;
  const RealScenes rigged(webcam, listBackgrounds(defaultBackgroundsDir()), kWebcamRigEffects);
  Engine webcam_engine(webcam);
  EngineFigures webcam_stills;
  for (int i = 0; i < kWebcamStills; ++i) {
    RealSceneFrame f;
    ASSERT_TRUE(rigged.still(kSeed, i, true, f, error)) << error;
    webcam_engine.resetTracking();
    webcam_stills.add(process(webcam_engine, f, i, "still_" + std::to_string(i) + ".png"), *f.truth);
  }
  const std::string webcam_table = "## The webcam set";
  ASSERT_NE(md.find(webcam_table), std::string::npos);
  expectColumn(md, webcam_table, "frames with a pose (of the stills)", 2, kWebcamStills, &webcam_stills);
  int by_effect = 0;
  const std::size_t effects = md.find("### The target's stills by what the rig did to them");
  ASSERT_NE(effects, std::string::npos);
  // The table's rows: from the line after its header and rule to the first line not a row.
  std::size_t at = md.find("| --- |", effects);
  ASSERT_NE(at, std::string::npos);
  for (at = md.find('\n', at) + 1; md.compare(at, 2, "| ") == 0; at = md.find('\n', at) + 1)
    by_effect += std::stoi(md.substr(md.find(" | ", at + 2) + 3));
  EXPECT_EQ(by_effect, kWebcamStills);
}

// Without photographs: the real part alone is an error that says why; with the virtual
// part the report stands and says what it lacks.
TEST(StudiesRealScenes, WithoutPhotographsTheReportSaysSo) {
  const fs::path dir = freshDir("studies_real_none");
  const fs::path empty = dir / "photos";
  fs::create_directories(empty);
  const fs::path out = dir / "accuracy.md";
  const std::string doc = " --template " + accuracyTemplate() + " --out " + out.string();
  const test::CliRun alone = studies("accuracy --scene real --stills 2 --backgrounds " + empty.string() + doc);
  EXPECT_EQ(alone.exit_code, 1);
  EXPECT_NE(alone.err.find("no photographs"), std::string::npos) << alone.err;
  EXPECT_FALSE(fs::exists(out));
  const test::CliRun both = studies("accuracy --frames 1 --stills 2 --backgrounds " + empty.string() + doc);
  ASSERT_EQ(both.exit_code, 0) << both.err;
  std::string md, e;
  ASSERT_TRUE(readWholeFile(out.string(), md, e)) << e;
  EXPECT_NE(md.find("## No lens distortion\n\nTarget detected in <!--m:virtual.no_lens.detected-->1<!--/m--> of"),
            std::string::npos);
  // Both real-scene sections say so above the figures they keep.
  for (const char* section : {"## Real scenes: the target over photographs\n\n<!--m:real.not_measured-->",
                              "## The webcam set: occluders, glare, dim light and a wide lens\n\n"
                              "<!--m:webcam.not_measured-->"})
    EXPECT_NE(md.find(std::string(section) + "\n\nNot measured in this run: " + empty.string() + ": no photographs"),
              std::string::npos)
        << section;
  EXPECT_EQ(studies("accuracy --scene virtual --stills 3").exit_code, 2);
  EXPECT_EQ(studies("accuracy --scene real --frames 3").exit_code, 2);
  EXPECT_EQ(studies("accuracy --scene photo").exit_code, 2);
  EXPECT_EQ(studies("accuracy --video-frames 10").exit_code, 2);
}

}  // namespace
}  // namespace imagepro
