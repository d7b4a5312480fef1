#include "core/common/data_directory.h"

#include <system_error>

namespace imagepro {
namespace {

// The file whose presence marks a data folder.
constexpr const char* kMarker = "settings.json";

bool holdsData(const std::filesystem::path& dir) {
  std::error_code ec;
  return std::filesystem::is_regular_file(dir / kMarker, ec);
}

}  // namespace

std::filesystem::path executablePath() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : self;
}

std::filesystem::path dataDirectoryFor(const std::filesystem::path& executable) {
  // IMAGEPRO_DATA_FROM_BINDIR: bin -> share/imagepro as GNUInstallDirs lays them out
  // (src/core/common/CMakeLists.txt); IMAGEPRO_BUILD_DATA_DIR: the sources' data/.
  if (!executable.empty()) {
    const std::filesystem::path installed =
        (executable.parent_path() / IMAGEPRO_DATA_FROM_BINDIR).lexically_normal();
    if (holdsData(installed)) return installed;
  }
  const std::filesystem::path built(IMAGEPRO_BUILD_DATA_DIR);
  if (holdsData(built)) return built;
  return {};
}

std::filesystem::path dataDirectory() { return dataDirectoryFor(executablePath()); }

}  // namespace imagepro
