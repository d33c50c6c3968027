// The DIS UDP receiver (dis/udp_socket.hpp) over POSIX sockets.
#include "dis/udp_socket.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>

namespace gs::dis {

namespace {

/// The IPv4 socket address of UDP `port` (1..65535) at `address` ("" or "localhost": the
/// loopback; with `any`, "*" or "0.0.0.0": every address; else a dotted IPv4 address).
/// False, and `error` says why, when there is none.
bool udpAddress(int port, const std::string& address, bool any, sockaddr_in& a,
                std::string& error) {
  if (port < 1 || port > 65535) {
    error = "DIS port " + std::to_string(port) + " is not a UDP port (1 to 65535)";
    return false;
  }
  a = sockaddr_in{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  if (address.empty() || address == "localhost") {
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  } else if (any && (address == "*" || address == "0.0.0.0")) {
    a.sin_addr.s_addr = htonl(INADDR_ANY);
  } else if (::inet_pton(AF_INET, address.c_str(), &a.sin_addr) != 1) {
    error = "DIS address \"" + address + "\" is not an IPv4 address or localhost";
    return false;
  }
  return true;
}

/// A non-blocking UDP socket, or -1 with `error` saying why.
int udpSocket(std::string& error) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) error = std::string("cannot make a UDP socket: ") + std::strerror(errno);
  return fd;
}

}  // namespace

UdpReceiver::~UdpReceiver() {
  if (fd_ >= 0) ::close(fd_);
}

bool UdpReceiver::open(int port, const std::string& address, std::string& error) {
  sockaddr_in a{};
  if (!udpAddress(port, address, true, a, error)) return false;
  const int fd = udpSocket(error);
  if (fd < 0) return false;
  const int yes = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) {
    error = "cannot listen for DIS PDUs on UDP port " + std::to_string(port) + " of " +
            (address.empty() ? std::string("localhost") : address) + ": " + std::strerror(errno);
    ::close(fd);
    return false;
  }
  fd_ = fd;
  return true;
}

std::vector<std::vector<std::uint8_t>> UdpReceiver::receive(std::size_t maxDatagrams) {
  std::vector<std::vector<std::uint8_t>> out;
  if (fd_ < 0) return out;
  std::vector<std::uint8_t> buffer(8192);
  while (out.size() < maxDatagrams) {
    const ssize_t n = ::recv(fd_, buffer.data(), buffer.size(), 0);
    if (n < 0) break;  // EAGAIN: nothing more waits (or an error: try again next frame)
    out.emplace_back(buffer.begin(), buffer.begin() + n);
  }
  return out;
}

bool UdpReceiver::sendToLoopback(int port, const std::vector<std::uint8_t>& bytes) {
  std::string error;
  return sendTo("localhost", port, bytes, error);
}

bool UdpReceiver::sendTo(const std::string& address, int port,
                         const std::vector<std::uint8_t>& bytes, std::string& error) {
  const std::string where = "UDP port " + std::to_string(port) + " of " +
                            (address.empty() ? std::string("localhost") : address);
  sockaddr_in a{};
  if (!udpAddress(port, address, false, a, error)) return false;
  const int fd = udpSocket(error);
  if (fd < 0) return false;
  const ssize_t sent =
      ::sendto(fd, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&a), sizeof a);
  const int why = errno;
  ::close(fd);
  if (sent == static_cast<ssize_t>(bytes.size())) return true;
  error = "cannot send a DIS PDU to " + where + ": " +
          (sent < 0 ? std::strerror(why) : "the datagram was cut");
  return false;
}

}  // namespace gs::dis
