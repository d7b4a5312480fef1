#pragma once
// A UDP socket bound to an unused port of the loopback address, for the tests of the
// live pose stream: what a reader of the stream would receive.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <string>
#include <vector>

namespace imagepro::test {

class UdpReceiver {
 public:
  UdpReceiver() {
    fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof a;
    if (fd_ >= 0 && ::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
        ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len) == 0)
      port_ = ntohs(a.sin_port);
  }
  ~UdpReceiver() { close(); }
  UdpReceiver(const UdpReceiver&) = delete;
  UdpReceiver& operator=(const UdpReceiver&) = delete;

  void close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
  // The bound port; 0 when the socket could not be made.
  int port() const { return port_; }
  // Every datagram waiting now, in the order they came; none waits for more.
  std::vector<std::string> drain() {
    std::vector<std::string> out;
    static char buf[65536];
    for (ssize_t n; fd_ >= 0 && (n = ::recv(fd_, buf, sizeof buf, 0)) >= 0;)
      out.emplace_back(buf, static_cast<std::size_t>(n));
    return out;
  }

 private:
  int fd_ = -1;
  int port_ = 0;
};

}  // namespace imagepro::test
