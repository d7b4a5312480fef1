#pragma once
// Scratch folders for the tests: each test names its own, under the build's test-tmp
// (IMAGEPRO_TEST_TMP), so tests that ctest runs in parallel never share files.
#include <filesystem>
#include <string>

namespace imagepro::test {

// An empty folder IMAGEPRO_TEST_TMP/name, made anew (what an earlier run left is removed).
inline std::filesystem::path freshDir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(IMAGEPRO_TEST_TMP) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace imagepro::test
