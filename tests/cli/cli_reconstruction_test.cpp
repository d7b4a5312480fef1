// imagepro-cli reconstruct (JSON output) and estimate-d0, run as a user would,
// their output checked against the renderer's exact poses.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "support/cli_run.h"
#include "core/common/atomic_file.h"
#include "support/test_dirs.h"
#include "support/udp_receiver.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;
using test::cli;
using test::CliRun;
using test::freshDir;
using test::lines;

// One CSV line split into fields, double-quoted fields unquoted ("" is a quote).
std::vector<std::string> csvFields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      fields.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

// The renderer's truth.csv: frame name -> Rx, Ry, Rz, Tx, Ty, Tz.
std::map<std::string, std::vector<double>> readTruth(const fs::path& file) {
  std::string text, e;
  EXPECT_TRUE(readWholeFile(file.string(), text, e)) << e;
  std::map<std::string, std::vector<double>> truth;
  const auto rows = lines(text);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto f = csvFields(rows[i]);
    if (f.size() < 8) continue;
    std::vector<double>& pose = truth[f[0]];
    for (int k = 2; k < 8; ++k) pose.push_back(std::stod(f[k]));
  }
  return truth;
}

// Shell quoting for a path that may hold quotes and backslashes.
std::string shellQuoted(const fs::path& p) {
  std::string s = "'";
  for (char c : p.string()) s += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return s + "'";
}

// A name with a double quote and a backslash is escaped (the JSON parses), each row's pose
// is the rendered one, and a readable frame without a target is a NoTarget row of a
// command that succeeds.
TEST(CliReconstruction, JsonEscapesNamesAndMatchesTheRenderedPoses) {
  const fs::path dir = freshDir("cli_reconstruction_json");
  const std::string odd = "we\"ird\\name";
  CliRun r = cli("render --out " + dir.string() + " --frames 1 --mode grey --pose 20,-15,30,10,-5,700 --name " +
                 shellQuoted(odd));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = cli("render --out " + dir.string() + " --frames 1 --mode grey --pose -10,25,-120,-30,20,950 --name plain --append");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The whole card outside the image, clutter in it: edges, but no target.
  r = cli("render --out " + dir.string() +
          " --frames 1 --mode grey --clutter 6 --pose 0,0,0,3000,0,1000 --name blank --append");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(dir / (odd + ".png")));
  const auto truth = readTruth(dir / "truth.csv");
  ASSERT_EQ(truth.count(odd + ".png"), 1u);

  r = cli("reconstruct --format json " + shellQuoted(dir / (odd + ".png")) + " " + shellQuoted(dir / "plain.png") + " " +
          shellQuoted(dir / "blank.png"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json rows;
  ASSERT_NO_THROW(rows = nlohmann::json::parse(r.out)) << r.out;
  ASSERT_TRUE(rows.is_array());
  ASSERT_EQ(rows.size(), 3u) << r.out;
  EXPECT_EQ(rows[0]["frame"], odd + ".png");
  EXPECT_EQ(rows[1]["frame"], "plain.png");
  EXPECT_EQ(rows[2]["frame"], "blank.png");
  for (int i = 0; i < 2; ++i) {
    const nlohmann::json& row = rows[i];
    ASSERT_EQ(row["status"], "ok") << row.dump();
    const std::vector<double>& t = truth.at(row["frame"].get<std::string>());
    const char* names[] = {"Rx_deg", "Ry_deg", "Rz_deg", "Tx_mm", "Ty_mm", "Tz_mm"};
    // Sub-pixel mode on a clean grey frame: a few hundredths of a degree, a few hundredths
    // of a per cent of the distance.
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(row[names[k]].get<double>(), t[k], 0.1) << names[k] << " " << row.dump();
    for (int k = 3; k < 6; ++k)
      EXPECT_NEAR(row[names[k]].get<double>(), t[k], 1e-3 * t[5]) << names[k] << " " << row.dump();
    // The self-check's measures of a clean frame: well inside its limits.
    EXPECT_LT(row["spot_error_px"].get<double>(), 0.2) << row.dump();
    EXPECT_LT(row["rim_error_px"].get<double>(), 0.2) << row.dump();
  }
  EXPECT_EQ(rows[2]["status"], "NoTarget") << rows[2].dump();
  EXPECT_FALSE(rows[2].contains("Tz_mm"));
  EXPECT_FALSE(rows[2].contains("rim_error_px"));

  // The same NoTarget row in CSV.
  r = cli("reconstruct " + shellQuoted(dir / "blank.png"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto csv = lines(r.out);
  ASSERT_EQ(csv.size(), 2u) << r.out;
  EXPECT_EQ(csv[1], "blank.png,NoTarget,,,,,,,,");  // every column of the header, rim_seen and target empty
}

// A frame of another size than the camera model's is a named error row, not a wrong pose.
TEST(CliReconstruction, FrameOfAnotherSizeIsANamedErrorRow) {
  const fs::path dir = freshDir("cli_reconstruction_size");
  CliRun r = cli("settings");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json small = nlohmann::json::parse(r.out);
  for (auto& camera : small["cameras"]) {  // rendered (Virtual) and read back (File) through it
    camera["width"] = 320;
    camera["height"] = 240;
    camera["principal_point_px"] = {159.5, 119.5};
    camera["image_plane_distance_mm"] = 4.0;
  }
  std::string e;
  ASSERT_TRUE(writeFileAtomically((dir / "small.json").string(), small.dump(2), e)) << e;
  r = cli("render --config " + (dir / "small.json").string() + " --out " + dir.string() +
          " --frames 1 --mode grey --pose 10,20,30,0,0,800 --name small");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = cli("reconstruct --format json --config " + (dir / "small.json").string() + " " + (dir / "small.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)[0]["status"], "ok") << r.out;
  r = cli("reconstruct --format json " + (dir / "small.png").string());  // the default 640x480 model
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)[0]["status"], "FrameSizeMismatch") << r.out;
}

// Frames rendered with a known image plane distance (12 mm, not the default 8): eq. 4.1
// from the thin-lens focal length of the target's depth leads back to it.
TEST(CliReconstruction, EstimateD0RecoversTheRenderedImagePlaneDistance) {
  const fs::path dir = freshDir("cli_reconstruction_d0");
  CliRun r = cli("settings");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json settings = nlohmann::json::parse(r.out);
  const double d0 = 12.0, depth = 900.0;
  for (auto& camera : settings["cameras"]) camera["image_plane_distance_mm"] = d0;
  const std::string config = (dir / "d0.json").string();
  std::string e;
  ASSERT_TRUE(writeFileAtomically(config, settings.dump(2), e)) << e;
  r = cli("render --config " + config + " --out " + dir.string() + " --frames 1 --mode grey --pose 15,-20,40,30,-20," +
          std::to_string(depth) + " --name a");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = cli("render --config " + config + " --out " + dir.string() + " --frames 1 --mode grey --pose -30,5,170,-60,40," +
          std::to_string(depth) + " --name b --append");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const double focal = d0 * depth / (d0 + depth);
  char f[32];
  std::snprintf(f, sizeof f, "%.9f", focal);
  // The estimate starts from the focal length, not from the settings' d0: the default 8 mm
  // model must give the same answer.
  r = cli("estimate-d0 --focal-length " + std::string(f) + " " + (dir / "a.png").string() + " " +
          (dir / "b.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 3u) << r.out;
  EXPECT_EQ(rows[0], "frame,status,d0_mm,depth_mm,iterations");
  for (int i = 1; i <= 2; ++i) {
    const auto fields = csvFields(rows[i]);
    ASSERT_EQ(fields.size(), 5u) << rows[i];
    EXPECT_EQ(fields[1], "ok") << rows[i];
    EXPECT_NEAR(std::stod(fields[2]), d0, 1e-3 * d0) << rows[i];
    EXPECT_NEAR(std::stod(fields[3]), depth, 1e-3 * depth) << rows[i];
    EXPECT_LE(std::stoi(fields[4]), 5) << rows[i];
  }
  const std::size_t said = r.err.find("d0 = ");
  ASSERT_NE(said, std::string::npos) << r.err;
  EXPECT_NEAR(std::stod(r.err.substr(said + 5)), d0, 1e-3 * d0) << r.err;
  // A frame without a target is a row with the error's name; with no estimate at all
  // the command has failed, and says why.
  r = cli("render --out " + dir.string() + " --frames 1 --mode grey --clutter 6 --pose 0,0,0,3000,0,1000 --name blank");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = cli("estimate-d0 --focal-length " + std::string(f) + " " + (dir / "blank.png").string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(lines(r.out).at(1), "blank.png,NoTarget,,,");
  EXPECT_NE(r.err.find("no frame gave an estimate of d0 (blank.png: NoTarget: "), std::string::npos) << r.err;
}

// --stream: a reader on the loopback address gets one datagram a frame, in order, with
// the values of the data-out file the same run wrote; the summary counts them.
TEST(CliReconstruct, StreamsEveryFrameToALoopbackReader) {
  test::UdpReceiver receiver;
  const int port = receiver.port();
  ASSERT_NE(port, 0);
  const fs::path dir = freshDir("cli_stream");
  const std::string csv = (dir / "run.csv").string();
  const CliRun r = cli("reconstruct --virtual --frames 25 --no-pace --data-out " + csv + " --stream udp://127.0.0.1:" +
                       std::to_string(port));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("stream udp://127.0.0.1:" + std::to_string(port) + " json: 25 sent, 0 dropped"), std::string::npos)
      << r.err;
  std::string text, e;
  ASSERT_TRUE(readWholeFile(csv, text, e)) << e;
  const auto rows = lines(text);
  ASSERT_EQ(rows.size(), 26u);
  const auto datagrams = receiver.drain();  // the run has ended: all are waiting
  ASSERT_EQ(datagrams.size(), 25u);
  for (int i = 0; i < 25; ++i) {
    const auto j = nlohmann::json::parse(datagrams[static_cast<std::size_t>(i)]);
    const auto fields = csvFields(rows[static_cast<std::size_t>(i) + 1]);
    EXPECT_EQ(j["frame"], i);
    EXPECT_EQ(std::to_string(j["frame"].get<int>()), fields[0]);
    EXPECT_EQ(j["status"], fields[1]);
    ASSERT_TRUE(j["Tz_mm"].is_number()) << fields[1];
    EXPECT_NEAR(j["Tz_mm"].get<double>(), std::stod(fields[7]), 0.0);
  }
}

TEST(CliReconstruct, StreamProblemsAreNamed) {
  // A host that does not resolve: the frames still come, the summary names the problem.
  CliRun r = cli("reconstruct --virtual --frames 3 --no-pace --stream 'udp://no such host!:5005'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(lines(r.out).size(), 4u);
  EXPECT_NE(r.err.find("0 sent, 3 dropped; StreamHostNotFound"), std::string::npos) << r.err;
  // A malformed address or format is a usage error.
  r = cli("reconstruct --virtual --frames 3 --stream udp://127.0.0.1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--stream"), std::string::npos) << r.err;
  r = cli("reconstruct --virtual --frames 3 --stream udp://127.0.0.1:5005 --stream-format xml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("opentrack"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace imagepro

namespace imagepro {
namespace {

// The constant-velocity motion (thesis A.2) from the command line: render's truth advances
// by velocity / rate a frame and wraps inside the box, and reconstruct --virtual follows it.
TEST(CliReconstruction, ConstantVelocityMotionAdvancesAndWraps) {
  const fs::path dir = freshDir("cli_constant_velocity");
  // Tx 200 mm/s at 10 Hz: 20 mm a frame, wrapping inside 100 mm about the start (+-50 mm).
  CliRun r = cli("render --out " + dir.string() + " --frames 8 --rate 10 --mode binary --pose 0,0,0,0,0,800" +
                 " --motion constant-velocity --velocity 0,5,0,200,0,-30 --box 0,0,0,100,0,0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto truth = readTruth(dir / "truth.csv");
  ASSERT_EQ(truth.size(), 8u);
  const double tx[] = {0, 20, 40, -40, -20, 0, 20, 40};
  for (int i = 0; i < 8; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.png", i);
    const std::vector<double>& p = truth.at(name);
    EXPECT_NEAR(p[1], 0.5 * i, 1e-6) << name;         // Ry 5 deg/s, never wraps (width 0)
    EXPECT_NEAR(p[3], tx[i], 1e-6) << name;           // Tx wraps at +-50 mm
    EXPECT_NEAR(p[5], 800 - 3.0 * i, 1e-6) << name;   // Tz -30 mm/s
  }
  // The same velocities reconstructed from the virtual source (no wrap: no jump for the tracker).
  r = cli("reconstruct --virtual --frames 8 --no-pace --truth --motion constant-velocity --velocity 0,5,0,200,0,-30"
          " --box 0,0,0,0,0,0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 9u) << r.out;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto f = csvFields(rows[i]);
    ASSERT_EQ(f.size(), 16u) << rows[i];  // the pose, its truth, rim_seen, target
    ASSERT_EQ(f[1], "ok") << rows[i];
    EXPECT_NEAR(std::stod(f[11]), 200.0 / 25.0 * static_cast<double>(i - 1), 1e-6) << rows[i];  // 25 Hz
    EXPECT_NEAR(std::stod(f[5]), std::stod(f[11]), 1.0) << rows[i];  // Tx against its truth
  }
  // Named errors: a malformed list, a negative box, the options without --virtual.
  r = cli("reconstruct --virtual --frames 1 --velocity 1,2,3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--velocity takes six numbers"), std::string::npos) << r.err;
  r = cli("render --out " + dir.string() + " --box 0,0,0,-5,0,0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--box"), std::string::npos) << r.err;
  r = cli("reconstruct --motion constant-velocity " + (dir / "frame_00000.png").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--motion goes with --virtual"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace imagepro
