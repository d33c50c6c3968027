// A UDP socket that receives DIS PDUs (IEEE 1278.2: DIS over UDP, port given by the world):
// bound to a port on every local address (or the address given, or a multicast group it
// joins), non-blocking; and the sending of one datagram. POSIX.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace gs::dis {

class UdpReceiver {
 public:
  UdpReceiver() = default;
  ~UdpReceiver();
  UdpReceiver(const UdpReceiver&) = delete;
  UdpReceiver& operator=(const UdpReceiver&) = delete;

  /// Binds to UDP `port` (1..65535) of `address` ("" or "localhost": the loopback; "*" or
  /// "0.0.0.0": every address; else a dotted IPv4 address). A multicast address
  /// (224.0.0.0/4) is joined as a group (RFC 1112) on the loopback and on the interface the
  /// routing table picks, so that its datagrams sent from this host or the network arrive.
  /// False, and `error` says which port and why, when it cannot (a port in use, a bad
  /// address, a group that cannot be joined).
  bool open(int port, const std::string& address, std::string& error);
  bool isOpen() const { return fd_ >= 0; }
  /// The datagrams waiting, oldest first, at most `maxDatagrams` of them (each at most
  /// 8192 bytes: a longer one is cut there); never blocks.
  std::vector<std::vector<std::uint8_t>> receive(std::size_t maxDatagrams);
  /// Sends `bytes` to UDP `port` of the loopback (tests); false when it could not.
  static bool sendToLoopback(int port, const std::vector<std::uint8_t>& bytes);
  /// Sends `bytes` as one datagram to UDP `port` (1..65535) of `address` ("" or
  /// "localhost": the loopback; else a dotted IPv4 address, multicast ones included:
  /// EspduTransform's networkWriter; a group with no route is sent on the loopback, where
  /// this host's members hear it). False, and `error` says where to and why, when it
  /// could not. Never blocks.
  static bool sendTo(const std::string& address, int port, const std::vector<std::uint8_t>& bytes,
                     std::string& error);

 private:
  int fd_ = -1;
};

}  // namespace gs::dis
