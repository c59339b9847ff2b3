#pragma once
/// @file
/// A UDP port on 127.0.0.1 held busy for the lifetime of the object (tests of "port in use" errors).

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdint>
#include <stdexcept>

namespace laguerre::testing {

/// Binds a UDP socket to a port of 127.0.0.1 the kernel picks and keeps it until destruction.
class BusyUdpPort {
public:
  BusyUdpPort() : fd_(::socket(AF_INET, SOCK_DGRAM, 0)) {
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof addr;
    if (fd_ < 0 || ::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
        ::getsockname(fd_, reinterpret_cast<sockaddr*>(&addr), &len) != 0)
      throw std::runtime_error("BusyUdpPort: cannot bind a UDP socket on 127.0.0.1");
    port_ = ntohs(addr.sin_port);
  }
  ~BusyUdpPort() { ::close(fd_); }
  BusyUdpPort(const BusyUdpPort&) = delete;
  BusyUdpPort& operator=(const BusyUdpPort&) = delete;

  /// The port held.
  std::uint16_t port() const { return port_; }

private:
  int fd_;
  std::uint16_t port_ = 0;
};

}  // namespace laguerre::testing
