#include "core/common/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace imagepro {

namespace {
std::string reason() { return std::strerror(errno); }
}  // namespace

bool writeFileAtomically(const std::string& path, std::string_view content, std::string& error,
                         bool keep_backup) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::string tmpl = (dir / ("." + target.filename().string() + ".XXXXXX")).string();
  const int fd = ::mkstemp(tmpl.data());
  if (fd < 0) {
    error = "cannot create a temporary file beside " + path + ": " + reason();
    return false;
  }
  const char* p = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      error = "cannot write " + path + ": " + reason();
      ::close(fd);
      ::unlink(tmpl.c_str());
      return false;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    error = "cannot flush " + path + ": " + reason();
    ::unlink(tmpl.c_str());
    return false;
  }
  std::error_code ec;
  if (keep_backup && fs::exists(target, ec)) {
    fs::copy_file(target, fs::path(path + ".bak"), fs::copy_options::overwrite_existing, ec);
    if (ec) {
      error = "cannot keep a backup of " + path + ": " + ec.message();
      ::unlink(tmpl.c_str());
      return false;
    }
  }
  // mkstemp creates 0600; give the file the usual permissions.
  ::chmod(tmpl.c_str(), 0644);
  if (std::rename(tmpl.c_str(), path.c_str()) != 0) {
    error = "cannot replace " + path + ": " + reason();
    ::unlink(tmpl.c_str());
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
