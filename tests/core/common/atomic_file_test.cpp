#include "core/common/atomic_file.h"

#include <dlfcn.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/file_size_limit.h"
#include "support/test_dirs.h"

// Records what every fsync of this process flushed (the path behind the descriptor)
// and what the written file held at that moment, then forwards to the C library:
// the tests below see whether the folder was flushed after the rename.
namespace {
std::vector<std::string> gSynced;
std::string gWatched;          // the file whose content is noted at each fsync
std::vector<std::string> gWatchedContent;
}  // namespace

extern "C" int fsync(int fd) {
  using Fn = int (*)(int);
  static const Fn real = reinterpret_cast<Fn>(dlsym(RTLD_NEXT, "fsync"));
  char link[64];
  std::snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  char buf[4096];
  const ssize_t n = readlink(link, buf, sizeof buf - 1);
  gSynced.push_back(n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : std::string());
  if (!gWatched.empty()) {
    std::ifstream in(gWatched);
    gWatchedContent.push_back(std::string(std::istreambuf_iterator<char>(in), {}));
  }
  return real(fd);
}

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

mode_t modeOf(const fs::path& p) {
  struct stat st {};
  EXPECT_EQ(::stat(p.c_str(), &st), 0) << p;
  return st.st_mode & 07777;
}

int countEntries(const fs::path& dir) {
  int count = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++count;
  return count;
}

// After the rename the folder itself is flushed, so the new name survives a power cut:
// the last fsync is of the folder, made when the file already holds the new content.
TEST(AtomicFile, FlushesTheFolderAfterTheRename) {
  const fs::path dir = fs::canonical(freshDir("atomic_dirsync"));
  const std::string path = (dir / "a.json").string();
  std::string err;
  ASSERT_TRUE(writeFileAtomically(path, "old", err)) << err;
  gSynced.clear();
  gWatchedContent.clear();
  gWatched = path;
  ASSERT_TRUE(writeFileAtomically(path, "new", err)) << err;
  gWatched.clear();
  ASSERT_EQ(gSynced.size(), 2u);                   // the temporary file, then the folder
  EXPECT_NE(gSynced[0].find(".a.json.tmp-"), std::string::npos) << gSynced[0];
  EXPECT_EQ(gSynced[1], dir.string());
  EXPECT_EQ(gWatchedContent[0], "old");           // the file is flushed before it replaces the old one
  EXPECT_EQ(gWatchedContent[1], "new");           // the folder after the rename
}

// The replaced file keeps its permission bits; a new file gets 0666 less the umask.
TEST(AtomicFile, KeepsTheOldFilesMode) {
  const fs::path dir = freshDir("atomic_mode");
  const fs::path priv = dir / "private.json", script = dir / "run.sh";
  std::string err;
  ASSERT_TRUE(writeFileAtomically(priv.string(), "a", err)) << err;
  ASSERT_TRUE(writeFileAtomically(script.string(), "a", err)) << err;
  ASSERT_EQ(::chmod(priv.c_str(), 0600), 0);
  ASSERT_EQ(::chmod(script.c_str(), 0750), 0);
  ASSERT_TRUE(writeFileAtomically(priv.string(), "b", err, /*keep_backup=*/true)) << err;
  ASSERT_TRUE(writeFileAtomically(script.string(), "b", err)) << err;
  EXPECT_EQ(modeOf(priv), 0600u);
  EXPECT_EQ(modeOf(script), 0750u);

  const mode_t old_mask = ::umask(027);
  ASSERT_TRUE(writeFileAtomically((dir / "new.json").string(), "c", err)) << err;
  ::umask(old_mask);
  EXPECT_EQ(modeOf(dir / "new.json"), 0640u);
}

// A path that is a symbolic link is written through: the link stays, its target gets
// the new content (also through a relative link, a chain of links and a dangling one).
TEST(AtomicFile, WritesThroughASymbolicLink) {
  const fs::path dir = freshDir("atomic_link");
  fs::create_directories(dir / "real");
  const fs::path real = dir / "real" / "settings.json";
  std::string err, back;
  ASSERT_TRUE(writeFileAtomically(real.string(), "old", err)) << err;
  ASSERT_EQ(::chmod(real.c_str(), 0640), 0);
  fs::create_symlink("real/settings.json", dir / "link.json");
  fs::create_symlink("link.json", dir / "link2.json");

  ASSERT_TRUE(writeFileAtomically((dir / "link2.json").string(), "new", err)) << err;
  EXPECT_TRUE(fs::is_symlink(dir / "link.json"));
  EXPECT_TRUE(fs::is_symlink(dir / "link2.json"));
  ASSERT_TRUE(readWholeFile(real.string(), back, err)) << err;
  EXPECT_EQ(back, "new");
  EXPECT_EQ(modeOf(real), 0640u);
  EXPECT_EQ(countEntries(dir / "real"), 1);  // no temporary file left beside the target

  fs::create_symlink("real/later.json", dir / "dangling.json");
  ASSERT_TRUE(writeFileAtomically((dir / "dangling.json").string(), "made", err)) << err;
  EXPECT_TRUE(fs::is_symlink(dir / "dangling.json"));
  ASSERT_TRUE(readWholeFile((dir / "real" / "later.json").string(), back, err)) << err;
  EXPECT_EQ(back, "made");

  fs::create_symlink("loop_b", dir / "loop_a");
  fs::create_symlink("loop_a", dir / "loop_b");
  EXPECT_FALSE(writeFileAtomically((dir / "loop_a").string(), "x", err));
  EXPECT_NE(err.find("symbolic links"), std::string::npos) << err;
  EXPECT_TRUE(fs::is_symlink(dir / "loop_a"));
}

// A write killed part-way leaves its temporary file; the next write of the same file
// removes it once its process is gone, and leaves alone those of a live writer and
// those of other files.
TEST(AtomicFile, RemovesStaleTemporaryFiles) {
  const fs::path dir = freshDir("atomic_stale");
  const std::string path = (dir / "data.json").string();
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) ::_exit(0);
  ASSERT_EQ(::waitpid(child, nullptr, 0), child);  // its pid now names no process

  auto touch = [&](const std::string& name) {
    std::ofstream(dir / name) << "partial";
    return dir / name;
  };
  const fs::path stale = touch(atomicTemporaryPrefix("data.json", child) + "aB3xY9");
  const fs::path live = touch(atomicTemporaryPrefix("data.json", 1) + "aB3xY9");  // init never exits
  const fs::path other = touch(atomicTemporaryPrefix("other.json", child) + "aB3xY9");
  const fs::path user = touch(".data.json.tmp-notes");  // not of our form: never touched
  std::string err;
  ASSERT_TRUE(writeFileAtomically(path, "x", err)) << err;
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(other));
  EXPECT_TRUE(fs::exists(user));
}

}  // namespace
}  // namespace imagepro
