#include "core/pipeline/pose_stream.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "core/analysis/pose_series.h"
#include "core/common/geometry.h"
#include "core/common/pose_csv.h"
#include "core/pipeline/data_out.h"
#include "core/pipeline/engine.h"
#include "core/source/sources.h"
#include "support/test_dirs.h"
#include "support/udp_receiver.h"

namespace imagepro {
namespace {

using Receiver = test::UdpReceiver;

StreamOptions loopback(int port, StreamFormat format = StreamFormat::Json) {
  StreamOptions o;
  o.enabled = true;
  o.host = "127.0.0.1";
  o.port = port;
  o.format = format;
  return o;
}

// A virtual run whose target swings out of view part of the time, so some frames have
// no pose: every frame goes to the data-out CSV and to the stream.
TEST(PoseStream, LoopbackReaderGetsEveryFrameOfAVirtualRunInOrderWithTheCsvValues) {
  Settings s;
  s.virtual_scene.motion.kind = MotionKind::Sinusoid;
  s.virtual_scene.motion.axis = PoseAxis::Tx;
  s.virtual_scene.motion.amplitude = 700;
  s.virtual_scene.motion.period_s = 3;
  VirtualSource source(s);
  Engine engine(s);
  const auto dir = test::freshDir("pose_stream_loopback");
  const std::string csv_path = (dir / "run.csv").string();
  DataOut data_out;
  std::string error;
  ASSERT_EQ(data_out.open(csv_path, ExistingFile::Fail, error), Status::Ok) << error;
  Receiver receiver;
  PoseStream stream;
  ASSERT_NE(receiver.port(), 0);
  ASSERT_EQ(stream.open(loopback(receiver.port()), error), Status::Ok) << error;

  constexpr int kFrames = 120;
  std::vector<std::string> datagrams;
  FrameResult r;
  for (int i = 0; i < kFrames; ++i) {
    ASSERT_EQ(engine.step(source, r), Status::Ok);
    ASSERT_TRUE(data_out.write(r, error)) << error;
    stream.send(r);
    for (std::string& d : receiver.drain()) datagrams.push_back(std::move(d));
  }
  data_out.close();
  EXPECT_EQ(stream.sent(), kFrames);
  EXPECT_EQ(stream.dropped(), 0);
  EXPECT_EQ(stream.status(), Status::Ok);
  ASSERT_EQ(datagrams.size(), static_cast<std::size_t>(kFrames));

  std::ifstream csv(csv_path);
  std::string line;
  std::getline(csv, line);  // header
  int with_pose = 0, without = 0;
  for (int i = 0; i < kFrames; ++i) {
    ASSERT_TRUE(std::getline(csv, line));
    const auto cells = splitCsvLine(line);
    ASSERT_GE(cells.size(), 9u);
    const auto j = nlohmann::json::parse(datagrams[static_cast<std::size_t>(i)]);
    EXPECT_EQ(j["frame"].get<std::int64_t>(), i);  // in order, none lost
    EXPECT_EQ(std::to_string(j["frame"].get<std::int64_t>()), cells[0]);
    EXPECT_EQ(j["status"].get<std::string>(), cells[1]) << "frame " << i;
    EXPECT_EQ(poseNumber(j["timestamp_s"].get<double>()), cells[8]);
    for (std::size_t k = 0; k < kPoseColumnNames.size(); ++k) {
      const auto& v = j[std::string(kPoseColumnNames[k])];
      if (cells[2 + k].empty()) {
        EXPECT_TRUE(v.is_null()) << "frame " << i << " " << kPoseColumnNames[k];
      } else {
        ASSERT_TRUE(v.is_number()) << "frame " << i << " " << kPoseColumnNames[k];
        EXPECT_EQ(poseNumber(v.get<double>()), cells[2 + k]) << "frame " << i << " " << kPoseColumnNames[k];
      }
    }
    (cells[2].empty() ? without : with_pose)++;
  }
  // The run holds both kinds of frame, so both kinds were compared.
  EXPECT_GT(with_pose, 20);
  EXPECT_GT(without, 5);
}

TEST(PoseStream, JsonCarriesEveryTargetWhenThereAreSeveral) {
  FrameResult r;
  r.index = 7;
  r.timestamp_s = 0.28;
  r.status = Status::Ok;
  r.pose = Pose{1, 2, 3, 4, 5, 600};
  r.targets.resize(2);
  r.targets[0].status = Status::Ok;
  r.targets[0].pose = r.pose;
  r.targets[1].status = Status::SpotsNotFound;
  const auto j = nlohmann::json::parse(poseStreamJson(r));
  EXPECT_EQ(j["frame"], 7);
  EXPECT_EQ(j["Tz_mm"].get<double>(), 600.0);
  ASSERT_EQ(j["targets"].size(), 2u);
  EXPECT_EQ(j["targets"][0]["Rx_deg"].get<double>(), 1.0);
  EXPECT_EQ(j["targets"][1]["status"], "SpotsNotFound");
  EXPECT_TRUE(j["targets"][1]["Rx_deg"].is_null());

  r.targets.resize(1);
  EXPECT_FALSE(nlohmann::json::parse(poseStreamJson(r)).contains("targets"));
  r.name = "a \"quoted\", name.png";
  EXPECT_EQ(nlohmann::json::parse(poseStreamJson(r))["name"], r.name);
  // A value JSON cannot hold is null, never invalid JSON.
  r.pose->tx_mm = std::nan("");
  EXPECT_TRUE(nlohmann::json::parse(poseStreamJson(r))["Tx_mm"].is_null());
}

TEST(PoseStream, OpenTrackDatagramIsSixLittleEndianDoublesInCentimetresAndDegrees) {
  const Pose p{0, 0, 0, 100, -50, 800};
  const auto bytes = openTrackDatagram(p);
  // 10.0 = 0x4024000000000000, 5.0 = 0x4014..., 80.0 = 0x4054..., least significant byte first.
  const std::array<std::uint8_t, 8> ten{0, 0, 0, 0, 0, 0, 0x24, 0x40}, five{0, 0, 0, 0, 0, 0, 0x14, 0x40},
      eighty{0, 0, 0, 0, 0, 0, 0x54, 0x40}, zero{};
  EXPECT_TRUE(std::equal(ten.begin(), ten.end(), bytes.begin()));         // x: Tx / 10
  EXPECT_TRUE(std::equal(five.begin(), five.end(), bytes.begin() + 8));   // y: up, -Ty / 10
  EXPECT_TRUE(std::equal(eighty.begin(), eighty.end(), bytes.begin() + 16));
  for (int k = 3; k < 6; ++k) EXPECT_TRUE(std::equal(zero.begin(), zero.end(), bytes.begin() + 8 * k)) << k;
}

TEST(PoseStream, OpenTrackAnglesFollowItsAxes) {
  auto angles = [](double rx, double ry, double rz) {
    const auto v = openTrackValues(Pose{rx, ry, rz, 0, 0, 1000});
    return std::array<double, 3>{v[3], v[4], v[5]};
  };
  // Turning about the camera's vertical axis is yaw, tilting about its horizontal axis
  // pitch (nose up positive: our Rx turns the face down), about the optical axis roll.
  const auto yaw = angles(0, 20, 0), pitch = angles(10, 0, 0), roll = angles(0, 0, 15);
  EXPECT_NEAR(yaw[0], 20, 1e-9);
  EXPECT_NEAR(yaw[1], 0, 1e-9);
  EXPECT_NEAR(yaw[2], 0, 1e-9);
  EXPECT_NEAR(pitch[0], 0, 1e-9);
  EXPECT_NEAR(pitch[1], -10, 1e-9);
  EXPECT_NEAR(pitch[2], 0, 1e-9);
  EXPECT_NEAR(roll[0], 0, 1e-9);
  EXPECT_NEAR(roll[1], 0, 1e-9);
  EXPECT_NEAR(roll[2], 15, 1e-9);
  // Combined: yaw, pitch and roll composed as OpenTrack composes them give our rotation back.
  const Pose p{12, -25, 40, 0, 0, 1000};
  const auto v = openTrackValues(p);
  auto about = [](const Eigen::Vector3d& axis, double deg) {
    return Eigen::AngleAxisd(deg * M_PI / 180.0, axis).toRotationMatrix();
  };
  const Eigen::Matrix3d E = about(Eigen::Vector3d::UnitZ(), v[3]) * about(Eigen::Vector3d::UnitY(), -v[4]) *
                            about(Eigen::Vector3d::UnitX(), v[5]);
  Eigen::Matrix3d M;
  M << 0, 0, -1, -1, 0, 0, 0, -1, 0;
  EXPECT_LT((M.transpose() * E * M - rotationMatrix(p)).norm(), 1e-9);
}

// A datagram read back as OpenTrack reads it: six little-endian doubles, whatever this
// machine's byte order.
std::array<double, 6> decodeOpenTrack(const std::string& datagram) {
  std::array<double, 6> v{};
  EXPECT_EQ(datagram.size(), 48u);
  for (std::size_t k = 0; k < 6 && datagram.size() >= 8 * (k + 1); ++k) {
    std::uint64_t bits = 0;
    for (int b = 7; b >= 0; --b) bits = (bits << 8) | static_cast<std::uint8_t>(datagram[8 * k + static_cast<std::size_t>(b)]);
    std::memcpy(&v[k], &bits, sizeof bits);
  }
  return v;
}

// docs/streaming.md's table, one axis at a time, through a real socket: x = Tx/10,
// y = -Ty/10, z = Tz/10 in cm; yaw = Ry, pitch = -Rx, roll = Rz in degrees.
TEST(PoseStream, OpenTrackDatagramsDecodeToTheDocumentedAxes) {
  Receiver receiver;
  PoseStream stream;
  std::string error;
  ASSERT_EQ(stream.open(loopback(receiver.port(), StreamFormat::OpenTrack), error), Status::Ok) << error;
  const std::array<Pose, 4> poses{Pose{0, 0, 0, 40, -30, 900}, Pose{0, 20, 0, 0, 0, 700}, Pose{10, 0, 0, 0, 0, 700},
                                  Pose{0, 0, -35, -5, 12.5, 1234}};
  const std::array<std::array<double, 6>, 4> expected{{{4, 3, 90, 0, 0, 0},
                                                       {0, 0, 70, 20, 0, 0},
                                                       {0, 0, 70, 0, -10, 0},
                                                       {-0.5, -1.25, 123.4, 0, 0, -35}}};
  for (const Pose& p : poses) {
    FrameResult r;
    r.status = Status::Ok;
    r.pose = p;
    stream.send(r);
  }
  const auto got = receiver.drain();
  ASSERT_EQ(got.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const auto v = decodeOpenTrack(got[i]);
    for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(v[k], expected[i][k], 1e-9) << "pose " << i << ", value " << k;
  }
}

TEST(PoseStream, OpenTrackSendsFramesWithAPoseOnly) {
  Receiver receiver;
  PoseStream stream;
  std::string error;
  ASSERT_EQ(stream.open(loopback(receiver.port(), StreamFormat::OpenTrack), error), Status::Ok) << error;
  FrameResult r;
  r.status = Status::Ok;
  r.pose = Pose{1, 2, 3, 4, 5, 600};
  stream.send(r);
  FrameResult miss;
  miss.status = Status::NoTarget;
  stream.send(miss);
  const auto got = receiver.drain();
  ASSERT_EQ(got.size(), 1u);
  const auto expected = openTrackDatagram(*r.pose);
  EXPECT_EQ(got[0], std::string(expected.begin(), expected.end()));
  EXPECT_EQ(stream.sent(), 1);
  EXPECT_EQ(stream.dropped(), 0);
}

TEST(PoseStream, BadHostIsStreamHostNotFoundAndTheFramesAreCountedDropped) {
  for (const char* host : {"no such host!", "999.1.2.3", "bad..name.invalid"}) {
    PoseStream stream;
    StreamOptions o = loopback(5005);
    o.host = host;
    std::string error;
    EXPECT_EQ(stream.open(o, error), Status::StreamHostNotFound) << host;
    EXPECT_NE(error.find(host), std::string::npos) << error;
    FrameResult r;
    stream.send(r);
    stream.send(r);
    EXPECT_EQ(stream.dropped(), 2);
    EXPECT_EQ(stream.sent(), 0);
    EXPECT_EQ(stream.status(), Status::StreamHostNotFound);
    EXPECT_NE(stream.report().find("StreamHostNotFound"), std::string::npos) << stream.report();
  }
}

TEST(PoseStream, NobodyListeningIsStreamRefusedAndTheFramesGoOn) {
  int port = 0;
  {
    Receiver gone;  // a port that was free a moment ago, closed again
    port = gone.port();
  }
  PoseStream stream;
  std::string error;
  ASSERT_EQ(stream.open(loopback(port), error), Status::Ok) << error;
  FrameResult r;
  for (int i = 0; i < 6; ++i) stream.send(r);
  EXPECT_EQ(stream.sent() + stream.dropped(), 6);
  EXPECT_GE(stream.dropped(), 1);
  EXPECT_EQ(stream.status(), Status::StreamRefused);
  EXPECT_NE(stream.problem().find("udp://127.0.0.1:" + std::to_string(port)), std::string::npos);
}

// A reader that never reads: the sender neither waits nor fails; what the socket cannot
// take is dropped and counted.
TEST(PoseStream, SendingNeverWaitsForTheReader) {
  Receiver receiver;
  PoseStream stream;
  std::string error;
  ASSERT_EQ(stream.open(loopback(receiver.port()), error), Status::Ok) << error;
  FrameResult r;
  r.pose = Pose{};
  constexpr int kFrames = 20000;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < kFrames; ++i) {
    r.index = i;
    stream.send(r);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(stream.sent() + stream.dropped(), kFrames);
  EXPECT_LT(seconds / kFrames, 1e-3) << seconds << " s";
  // docs/streaming.md quotes this: the cost of one frame's datagram, made and sent.
  std::printf("%d datagrams in %.3f s: %.1f us each; %lld sent, %lld dropped\n", kFrames, seconds,
              1e6 * seconds / kFrames, static_cast<long long>(stream.sent()), static_cast<long long>(stream.dropped()));
  EXPECT_LT(receiver.drain().size(), static_cast<std::size_t>(kFrames));  // the reader's buffer overflowed
}

TEST(PoseStream, ParsesStreamUrls) {
  StreamOptions o;
  std::string error;
  ASSERT_TRUE(parseStreamUrl("udp://localhost:4242", o, error)) << error;
  EXPECT_EQ(o.host, "localhost");
  EXPECT_EQ(o.port, 4242);
  ASSERT_TRUE(parseStreamUrl("udp://[::1]:5005", o, error)) << error;
  EXPECT_EQ(o.host, "::1");
  EXPECT_EQ(streamUrl(o), "udp://[::1]:5005");
  for (const char* bad : {"tcp://a:1", "udp://a", "udp://:5005", "udp://a:0", "udp://a:65536", "udp://a:12x",
                          "udp://[::1:5005", "udp://a:"}) {
    StreamOptions before = o;
    EXPECT_FALSE(parseStreamUrl(bad, o, error)) << bad;
    EXPECT_NE(error.find(bad), std::string::npos) << error;
    EXPECT_EQ(o, before);
  }
}

}  // namespace
}  // namespace imagepro
