// imagepro-cli calibrate and pattern as a user runs them: the pattern's views rendered by
// `render --pattern` through the thesis camera's lens, calibrated in text and JSON, with
// bad images among them, the exit codes, the atomic write with its backup; the printable
// pattern in each format and paper size, and its bad arguments.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <utility>
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
using test::readText;
using test::writeText;
using json = nlohmann::json;

// The thesis camera's lens (thesis 4.6), as the renderer's settings.
constexpr double kK1 = -2.05e-7, kK2 = -1.21e-13, kP1 = 3.39e-6, kP2 = 2.56e-6;

std::string lensJson(const std::string& extra = "") {
  char camera[256];
  std::snprintf(camera, sizeof camera, R"("camera": {"distortion": {"k1": %g, "k2": %g, "p1": %g, "p2": %g}})", kK1,
                kK2, kP1, kP2);
  return "{" + std::string(camera) + extra + "}";
}

// The four views of thesis 4.6 (+-45 deg about x and y, the target on the optical axis),
// grey, blurred and noisy, rendered through `config`'s lens; returns their paths.
std::vector<std::string> renderViews(const fs::path& dir, const fs::path& config, double distance_mm) {
  const double angles[4][2] = {{45, 0}, {-45, 0}, {0, 45}, {0, -45}};
  std::vector<std::string> paths;
  for (int i = 0; i < 4; ++i) {
    char args[512];
    std::snprintf(args, sizeof args,
                  "render --config %s --out %s --pattern --mode grey --noise 3 --blur 0.8 --seed %d "
                  "--pose %g,%g,0,0,0,%g --name view%d",
                  config.c_str(), dir.c_str(), i + 1, angles[i][0], angles[i][1], distance_mm, i);
    const CliRun r = cli(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    paths.push_back((dir / ("view" + std::to_string(i) + ".png")).string());
  }
  return paths;
}

std::string joined(const std::vector<std::string>& paths) {
  std::string out;
  for (const std::string& p : paths) out += p + " ";
  return out;
}

// An 8-bit binary PGM of one grey level.
void writeFlatPgm(const fs::path& path, int width, int height, unsigned char level) {
  writeText(path, "P5\n" + std::to_string(width) + " " + std::to_string(height) + "\n255\n" +
                      std::string(static_cast<size_t>(width) * height, static_cast<char>(level)));
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

class CliCalibrate : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = freshDir("cli_calibrate_" + name);
    writeText(dir_ / "lens.json", lensJson());
    views_ = renderViews(dir_, dir_ / "lens.json", 800.0);
  }
  fs::path dir_;
  std::vector<std::string> views_;
};

TEST_F(CliCalibrate, TextShowsEveryIterationAndTheFinalResidual) {
  const fs::path out = dir_ / "camera.json";
  const CliRun r = cli("calibrate " + joined(views_) + "--out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int iterationRows = 0, iterations = 0;
  double residual = -1.0;
  bool wrote = false;
  int imagesReported = 0;
  for (const std::string& line : lines(r.out)) {
    int n = 0;
    double k1 = 0, k2 = 0, p1 = 0, p2 = 0;
    if (std::sscanf(line.c_str(), "iteration %d: k1 %lf k2 %lf p1 %lf p2 %lf", &n, &k1, &k2, &p1, &p2) == 5) {
      EXPECT_EQ(n, ++iterationRows);
      EXPECT_NE(line.find("residual"), std::string::npos);
      EXPECT_NE(line.find("in 4 image(s)"), std::string::npos) << line;
    }
    std::sscanf(line.c_str(), "converged in %d iterations; RMS residual %lf px", &iterations, &residual);
    if (line == "wrote " + out.string()) wrote = true;
    for (const std::string& v : views_)
      if (line.rfind(v + ": ", 0) == 0 && line.find("spots matched") != std::string::npos) ++imagesReported;
  }
  EXPECT_GE(iterationRows, 2);
  EXPECT_LE(iterationRows, 5);
  EXPECT_EQ(iterations, iterationRows);
  EXPECT_GT(residual, 0.0);
  EXPECT_LT(residual, 0.1);
  EXPECT_TRUE(wrote);
  EXPECT_EQ(imagesReported, 4);

  // The file is the settings' cameras section with the File source's (the images') alone,
  // with the distortion found.
  const json file = json::parse(readText(out));
  ASSERT_EQ(file.size(), 1u);
  ASSERT_EQ(file.at("cameras").size(), 1u);
  const json& d = file.at("cameras").at("file").at("distortion");
  EXPECT_NEAR(d.at("k1").get<double>(), kK1, 0.01 * std::abs(kK1));
  EXPECT_NEAR(d.at("k2").get<double>(), kK2, 0.05 * std::abs(kK2));
  EXPECT_NEAR(d.at("p1").get<double>(), kP1, 0.02 * std::abs(kP1));
  EXPECT_NEAR(d.at("p2").get<double>(), kP2, 0.02 * std::abs(kP2));
  EXPECT_EQ(file.at("cameras").at("file").at("width").get<int>(), 640);
  // It is a settings file: --config takes it.
  EXPECT_EQ(cli("settings --config " + out.string()).exit_code, 0);
}

TEST_F(CliCalibrate, JsonIsOneObjectWithTheParameters) {
  const CliRun r = cli("calibrate " + joined(views_) + "--format json --out " + (dir_ / "camera.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(lines(r.out).size(), 1u) << r.out;
  const json j = json::parse(r.out);
  for (const char* key : {"status", "k1", "k2", "p1", "p2", "iterations", "rms_residual_px"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j.at("status"), "ok");
  EXPECT_NEAR(j.at("k1").get<double>(), kK1, 0.01 * std::abs(kK1));
  EXPECT_NEAR(j.at("k2").get<double>(), kK2, 0.05 * std::abs(kK2));
  EXPECT_NEAR(j.at("p1").get<double>(), kP1, 0.02 * std::abs(kP1));
  EXPECT_NEAR(j.at("p2").get<double>(), kP2, 0.02 * std::abs(kP2));
  EXPECT_GE(j.at("iterations").get<int>(), 2);
  EXPECT_LE(j.at("iterations").get<int>(), 5);
  EXPECT_GT(j.at("rms_residual_px").get<double>(), 0.0);
  EXPECT_LT(j.at("rms_residual_px").get<double>(), 0.1);
  EXPECT_GE(j.at("coverage_radius_fraction").get<double>(), 0.6);
  // The same parameters as the file written.
  const json file = json::parse(readText(dir_ / "camera.json"));
  EXPECT_EQ(file.at("cameras").at("file").at("distortion").at("k1").get<double>(), j.at("k1").get<double>());
}

TEST_F(CliCalibrate, BadImagesAreReportedOnceAndSkipped) {
  const fs::path garbage = dir_ / "garbage.png", small = dir_ / "small.pgm", blank = dir_ / "blank.pgm";
  writeText(garbage, "not an image");
  writeFlatPgm(small, 320, 240, 128);
  writeFlatPgm(blank, 640, 480, 230);  // the right size, nothing on it
  const std::string missing = (dir_ / "missing.png").string();
  // At most four images a run: the two good views (+-45 deg about x) with two bad ones.
  for (const auto& bad : {std::pair{missing, garbage.string()}, std::pair{small.string(), blank.string()}}) {
    const std::string images = views_[0] + " " + bad.first + " " + views_[1] + " " + bad.second;
    const CliRun r = cli("calibrate " + images + " --out " + (dir_ / "camera.json").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string all = r.out + r.err;
    for (const std::string& path : {bad.first, bad.second}) {
      EXPECT_EQ(count(all, path), 1u) << path << "\n" << all;
      bool skipped = false;
      for (const std::string& line : lines(all))
        skipped = skipped || (line.find(path) != std::string::npos && line.find("(skipped)") != std::string::npos);
      EXPECT_TRUE(skipped) << path;
    }
    EXPECT_EQ(all.find("InvalidSettings"), std::string::npos);
    EXPECT_NE(r.out.find("in 2 image(s)"), std::string::npos) << r.out;
    EXPECT_TRUE(fs::exists(dir_ / "camera.json"));
    if (bad.first == small.string()) {
      EXPECT_NE(r.err.find(small.string() + ": 320x240, but the settings' camera is 640x480 (skipped)"),
                std::string::npos)
          << r.err;
      EXPECT_NE(r.out.find(blank.string() + ": ThresholdUndefined"), std::string::npos) << r.out;
    }
  }
}

TEST_F(CliCalibrate, ExitCodes) {
  const std::string out = " --out " + (dir_ / "camera.json").string();
  // Usage errors: 2, one line.
  for (const std::string& args :
       {std::string("calibrate"), "calibrate" + out, "calibrate " + views_[0], "calibrate " + views_[0] + " --format xml" + out,
        "calibrate " + joined(views_) + views_[0] + out, "calibrate " + views_[0] + " --bogus 1" + out}) {
    const CliRun r = cli(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_EQ(lines(r.err).size(), 1u) << args << "\n" << r.err;
  }
  EXPECT_NE(cli("calibrate " + joined(views_) + views_[0] + out).err.find("at most four"), std::string::npos);
  // Input errors: 1, named.
  CliRun r = cli("calibrate " + (dir_ / "missing.png").string() + out);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("none of the images can be used"), std::string::npos) << r.err;
  writeFlatPgm(dir_ / "blank.pgm", 640, 480, 230);
  r = cli("calibrate " + (dir_ / "blank.pgm").string() + out);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("calibration failed: ThresholdUndefined"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "camera.json"));
  // One good view is enough (one to four images).
  r = cli("calibrate " + views_[2] + out);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  // A folder that does not exist cannot be written.
  r = cli("calibrate " + joined(views_) + "--out " + (dir_ / "no" / "camera.json").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find((dir_ / "no" / "camera.json").string()), std::string::npos) << r.err;
}

// Folders and list files stand for their images as in every other command, and a
// corrupt or cut-off PNG among them is one line of ours, never the decoder's own.
TEST_F(CliCalibrate, FoldersAndListsExpandAndDecodersStayQuiet) {
  const fs::path views = dir_ / "views";
  fs::create_directories(views);
  fs::copy_file(views_[0], views / "a.png");
  fs::copy_file(views_[1], views / "b.png");
  const std::string png = readText(views_[2]);
  writeText(views / "c.png", png.substr(0, png.size() / 2));  // cut off half-way
  writeText(dir_ / "list.txt", "views/a.png\n# the other view\n" + views_[1] + "\n");
  const std::string out = " --out " + (dir_ / "camera.json").string();

  CliRun r = cli("calibrate " + views.string() + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("calibrating from 2 image(s)"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find((views / "c.png").string() + ": the file ends before its image does"), std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("libpng"), std::string::npos) << r.err;
  EXPECT_EQ(lines(r.err).size(), 1u) << r.err;

  r = cli("calibrate " + (dir_ / "list.txt").string() + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("calibrating from 2 image(s)"), std::string::npos) << r.out;

  // Four at most, counted after the folders are expanded.
  r = cli("calibrate " + views.string() + " " + (dir_ / "list.txt").string() + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("at most four images"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("5 given"), std::string::npos) << r.err;
}

// An A4-sized sheet (11 x 7 spacings, as `pattern --paper A4` prints it) at 800 mm: its
// spots stay in the middle of the image and the calibration must not pass.
TEST_F(CliCalibrate, APatternTooSmallInTheImageIsPoorCoverage) {
  writeText(dir_ / "a4.json", lensJson(R"(, "pattern": {"columns": 11, "rows": 7})"));
  const fs::path a4 = dir_ / "a4";
  fs::create_directories(a4);
  const std::vector<std::string> far = renderViews(a4, dir_ / "a4.json", 800.0);
  const fs::path out = dir_ / "camera.json";
  writeText(out, "previous\n");
  CliRun r = cli("calibrate " + joined(far) + "--config " + (dir_ / "a4.json").string() + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("calibration failed: PoorCoverage"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("move the pattern closer or print it larger"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("coverage: the matched spots reach"), std::string::npos) << r.out;
  EXPECT_EQ(readText(out), "previous\n");  // nothing written, no backup made
  EXPECT_FALSE(fs::exists(out.string() + ".bak"));
  r = cli("calibrate " + joined(far) + "--format json --config " + (dir_ / "a4.json").string() + " --out " +
          out.string());
  EXPECT_EQ(r.exit_code, 1);
  const json j = json::parse(r.out);
  EXPECT_EQ(j.at("status"), "PoorCoverage");
  EXPECT_LT(j.at("coverage_radius_fraction").get<double>(), 0.6);
  // The same sheet at 400 mm covers enough.
  const fs::path near = dir_ / "near";
  fs::create_directories(near);
  r = cli("calibrate " + joined(renderViews(near, dir_ / "a4.json", 400.0)) + "--config " +
          (dir_ / "a4.json").string() + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST_F(CliCalibrate, WritesAtomicallyAndKeepsTheFormerFile) {
  const fs::path out = dir_ / "camera.json";
  writeText(out, "the former calibration\n");
  const std::set<fs::path> before{fs::directory_iterator(dir_), fs::directory_iterator()};
  const CliRun r = cli("calibrate " + joined(views_) + "--out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(readText(out.string() + ".bak"), "the former calibration\n");
  EXPECT_NO_THROW(json::parse(readText(out)));
  // Only the backup is new: no temporary file is left behind.
  std::set<fs::path> after{fs::directory_iterator(dir_), fs::directory_iterator()};
  after.erase(out.string() + ".bak");
  EXPECT_EQ(after, before);
  // Again: the backup is now the first calibration.
  const std::string first = readText(out);
  ASSERT_EQ(cli("calibrate " + joined(views_) + "--out " + out.string()).exit_code, 0);
  EXPECT_EQ(readText(out.string() + ".bak"), first);
}

std::string fileStart(const fs::path& path, size_t n) { return readText(path).substr(0, n); }

// Width and height from a PNG's IHDR chunk.
std::pair<std::uint32_t, std::uint32_t> pngSize(const fs::path& path) {
  const std::string s = readText(path);
  auto be32 = [&](size_t at) {
    return (std::uint32_t(std::uint8_t(s[at])) << 24) | (std::uint32_t(std::uint8_t(s[at + 1])) << 16) |
           (std::uint32_t(std::uint8_t(s[at + 2])) << 8) | std::uint32_t(std::uint8_t(s[at + 3]));
  };
  return s.size() >= 24 ? std::pair{be32(16), be32(20)} : std::pair{0u, 0u};
}

TEST(CliPattern, EachFormatAndPaper) {
  const fs::path dir = freshDir("cli_pattern_formats");
  struct Paper {
    const char* name;
    double width_mm, height_mm;
    const char* grid;  // spots 25 mm apart centred on the card, inside 10 mm margins, above the text
  };
  for (const Paper& paper : {Paper{"A4", 297, 210, "11 x 7 grid spots"}, Paper{"A3", 420, 297, "15 x 11 grid spots"}}) {
    for (const char* ext : {"pdf", "svg", "png"}) {
      const fs::path out = dir / (std::string(paper.name) + "." + ext);
      const CliRun r = cli("pattern --out " + out.string() + " --paper " + paper.name +
                           (std::string(ext) == "png" ? " --dpi 100" : ""));
      ASSERT_EQ(r.exit_code, 0) << r.err;
      EXPECT_NE(r.out.find(std::string(paper.name) + " landscape, " + paper.grid), std::string::npos) << r.out;
      EXPECT_NE(r.out.find("print it at actual size"), std::string::npos);
      if (std::string(ext) == "pdf") {
        EXPECT_EQ(fileStart(out, 8), "%PDF-1.4");
        char box[64];  // the page in points, 72 per inch
        std::snprintf(box, sizeof box, "/MediaBox [0 0 %.4f %.4f]", paper.width_mm * 72 / 25.4,
                      paper.height_mm * 72 / 25.4);
        EXPECT_NE(readText(out).find(box), std::string::npos) << box;
      } else if (std::string(ext) == "svg") {
        char size[64];
        std::snprintf(size, sizeof size, "width=\"%gmm\" height=\"%gmm\"", paper.width_mm, paper.height_mm);
        EXPECT_NE(readText(out).find(size), std::string::npos) << size;
      } else {
        EXPECT_EQ(fileStart(out, 8), "\x89PNG\r\n\x1a\n");
        const auto [w, h] = pngSize(out);
        EXPECT_EQ(w, static_cast<std::uint32_t>(std::lround(paper.width_mm / 25.4 * 100)));
        EXPECT_EQ(h, static_cast<std::uint32_t>(std::lround(paper.height_mm / 25.4 * 100)));
      }
    }
  }
  // A4 is the default paper.
  ASSERT_EQ(cli("pattern --out " + (dir / "default.svg").string()).exit_code, 0);
  EXPECT_EQ(readText(dir / "default.svg"), readText(dir / "A4.svg"));
}

TEST(CliPattern, BadArguments) {
  const fs::path dir = freshDir("cli_pattern_bad");
  const std::string svg = (dir / "p.svg").string(), png = (dir / "p.png").string();
  for (const std::string& args :
       {std::string("pattern"), "pattern --out " + (dir / "p.jpg").string(), "pattern --out " + svg + " --paper A5",
        "pattern --out " + svg + " --dpi 300", "pattern --out " + png + " --dpi 10", "pattern --out " + png + " --dpi 5000",
        "pattern --out " + svg + " extra", "pattern --out " + svg + " --bogus 1"}) {
    const CliRun r = cli(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_EQ(lines(r.err).size(), 1u) << args << "\n" << r.err;
  }
  EXPECT_FALSE(fs::exists(svg));
  EXPECT_FALSE(fs::exists(png));
  const CliRun r = cli("pattern --out " + (dir / "no" / "p.svg").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
}

// A set of targets at true scale: the whole set on one page, or one member alone; each
// card carries its id and offset; a set that does not fit, or an id that is none, is refused.
TEST(CliPattern, TheTargetsOfASetWithTheirIds) {
  const fs::path dir = freshDir("cli_pattern_targets");
  const fs::path config = dir / "set.json";
  std::ofstream(config) << R"({"targets": [{"id": 1, "name": "arm", "spot_offset_mm": 20},
                                           {"id": 2, "spot_offset_mm": 30}]})";
  const fs::path both = dir / "both.svg", one = dir / "one.svg";
  CliRun r = cli("pattern --config " + config.string() + " --targets --out " + both.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string svg = readText(both);
  EXPECT_NE(svg.find("id 1 arm: offset spot 20 mm (0.4 R)"), std::string::npos);
  EXPECT_NE(svg.find("id 2: offset spot 30 mm (0.6 R)"), std::string::npos);
  EXPECT_NE(svg.find("r=\"50\" fill=\"#ffffff\""), std::string::npos) << "the disk at true scale";
  EXPECT_NE(svg.find("width=\"130\" height=\"130\""), std::string::npos) << "the card of today's target";
  r = cli("pattern --config " + config.string() + " --target 2 --out " + one.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(readText(one).find("id 1"), std::string::npos);
  EXPECT_NE(readText(one).find("id 2"), std::string::npos);
  r = cli("pattern --config " + config.string() + " --target 7 --out " + one.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("7 is not the id"), std::string::npos) << r.err;
  std::ofstream(config) << R"({"targets": [{"id": 1, "spot_offset_mm": 12, "spot_radius_mm": 4},
                                           {"id": 2, "spot_offset_mm": 21, "spot_radius_mm": 4},
                                           {"id": 3, "spot_offset_mm": 30, "spot_radius_mm": 4},
                                           {"id": 4, "spot_offset_mm": 39, "spot_radius_mm": 4}]})";
  r = cli("pattern --config " + config.string() + " --targets --out " + (dir / "four.svg").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("4 cards of 130 mm do not fit on a A4 page (2 do)"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace imagepro
