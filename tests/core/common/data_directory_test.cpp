#include "core/common/data_directory.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/test_dirs.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;

TEST(DataDirectory, TheRunningProgramIsItself) { EXPECT_EQ(executablePath().filename(), "test_common"); }

TEST(DataDirectory, FromTheBuildTreeItIsTheSourcesDataFolder) {
  // Nothing is installed beside the test's executable: the build's own data/.
  const fs::path dir = dataDirectory();
  ASSERT_FALSE(dir.empty());
  EXPECT_TRUE(fs::equivalent(dir, IMAGEPRO_DATA_DIR));
  EXPECT_TRUE(fs::is_directory(dir / "samples"));
}

TEST(DataDirectory, InstalledItIsShareBesideBin) {
  // The layout `cmake --install` and the Debian package make (GNUInstallDirs' defaults).
  const fs::path prefix = test::freshDir("data_directory_installed") / "usr";
  fs::create_directories(prefix / "bin");
  fs::create_directories(prefix / "share/imagepro");
  std::ofstream(prefix / "share/imagepro/settings.json") << "{}\n";
  EXPECT_EQ(dataDirectoryFor(prefix / "bin/imagepro-cli"), prefix / "share/imagepro");
  // Found through the executable's folder, not the current one.
  EXPECT_EQ(dataDirectoryFor(prefix / "bin/../bin/imagepro"), prefix / "share/imagepro");
}

TEST(DataDirectory, AFolderWithoutTheSettingsIsNoDataFolder) {
  const fs::path prefix = test::freshDir("data_directory_empty");
  fs::create_directories(prefix / "bin");
  fs::create_directories(prefix / "share/imagepro/samples");
  const fs::path found = dataDirectoryFor(prefix / "bin/imagepro-cli");
  ASSERT_FALSE(found.empty());
  EXPECT_TRUE(fs::equivalent(found, IMAGEPRO_DATA_DIR));
  EXPECT_TRUE(fs::equivalent(dataDirectoryFor(fs::path()), IMAGEPRO_DATA_DIR));
}

}  // namespace
}  // namespace imagepro
