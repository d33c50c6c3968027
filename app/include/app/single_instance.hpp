// One window per user session (the web-browser helper, Nagasawa "Beyond VRML" section 4):
// a second `ghostspace FILE_OR_URL` hands its inputs to the window already running, which
// opens each in a new viewport. The channel is a Unix stream socket at
// $XDG_RUNTIME_DIR/ghostspace.sock (else /tmp/ghostspace-UID.sock), readable only by its
// owner; each message is one input per line, UTF-8, at most 64 KiB in all.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace gs::app {

/// The socket path described above.
std::string instanceSocketPath();

/// Sends `inputs` (local paths made absolute, URLs as they are) to a running window.
/// Returns false when none listens (no socket, or a stale one) or the send failed.
bool handToRunningInstance(const std::vector<std::string>& inputs);

/// The inputs of one message received on the socket (at most 64 KiB of bytes from any
/// local process of the user): one input per "\n"-terminated line; empty lines and an
/// unterminated last line are dropped. Any bytes are accepted (fuzzed:
/// tests/fuzz/fuzz_instance_message.cpp).
std::vector<std::string> parseInstanceMessage(std::string_view message);

/// The listening side, owned by the window: created on construction (a stale socket file
/// of a dead instance is replaced), removed on destruction. Never blocks.
class InstanceServer {
 public:
  InstanceServer();
  ~InstanceServer();
  InstanceServer(const InstanceServer&) = delete;
  InstanceServer& operator=(const InstanceServer&) = delete;
  /// Whether the socket is listening (false: another instance owns it, or no socket could
  /// be made; the window then works alone).
  bool listening() const { return fd_ >= 0; }
  /// The inputs other launches sent since the last call (non-blocking).
  std::vector<std::string> poll();

 private:
  int fd_ = -1;
  std::string path_;
};

}  // namespace gs::app
