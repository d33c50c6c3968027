// The DIS UDP receiver (dis/udp_socket.hpp) over POSIX sockets; a multicast address is
// joined as a group (RFC 1112).
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

/// Whether `a` is an IPv4 multicast group (224.0.0.0/4, RFC 5771).
bool isMulticast(const sockaddr_in& a) {
  return (ntohl(a.sin_addr.s_addr) >> 28) == 0xE;
}

/// Joins multicast group `group` on `fd` on the loopback and on the interface the routing
/// table picks (RFC 1112 host membership): datagrams for the group sent on this host (to
/// either) and from the network arrive. False, and `error` says why, when neither join
/// succeeds.
bool joinGroup(int fd, const in_addr& group, std::string& error) {
  bool joined = false;
  int why = 0;
  for (const std::uint32_t interface : {INADDR_LOOPBACK, INADDR_ANY}) {
    ip_mreq m{};
    m.imr_multiaddr = group;
    m.imr_interface.s_addr = htonl(interface);
    if (::setsockopt(fd, IPPROTO_IP, IP_ADD_MEMBERSHIP, &m, sizeof m) == 0)
      joined = true;
    else if (errno != EADDRINUSE)  // (the routing table picked the loopback too)
      why = errno;
  }
  if (!joined) error = std::string("cannot join the multicast group: ") + std::strerror(why);
  return joined;
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
  const std::string where = "UDP port " + std::to_string(port) + " of " +
                            (address.empty() ? std::string("localhost") : address);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) {
    error = "cannot listen for DIS PDUs on " + where + ": " + std::strerror(errno);
    ::close(fd);
    return false;
  }
  std::string why;
  if (isMulticast(a) && !joinGroup(fd, a.sin_addr, why)) {
    error = "cannot listen for DIS PDUs on " + where + ": " + why;
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
  ssize_t sent =
      ::sendto(fd, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&a), sizeof a);
  int why = errno;
  if (sent < 0 && isMulticast(a) && (why == ENETUNREACH || why == EHOSTUNREACH)) {
    // No route for the group (a host without a network): its members on this host can
    // still hear it on the loopback.
    in_addr loopback{};
    loopback.s_addr = htonl(INADDR_LOOPBACK);
    if (::setsockopt(fd, IPPROTO_IP, IP_MULTICAST_IF, &loopback, sizeof loopback) == 0) {
      sent = ::sendto(fd, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&a),
                      sizeof a);
      why = errno;
    }
  }
  ::close(fd);
  if (sent == static_cast<ssize_t>(bytes.size())) return true;
  error = "cannot send a DIS PDU to " + where + ": " +
          (sent < 0 ? std::strerror(why) : "the datagram was cut");
  return false;
}

}  // namespace gs::dis
