#pragma once
// The live pose stream (docs/streaming.md): every frame's result as one UDP datagram,
// for programs that read the pose as it is made. Two formats: JSON (the data-out row's
// frame, timestamp, status and six parameters, with the same names and digits) and
// OpenTrack's "UDP over network" input. Sending never blocks or stops the frame loop:
// a full socket buffer drops the datagram and counts it; an unknown host, no route or
// nobody listening is a named status (Status::Stream*), and the frames go on.
#include <array>
#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/common/status.h"
#include "core/pipeline/frame_result.h"
#include "core/settings/options.h"

namespace imagepro {

// "udp://HOST:PORT" (HOST a name, an IPv4 address or a bracketed IPv6 one) into `out`'s
// host and port; false with `error` saying what is wrong. The port's range is the
// settings table's (stream.port).
bool parseStreamUrl(std::string_view url, StreamOptions& out, std::string& error);
// The destination as parseStreamUrl reads it.
std::string streamUrl(const StreamOptions& options);

// One frame as its JSON datagram: {"frame", "timestamp_s", "status", the six pose columns
// (null without a pose), "name" for file input, "targets": with a set of targets every
// target told, each with the record's fields (the frame's own are its shown target's),
// else a status and pose per target when the frame has several}.
std::string poseStreamJson(const FrameResult& result);
// The pose in OpenTrack's axes: x, y, z in cm, yaw, pitch, roll in degrees (docs/streaming.md).
std::array<double, 6> openTrackValues(const Pose& pose);
// Those six values as OpenTrack reads them: little-endian IEEE doubles, 48 bytes.
std::array<std::uint8_t, 48> openTrackDatagram(const Pose& pose);

class PoseStream {
 public:
  PoseStream() = default;
  ~PoseStream();
  PoseStream(const PoseStream&) = delete;
  PoseStream& operator=(const PoseStream&) = delete;

  // Resolves the host and opens a non-blocking UDP socket towards it (enabled or not:
  // the caller decides). StreamHostNotFound or StreamUnreachable with `error` naming the
  // destination when it cannot; the stream then counts every frame as dropped.
  Status open(const StreamOptions& options, std::string& error);
  void close();
  bool isOpen() const { return fd_ >= 0; }
  // Whether open() was called since the last close(), successfully or not.
  bool isActive() const { return active_; }
  const StreamOptions& options() const { return options_; }

  // Sends the frame's datagram without waiting. OpenTrack's format sends frames with a
  // pose only (OpenTrack keeps the last pose); the others are neither sent nor dropped.
  void send(const FrameResult& result);

  std::int64_t sent() const { return sent_; }
  std::int64_t dropped() const { return dropped_; }
  // Ok, or the last problem while it is recent (kProblemHold): the status bar's word.
  Status status() const;
  // The last problem in words, with the destination and the system's reason.
  const std::string& problem() const { return problem_; }
  // "udp://127.0.0.1:5005 json: 250 sent, 0 dropped" and the status when not Ok.
  std::string report() const;

  // How long a problem stays the stream's status after it was last seen: a refused
  // datagram is reported on every other send, so a single success must not clear it.
  static constexpr std::chrono::milliseconds kProblemHold{2000};

 private:
  void setProblem(Status status, int error_number);

  int fd_ = -1;
  bool active_ = false;
  StreamOptions options_;
  std::int64_t sent_ = 0, dropped_ = 0;
  Status problem_status_ = Status::Ok;
  std::string problem_;
  std::chrono::steady_clock::time_point problem_seen_{};
};

}  // namespace imagepro
