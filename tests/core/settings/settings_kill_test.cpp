// kill -9 during a settings save: the file is always the old settings or the new ones,
// whole, and a later save clears what the killed one left behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/common/atomic_file.h"
#include "core/settings/settings.h"
#include "support/kill_loop.h"
#include "support/test_dirs.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;

TEST(SettingsKill, SaveKilledAnywhereLeavesTheOldOrTheNewFile) {
  const fs::path dir = test::freshDir("settings_kill");
  const std::string path = (dir / "settings.json").string();
  Settings a, b;
  b.camera().width = 800;
  b.camera().height = 600;
  b.pipeline.tracking.data_points = 7;
  const std::string text_a = settingsToJson(a), text_b = settingsToJson(b);
  std::string error;
  ASSERT_EQ(saveSettings(path, a, error), Status::Ok) << error;
  const std::string saved_a = [&] {
    std::string t;
    readWholeFile(path, t, error);
    return t;
  }();
  ASSERT_EQ(saveSettings(path, b, error), Status::Ok) << error;
  std::string saved_b;
  ASSERT_TRUE(readWholeFile(path, saved_b, error)) << error;
  ASSERT_NE(saved_a, saved_b);

  const auto save = [&](long i) {
    std::string e;
    return saveSettings(path, i % 2 ? b : a, e) == Status::Ok;
  };
  constexpr int kKills = 40;
  for (int k = 0; k < kKills; ++k) {
    ASSERT_TRUE(test::runThenKill(save, test::killDelay(k, kKills))) << "a save failed, kill " << k;
    std::string now;
    ASSERT_TRUE(readWholeFile(path, now, error)) << error;
    ASSERT_TRUE(now == saved_a || now == saved_b) << "kill " << k << " left:\n" << now;
    Settings loaded;
    ASSERT_EQ(loadSettings(path, loaded, error), Status::Ok) << error;
    EXPECT_TRUE(settingsToJson(loaded) == text_a || settingsToJson(loaded) == text_b);
  }
  // The next save removes the temporary files of the killed ones.
  ASSERT_EQ(saveSettings(path, a, error), Status::Ok) << error;
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().filename(), "settings.json") << e.path();
}

}  // namespace
}  // namespace imagepro
