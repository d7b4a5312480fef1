#include "core/common/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include "support/file_size_limit.h"
#include "support/test_dirs.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;

using test::freshDir;

TEST(AtomicFile, WritesAndReplaces) {
  const fs::path dir = freshDir("atomic_write");
  const std::string path = (dir / "a.json").string();
  std::string err, back;
  ASSERT_TRUE(writeFileAtomically(path, "first", err)) << err;
  ASSERT_TRUE(writeFileAtomically(path, "second", err, /*keep_backup=*/true)) << err;
  ASSERT_TRUE(readWholeFile(path, back, err));
  EXPECT_EQ(back, "second");
  ASSERT_TRUE(readWholeFile(path + ".bak", back, err));
  EXPECT_EQ(back, "first");
  // No temporary files left behind.
  int count = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++count;
  EXPECT_EQ(count, 2);
}

TEST(AtomicFile, FailedWriteKeepsOldFile) {
  const fs::path dir = freshDir("atomic_fail");
  std::string err;
  // Writing into a folder that does not exist fails and names the file.
  EXPECT_FALSE(writeFileAtomically((dir / "missing" / "x.json").string(), "x", err));
  EXPECT_NE(err.find("x.json"), std::string::npos);
}

// The disk fills up half-way through the new content: the save fails, names the file,
// and the old file is untouched, with no temporary file left beside it.
TEST(AtomicFile, WriteThatRunsOutOfSpaceKeepsTheOldFile) {
  const fs::path dir = freshDir("atomic_full");
  const std::string path = (dir / "settings.json").string();
  std::string err, back;
  ASSERT_TRUE(writeFileAtomically(path, "old content", err)) << err;
  const std::string big(64 * 1024, 'x');
  {
    test::FileSizeLimit limit(1024);
    ASSERT_TRUE(limit.active());
    EXPECT_FALSE(writeFileAtomically(path, big, err));
    EXPECT_FALSE(writeFileAtomically(path, big, err, /*keep_backup=*/true));
  }
  EXPECT_NE(err.find("settings.json"), std::string::npos) << err;
  ASSERT_TRUE(readWholeFile(path, back, err)) << err;
  EXPECT_EQ(back, "old content");
  int count = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++count;
  EXPECT_EQ(count, 1);
}

TEST(AtomicFile, ReadErrorsNameTheFile) {
  std::string content, err;
  EXPECT_FALSE(readWholeFile("/nonexistent/settings.json", content, err));
  EXPECT_NE(err.find("/nonexistent/settings.json"), std::string::npos);
  EXPECT_FALSE(readWholeFile(freshDir("atomic_dir").string(), content, err));
  EXPECT_NE(err.find("folder"), std::string::npos);
}

}  // namespace
}  // namespace imagepro
