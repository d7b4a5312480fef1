#include "core/pipeline/pose_stream.h"

#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>


#include <algorithm>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>

#include "core/pipeline/frame_record.h"
#include "core/pipeline/told_targets.h"
#include "core/settings/enum_names.h"
#include "core/settings/settings.h"

namespace imagepro {

namespace {

constexpr std::string_view kScheme = "udp://";

std::string hostForUrl(const std::string& host) {
  return host.find(':') != std::string::npos ? "[" + host + "]" : host;
}

double radToDeg(double r) { return r * 180.0 / M_PI; }

}  // namespace

bool parseStreamUrl(std::string_view url, StreamOptions& out, std::string& error) {
  if (url.substr(0, kScheme.size()) != kScheme) {
    error = "\"" + std::string(url) + "\": a stream is udp://HOST:PORT";
    return false;
  }
  std::string_view rest = url.substr(kScheme.size());
  std::string_view host, port;
  if (!rest.empty() && rest.front() == '[') {  // [IPv6]:PORT
    const auto close = rest.find(']');
    if (close == std::string_view::npos || close + 1 >= rest.size() || rest[close + 1] != ':') {
      error = "\"" + std::string(url) + "\": an IPv6 host is written [ADDRESS]:PORT";
      return false;
    }
    host = rest.substr(1, close - 1);
    port = rest.substr(close + 2);
  } else {
    const auto colon = rest.rfind(':');
    if (colon == std::string_view::npos) {
      error = "\"" + std::string(url) + "\": the port is missing (udp://HOST:PORT)";
      return false;
    }
    host = rest.substr(0, colon);
    port = rest.substr(colon + 1);
  }
  if (host.empty()) {
    error = "\"" + std::string(url) + "\": the host is missing (udp://HOST:PORT)";
    return false;
  }
  const SettingKey* key = findSettingKey("stream.port");
  long value = 0;
  const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
  if (port.empty() || ec != std::errc() || end != port.data() + port.size() || value < key->lo || value > key->hi) {
    error = "\"" + std::string(url) + "\": the port must be a whole number from " + std::to_string(int(key->lo)) +
            " to " + std::to_string(int(key->hi));
    return false;
  }
  out.host = std::string(host);
  out.port = static_cast<int>(value);
  return true;
}

std::string streamUrl(const StreamOptions& o) {
  return std::string(kScheme) + hostForUrl(o.host) + ":" + std::to_string(o.port);
}

std::string poseStreamJson(const FrameResult& r) {
  std::string out = "{" + recordJsonMembers(r, kStreamJson);
  if (r.set_of_targets) {
    // Every target told, each with the record's fields: the frame's own are its shown target's.
    out += ",\"targets\":[";
    FrameResult row;
    const bool told = std::any_of(r.targets.begin(), r.targets.end(), isToldTarget);  // else an empty list
    for (std::size_t k = 0; told && k < recordRowCount(r); ++k) {
      recordRow(r, k, row);
      out += (k ? ",{" : "{") + recordJsonMembers(row, kStreamJson) + "}";
    }
    out += ']';
  } else if (r.targets.size() > 1) {
    out += ",\"targets\":[";
    for (std::size_t i = 0; i < r.targets.size(); ++i) {
      const TargetSummary& t = r.targets[i];
      out += i ? ",{" : "{";
      out += "\"status\":\"" + std::string(statusName(t.status)) + "\",";  // names need no escaping
      out += poseJsonMembers(ok(t.status) && t.pose ? &*t.pose : nullptr);
      out += '}';
    }
    out += ']';
  }
  return out + "}";
}

std::array<double, 6> openTrackValues(const Pose& pose) {
  // OpenTrack's own point tracker reports a camera frame of x right, y up, z away from
  // the camera (ours: y down), and its angles in a frame of x towards the camera, y to
  // the camera's left, z up: M below takes our camera axes to that one. Yaw is about
  // its z, pitch about its y (negated), roll about its x, composed z-y-x as it does.
  Eigen::Matrix3d M;
  M << 0, 0, -1, -1, 0, 0, 0, -1, 0;
  const Eigen::Matrix3d R = M * rotationMatrix(pose) * M.transpose();
  const double yaw = radToDeg(std::atan2(R(1, 0), R(0, 0)));
  const double pitch = radToDeg(std::atan2(R(2, 0), std::hypot(R(2, 1), R(2, 2))));
  const double roll = radToDeg(std::atan2(R(2, 1), R(2, 2)));
  return {pose.tx_mm / 10.0, -pose.ty_mm / 10.0, pose.tz_mm / 10.0, yaw, pitch, roll};
}

std::array<std::uint8_t, 48> openTrackDatagram(const Pose& pose) {
  std::array<std::uint8_t, 48> bytes{};
  const auto values = openTrackValues(pose);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const auto bits = std::bit_cast<std::uint64_t>(values[i]);
    for (std::size_t b = 0; b < 8; ++b) bytes[8 * i + b] = static_cast<std::uint8_t>(bits >> (8 * b));
  }
  return bytes;
}

PoseStream::~PoseStream() { close(); }

void PoseStream::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  active_ = false;
}

Status PoseStream::open(const StreamOptions& options, std::string& error) {
  close();
  options_ = options;
  active_ = true;
  sent_ = dropped_ = 0;
  problem_status_ = Status::Ok;
  problem_.clear();
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_DGRAM;
  hints.ai_flags = AI_NUMERICSERV;
  addrinfo* found = nullptr;
  const std::string port = std::to_string(options.port);
  const int gai = options.host.empty() ? EAI_NONAME : ::getaddrinfo(options.host.c_str(), port.c_str(), &hints, &found);
  if (gai != 0) {
    problem_status_ = Status::StreamHostNotFound;
    problem_seen_ = std::chrono::steady_clock::now();
    problem_ = streamUrl(options) + ": the host \"" + options.host + "\" is not found (" + ::gai_strerror(gai) + ")";
    error = problem_;
    return problem_status_;
  }
  int last_errno = 0;
  for (const addrinfo* a = found; a && fd_ < 0; a = a->ai_next) {
    fd_ = ::socket(a->ai_family, a->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, a->ai_protocol);
    if (fd_ < 0) {
      last_errno = errno;
      continue;
    }
    // Connected, so the kernel reports an unreachable host or a closed port to send().
    if (::connect(fd_, a->ai_addr, a->ai_addrlen) != 0) {
      last_errno = errno;
      ::close(fd_);
      fd_ = -1;
    }
  }
  ::freeaddrinfo(found);
  if (fd_ < 0) {
    setProblem(Status::StreamUnreachable, last_errno);
    error = problem_;
    return problem_status_;
  }
  return Status::Ok;
}

void PoseStream::setProblem(Status status, int error_number) {
  problem_status_ = status;
  problem_seen_ = std::chrono::steady_clock::now();
  problem_ = streamUrl(options_) + ": " + std::string(statusMessage(status)) + " (" + std::strerror(error_number) + ")";
}

void PoseStream::send(const FrameResult& r) {
  if (!active_) return;
  const bool opentrack = options_.format == StreamFormat::OpenTrack;
  if (opentrack && !(ok(r.status) && r.pose)) return;
  if (fd_ < 0) {
    ++dropped_;
    return;
  }
  std::string json;
  std::array<std::uint8_t, 48> binary{};
  const void* data = nullptr;
  std::size_t size = 0;
  if (opentrack) {
    binary = openTrackDatagram(*r.pose);
    data = binary.data();
    size = binary.size();
  } else {
    json = poseStreamJson(r);
    data = json.data();
    size = json.size();
  }
  const ssize_t n = ::send(fd_, data, size, MSG_DONTWAIT | MSG_NOSIGNAL);
  if (n == static_cast<ssize_t>(size)) {
    ++sent_;
    return;
  }
  ++dropped_;
  if (n >= 0) return;  // a datagram goes whole or not at all; nothing else to report
  switch (errno) {
    case EAGAIN:
#if EWOULDBLOCK != EAGAIN
    case EWOULDBLOCK:
#endif
    case ENOBUFS:
    case EINTR:
      break;  // the socket's buffer is full: this datagram is dropped, the next may go
    case ECONNREFUSED:
      setProblem(Status::StreamRefused, errno);
      break;
    default:  // ENETUNREACH, EHOSTUNREACH, EHOSTDOWN, ENETDOWN, EACCES, EMSGSIZE, ...
      setProblem(Status::StreamUnreachable, errno);
      break;
  }
}

Status PoseStream::status() const {
  if (problem_status_ == Status::Ok) return Status::Ok;
  // An open failure stays: nothing is sent until the stream is opened anew.
  if (fd_ < 0) return problem_status_;
  return std::chrono::steady_clock::now() - problem_seen_ < kProblemHold ? problem_status_ : Status::Ok;
}

std::string PoseStream::report() const {
  std::string text = streamUrl(options_) + " " + std::string(enumName(options_.format)) + ": " +
                     std::to_string(sent_) + " sent, " + std::to_string(dropped_) + " dropped";
  if (const Status s = status(); !ok(s)) text += "; " + std::string(statusName(s));
  return text;
}

}  // namespace imagepro
