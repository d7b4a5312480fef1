#include "core/calibration/calibration_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/common/atomic_file.h"

namespace imagepro {
namespace {

std::string scratch(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(IMAGEPRO_TEST_TMP) / "calibration_file";
  std::filesystem::create_directories(dir);
  const std::filesystem::path p = dir / name;
  std::filesystem::remove(p);
  std::filesystem::remove(p.string() + ".bak");
  return p.string();
}

// The File source's camera calibrated (images taken as files), in use.
Settings calibrated() {
  Settings s;
  s.source = SourceKind::File;
  s.camera().distortion = kThesisCameraDistortion;
  s.camera().principal_point_px = {321.25, 238.5};
  s.target.radius_mm = 40.0;  // not part of the file
  return s;
}

TEST(CalibrationFile, HoldsOnlyTheCameraAndReadsBackAsSettings) {
  const std::string text = calibrationFileJson(calibrated());
  EXPECT_EQ(text.rfind("{\n  \"cameras\": {\n    \"file\": {", 0), 0u) << text;  // the source in use's alone
  EXPECT_EQ(text.find("\"virtual\""), std::string::npos);
  EXPECT_EQ(text.find("\"target\""), std::string::npos);
  EXPECT_EQ(text.back(), '\n');

  const std::string path = scratch("camera.json");
  std::string error;
  ASSERT_TRUE(writeCalibrationFile(path, calibrated(), error)) << error;
  Settings loaded;
  ASSERT_EQ(loadSettings(path, loaded, error), Status::Ok) << error;
  const CameraModel& file = loaded.camera(SourceKind::File);
  EXPECT_EQ(file.distortion.k1, kThesisCameraDistortion.k1);
  EXPECT_EQ(file.distortion.k2, kThesisCameraDistortion.k2);
  EXPECT_EQ(file.distortion.p1, kThesisCameraDistortion.p1);
  EXPECT_EQ(file.distortion.p2, kThesisCameraDistortion.p2);
  EXPECT_EQ(file.principal_point_px[0], 321.25);
  // Bound to that source: the others keep what they had.
  EXPECT_EQ(loaded.camera(SourceKind::Camera).distortion.k1, 0.0);
  EXPECT_EQ(loaded.camera(SourceKind::Virtual).principal_point_px[0], CameraModel{}.principal_point_px[0]);
  EXPECT_EQ(loaded.target.radius_mm, Settings{}.target.radius_mm);  // missing keys: defaults
}

TEST(CalibrationFile, AnExistingFileIsKeptAsBackup) {
  const std::string path = scratch("again.json");
  std::string error;
  ASSERT_TRUE(writeFileAtomically(path, "old\n", error)) << error;
  ASSERT_TRUE(writeCalibrationFile(path, calibrated(), error)) << error;
  std::string backup;
  ASSERT_TRUE(readWholeFile(path + ".bak", backup, error)) << error;
  EXPECT_EQ(backup, "old\n");
}

TEST(CalibrationFile, AFailedWriteNamesTheFile) {
  const std::string path = scratch("missing-folder") + "/camera.json";
  std::string error;
  EXPECT_FALSE(writeCalibrationFile(path, calibrated(), error));
  EXPECT_NE(error.find("camera.json"), std::string::npos) << error;
}

}  // namespace
}  // namespace imagepro
