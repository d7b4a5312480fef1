// imagepro-cli bench on rendered frames, run as a user would: the virtual bench scene and
// the real scenes (the target over photographs), each timed full frame and tracked, in
// text and JSON; without photographs one line says so and the virtual kind stands alone.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "support/cli_run.h"
#include "support/photographs.h"
#include "support/test_dirs.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;
using test::cli;
using test::CliRun;
using test::freshDir;
using test::lines;

TEST(CliBench, BothKindsOfFramesFullFrameAndTracked) {
  if (const std::string why = test::missingPhotographs(); !why.empty()) GTEST_SKIP() << why;
  const CliRun text = cli("bench --frames 12");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  const std::size_t virtual_kind = text.out.find("== 640x480, virtual scene, 12 frames");
  const std::size_t real_kind = text.out.find("== 640x480, real scenes, 12 frames");
  ASSERT_NE(virtual_kind, std::string::npos) << text.out;
  ASSERT_NE(real_kind, std::string::npos) << text.out;
  EXPECT_LT(virtual_kind, real_kind);
  // Each kind has the engine's two rows; the summary has a row per kind.
  EXPECT_NE(text.out.find("ImagePro full frame", real_kind), std::string::npos);
  EXPECT_NE(text.out.find("ImagePro tracked", real_kind), std::string::npos);
  int summary_rows = 0;
  for (const std::string& line : lines(text.out.substr(text.out.find("summary, frames/s"))))
    summary_rows += line.find("640x480") != std::string::npos;
  EXPECT_EQ(summary_rows, 2) << text.out;
  EXPECT_EQ(text.out.find("left out"), std::string::npos);

  const CliRun json = cli("bench --frames 12 --format json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  for (const char* key : {"full_frame_hz", "tracked_hz", "real_full_frame_hz", "real_tracked_hz"})
    EXPECT_GT(j.at(key).get<double>(), 0.0) << key;
  const auto& res = j.at("resolutions").at(0);
  EXPECT_EQ(res.at("real_frames").get<int>(), 12);
  // The real-scene videos show a large, clear target in every frame.
  for (const char* key : {"real_full_frame_found", "real_tracked_found"}) {
    EXPECT_GE(res.at(key).get<int>(), 10) << key;
    EXPECT_LE(res.at(key).get<int>(), 12) << key;
  }
  EXPECT_GT(res.at("real_tracked_region_fraction").get<double>(), 0.0);
  EXPECT_LT(res.at("real_tracked_region_fraction").get<double>(), 1.0);
}

TEST(CliBench, WithoutPhotographsOneLineAndTheVirtualKindAlone) {
  const fs::path empty = freshDir("cli_bench_no_photos");
  const CliRun text = cli("bench --frames 10 --backgrounds " + empty.string());
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("== 640x480, virtual scene, 10 frames"), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find("real scenes,"), std::string::npos) << text.out;
  int said = 0;
  for (const std::string& line : lines(text.out))
    said += line.rfind("real scenes: left out, no photographs in " + empty.string(), 0) == 0;
  EXPECT_EQ(said, 1) << text.out;
  const CliRun json = cli("bench --frames 10 --format json --backgrounds " + empty.string());
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  EXPECT_GT(j.at("full_frame_hz").get<double>(), 0.0);
  EXPECT_FALSE(j.contains("real_full_frame_hz"));
  EXPECT_FALSE(j.at("resolutions").at(0).contains("real_frames"));
  EXPECT_NE(json.err.find("real scenes: left out"), std::string::npos) << json.err;

  // A build that counts no allocations (a sanitizer build) says so once and shows
  // "n/a" and null where the counts would be; any other build shows the counts.
  const bool counted = text.err.find("does not count heap allocations") == std::string::npos;
  for (const std::string& line : lines(text.out))
    if (line.rfind("ImagePro ", 0) == 0) {
      const std::string last = line.substr(line.find_last_of(' ') + 1);
      if (counted)
        EXPECT_NO_THROW(std::stod(last)) << line;
      else
        EXPECT_EQ(last, "n/a") << line;
    }
  for (const char* key : {"full_frame_allocations_per_frame", "tracked_allocations_per_frame"}) {
    const auto& v = j.at("resolutions").at(0).at(key);
    EXPECT_EQ(v.is_number(), counted) << key << ": " << v;
    EXPECT_EQ(v.is_null(), !counted) << key << ": " << v;
  }
}

}  // namespace
}  // namespace imagepro
