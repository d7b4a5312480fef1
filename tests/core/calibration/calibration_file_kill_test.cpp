// kill -9 during a calibration save: the calibration file and its backup are each,
// whole, one of the calibrations written, and a later save clears what the killed one
// left behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>

#include "core/calibration/calibration_file.h"
#include "core/common/atomic_file.h"
#include "support/kill_loop.h"
#include "support/test_dirs.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;

std::string contents(const fs::path& p) {
  std::string text, error;
  readWholeFile(p.string(), text, error);
  return text;
}

TEST(CalibrationFileKill, SaveKilledAnywhereLeavesTheOldOrTheNewFiles) {
  const fs::path dir = test::freshDir("calibration_kill");
  const fs::path path = dir / "camera.json";
  Settings a, b;
  a.camera().distortion.k1 = -0.2;
  b.camera().distortion.k1 = 0.1;
  b.camera().image_plane_distance_mm = 8.3;
  const std::set<std::string> written{calibrationFileJson(a), calibrationFileJson(b)};
  std::string error;
  ASSERT_TRUE(writeCalibrationFile(path.string(), a, error)) << error;
  ASSERT_TRUE(writeCalibrationFile(path.string(), b, error)) << error;

  const auto save = [&](long i) {
    std::string e;
    return writeCalibrationFile(path.string(), i % 2 ? a : b, e);
  };
  constexpr int kKills = 40;
  for (int k = 0; k < kKills; ++k) {
    ASSERT_TRUE(test::runThenKill(save, test::killDelay(k, kKills))) << "a save failed, kill " << k;
    const std::string now = contents(path), backup = contents(dir / "camera.json.bak");
    ASSERT_TRUE(written.count(now)) << "kill " << k << " left camera.json:\n" << now;
    ASSERT_TRUE(written.count(backup)) << "kill " << k << " left camera.json.bak:\n" << backup;
    Settings loaded;
    ASSERT_EQ(loadSettings(path.string(), loaded, error), Status::Ok) << error;
  }
  ASSERT_TRUE(writeCalibrationFile(path.string(), a, error)) << error;
  std::set<std::string> left;
  for (const auto& e : fs::directory_iterator(dir)) left.insert(e.path().filename().string());
  EXPECT_EQ(left, (std::set<std::string>{"camera.json", "camera.json.bak"}));
}

}  // namespace
}  // namespace imagepro
