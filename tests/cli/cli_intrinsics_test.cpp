// calibrate --intrinsics, pattern's dot grids and settings' OpenCV camera files, run as a
// user would: rendered photographs of a printed asymmetric grid in, the camera section,
// OpenCV's file, the coverage map and the JSON contract out.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <string>

#include "core/calibration/intrinsic_scenes.h"
#include "core/calibration/opencv_camera_file.h"
#include "support/cli_run.h"
#include "support/test_dirs.h"

namespace imagepro {
namespace {

using test::cli;

TEST(CliIntrinsics, CalibratesAnAsymmetricGridAndWritesEveryFile) {
  const auto dir = test::freshDir("cli_intrinsics");
  DotGridSpec spec;
  spec.kind = DotGridKind::AsymmetricCircles;
  spec.columns = 4;
  spec.rows = 11;
  spec.spacing_mm = 15.0;
  const CameraModel truth = testing::intrinsicTruthCamera(testing::kWebcamLens);
  testing::RenderedGrid rendered;
  std::string error;
  testing::PhotoConditions light;
  light.gradient = 0.5;
  ASSERT_TRUE(testing::renderGridViews(spec, Paper::A4, truth, testing::intrinsicViews(420.0), light, rendered, error));
  std::string images;
  for (size_t i = 0; i < rendered.images.size(); ++i) {
    const auto path = dir / ("view" + std::to_string(i) + ".png");
    cv::imwrite(path.string(), rendered.images[i]);
    images += " " + path.string();
  }
  const auto out = dir / "camera.json", yaml = dir / "camera.yaml", png = dir / "coverage.png";
  test::writeText(out, "{\"camera\": {\"width\": 640}}\n");  // kept as .bak
  const test::CliRun r = cli("calibrate --intrinsics --pattern asymmetric-circles --columns 4 --rows 11 --spacing-mm 15" +
                             images + " --out " + out.string() + " --format json --export-opencv " + yaml.string() +
                             " --coverage " + png.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["status"], "ok");
  EXPECT_NEAR(j["fx_px"].get<double>(), truth.fu(), 0.002 * truth.fu());
  EXPECT_NEAR(j["cy_px"].get<double>(), truth.v0(), 1.0);
  EXPECT_NEAR(j["k1"].get<double>(), truth.distortion.k1, 0.05 * std::abs(truth.distortion.k1));
  EXPECT_EQ(j["opencv_dist"].size(), 5u);
  EXPECT_EQ(j["images_used"], 10);
  EXPECT_EQ(j["per_image"].size(), 10u);
  EXPECT_EQ(j["per_image"][0]["status"], "ok");
  EXPECT_LT(j["rms_px"].get<double>(), 0.05);
  EXPECT_GT(j["std_dev"]["fx_px"].get<double>(), 0.0);
  EXPECT_TRUE(std::filesystem::exists(out.string() + ".bak"));
  // The camera section, OpenCV's file and the coverage map.
  const auto settings = nlohmann::json::parse(test::readText(out));
  EXPECT_NEAR(settings["cameras"]["file"]["principal_point_px"][0].get<double>(), j["cx_px"].get<double>(), 1e-9);
  OpenCvCamera oc;
  ASSERT_TRUE(readOpenCvCamera(yaml.string(), oc, error)) << error;
  EXPECT_NEAR(oc.camera_matrix(0, 0), j["fx_px"].get<double>(), 1e-9);
  EXPECT_EQ(oc.width, 640);
  EXPECT_EQ(cv::imread(png.string()).cols, 640);

  // The exported file imported gives the same camera.
  const auto imported = dir / "imported.json";
  const test::CliRun s = cli("settings --import-opencv-camera " + yaml.string() + " --out " + imported.string());
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const auto& calibrated = settings["cameras"]["file"];
  const nlohmann::json importedSettings = nlohmann::json::parse(test::readText(imported));
  for (const auto& cam : importedSettings["cameras"]) {  // every source's
    EXPECT_NEAR(cam["image_plane_distance_mm"].get<double>(), calibrated["image_plane_distance_mm"].get<double>(), 1e-9);
    EXPECT_NEAR(cam["distortion"]["k1"].get<double>(), calibrated["distortion"]["k1"].get<double>(), 1e-15);
  }

  // Too few images, and a bad pattern description, are named.
  const test::CliRun few = cli("calibrate --intrinsics --pattern asymmetric-circles --columns 4 --rows 11 --spacing-mm 15 " +
                               (dir / "view0.png").string() + " --out " + (dir / "x.json").string());
  EXPECT_EQ(few.exit_code, 1);
  EXPECT_NE(few.err.find("TooFewViews"), std::string::npos) << few.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.json"));
  const test::CliRun bad = cli("calibrate --intrinsics --pattern symmetric-circles --columns 4 --rows 0 --spacing-mm 15 " +
                               (dir / "view0.png").string() + " --out " + (dir / "x.json").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("InvalidPattern"), std::string::npos) << bad.err;
  const test::CliRun negative = cli("calibrate --intrinsics --pattern symmetric-circles --columns 4 --rows 5 --spacing-mm -3 " +
                                    (dir / "view0.png").string() + " --out " + (dir / "x.json").string());
  EXPECT_EQ(negative.exit_code, 2);
}

TEST(CliIntrinsics, PatternWritesTheGridsAsPdf) {
  const auto dir = test::freshDir("cli_pattern_grids");
  for (const char* paper : {"A4", "Letter", "A3"}) {
    const auto pdf = dir / (std::string(paper) + ".pdf");
    const test::CliRun r = cli(std::string("pattern --pattern asymmetric-circles --columns 4 --rows 11 --spacing-mm 15 --paper ") +
                               paper + " --out " + pdf.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string text = test::readText(pdf);
    EXPECT_EQ(text.rfind("%PDF", 0), 0u);
    EXPECT_NE(text.find("--pattern asymmetric-circles --columns 4 --rows 11 --spacing-mm 15"), std::string::npos);
  }
  const test::CliRun big = cli("pattern --pattern symmetric-circles --columns 20 --rows 20 --spacing-mm 30 --out " +
                               (dir / "big.pdf").string());
  EXPECT_EQ(big.exit_code, 2);
  EXPECT_NE(big.err.find("page holds"), std::string::npos) << big.err;
  const test::CliRun thesis = cli("pattern --columns 13 --rows 9 --spacing-mm 20 --out " + (dir / "thesis.pdf").string());
  EXPECT_EQ(thesis.exit_code, 0) << thesis.err;
}

TEST(CliIntrinsics, ImportRejectsABrokenCameraFile) {
  const auto dir = test::freshDir("cli_import_camera");
  test::writeText(dir / "bad.yaml", "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\n");
  const test::CliRun r = cli("settings --import-opencv-camera " + (dir / "bad.yaml").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("camera_matrix"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace imagepro
