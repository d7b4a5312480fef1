#include "core/common/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

namespace imagepro {

namespace fs = std::filesystem;

namespace {
std::string reason() { return std::strerror(errno); }

// Follows `path` through symbolic links (relative ones against their own folder) to
// the file that is really written. A dangling link resolves to where its target
// would be, so the write creates it. False on a loop.
bool resolveLinks(const fs::path& path, fs::path& out, std::string& error) {
  fs::path p = path;
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(p, ec))) {
      out = p;
      return true;
    }
    const fs::path link = fs::read_symlink(p, ec);
    if (ec) {
      error = "cannot read the link " + p.string() + ": " + ec.message();
      return false;
    }
    p = link.is_absolute() ? link : p.parent_path() / link;
  }
  error = "cannot write " + path.string() + ": too many levels of symbolic links";
  return false;
}

// The process that wrote a temporary file is gone: its write was killed part-way.
bool writerIsGone(long pid) { return pid != ::getpid() && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH; }

// Removes ".<name>.tmp-<pid>-XXXXXX" files of `name` in `dir` whose writer is gone.
void removeStaleTemporaries(const fs::path& dir, const std::string& name) {
  const std::string head = "." + name + ".tmp-";
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string f = it->path().filename().string();
    if (f.size() <= head.size() || f.compare(0, head.size(), head) != 0) continue;
    char* after = nullptr;
    const long pid = std::strtol(f.c_str() + head.size(), &after, 10);
    if (pid <= 0 || !after || *after != '-' || std::strlen(after + 1) != 6) continue;
    if (writerIsGone(pid)) {
      std::error_code ignored;
      fs::remove(it->path(), ignored);
    }
  }
}

// Creates a new temporary file beside the target with mode 0666 (less the umask, as
// any new file); `name` receives its path. -1 with errno on failure.
int createTemporary(const fs::path& dir, const std::string& file_name, std::string& name) {
  static thread_local std::mt19937_64 rng{std::random_device{}()};
  static constexpr char kChars[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  const std::string prefix = (dir / atomicTemporaryPrefix(file_name, ::getpid())).string();
  for (int attempt = 0; attempt < 100; ++attempt) {
    name = prefix;
    for (int i = 0; i < 6; ++i) name += kChars[rng() % (sizeof(kChars) - 1)];
    const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  return -1;
}

// Flushes a folder's entries (the rename) to disk. File systems that cannot sync a
// folder say EINVAL; there is nothing more to do on them.
bool syncFolder(const fs::path& dir, std::string& why) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) {
    why = reason();
    return false;
  }
  const bool ok = ::fsync(fd) == 0 || errno == EINVAL;
  if (!ok) why = reason();
  ::close(fd);
  return ok;
}

// Keeps the file about to be replaced as `backup`, which is itself replaced atomically:
// a hard link to the old file under a temporary name is renamed over the backup, so a
// kill leaves the former backup or the new one, whole (a copy killed half-way left half
// a file). Where no link can be made (another file system, FAT) the old file is copied
// to the temporary name instead.
bool keepBackup(const fs::path& target, const fs::path& backup, std::string& why) {
  const fs::path dir = backup.has_parent_path() ? backup.parent_path() : fs::path(".");
  const std::string name = backup.filename().string();
  removeStaleTemporaries(dir, name);
  std::string tmp;
  const int fd = createTemporary(dir, name, tmp);
  if (fd < 0) {
    why = reason();
    return false;
  }
  ::close(fd);
  ::unlink(tmp.c_str());  // the name is reserved by our pid and random part; link() needs it free
  if (::link(target.c_str(), tmp.c_str()) != 0) {
    std::error_code ec;
    fs::copy_file(target, tmp, fs::copy_options::overwrite_existing, ec);
    if (ec) {
      why = ec.message();
      ::unlink(tmp.c_str());
      return false;
    }
  }
  const bool renamed = std::rename(tmp.c_str(), backup.c_str()) == 0;
  if (!renamed) why = reason();
  // rename() leaves both names when they are links to one file (a write killed after
  // its backup leaves the backup and the file the same file): the temporary goes.
  ::unlink(tmp.c_str());
  return renamed;
}
}  // namespace

std::string atomicTemporaryPrefix(const std::string& file_name, long pid) {
  return "." + file_name + ".tmp-" + std::to_string(pid) + "-";
}

bool writeFileAtomically(const std::string& path, std::string_view content, std::string& error,
                         bool keep_backup) {
  fs::path target;
  if (!resolveLinks(fs::path(path), target, error)) return false;
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string file_name = target.filename().string();
  removeStaleTemporaries(dir, file_name);

  std::string tmp;
  const int fd = createTemporary(dir, file_name, tmp);
  if (fd < 0) {
    error = "cannot create a temporary file beside " + path + ": " + reason();
    return false;
  }
  auto fail = [&](const std::string& message) {
    error = message;
    ::unlink(tmp.c_str());
    return false;
  };
  // The replaced file keeps its permissions (a script stays executable, a private file private).
  struct stat old {};
  if (::stat(target.c_str(), &old) == 0 && S_ISREG(old.st_mode) && ::fchmod(fd, old.st_mode & 07777) != 0) {
    const std::string why = reason();
    ::close(fd);
    return fail("cannot give the new " + path + " the old file's permissions: " + why);
  }
  const char* p = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string why = reason();
      ::close(fd);
      return fail("cannot write " + path + ": " + why);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const std::string why = reason();
    ::close(fd);
    return fail("cannot flush " + path + ": " + why);
  }
  if (::close(fd) != 0) return fail("cannot flush " + path + ": " + reason());
  std::error_code ec;
  if (keep_backup && fs::exists(target, ec)) {
    std::string why;
    if (!keepBackup(target, fs::path(path + ".bak"), why)) return fail("cannot keep a backup of " + path + ": " + why);
  }
  if (std::rename(tmp.c_str(), target.c_str()) != 0) return fail("cannot replace " + path + ": " + reason());
  std::string why;
  if (!syncFolder(dir, why)) {
    error = path + " was replaced, but its folder could not be flushed to disk: " + why;
    return false;
  }
  return true;
}

bool readWholeFile(const std::string& path, std::string& content, std::string& error) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    error = path + ": no such file";
    return false;
  }
  if (std::filesystem::is_directory(path, ec)) {
    error = path + ": is a folder, not a file";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = path + ": cannot open: " + reason();
    return false;
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) {
    error = path + ": read error";
    return false;
  }
  content = ss.str();
  return true;
}

}  // namespace imagepro
