#include "app/single_instance.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "base/url.hpp"

namespace gs::app {

namespace {

constexpr std::size_t kMaxMessage = 64 * 1024;

bool makeAddress(const std::string& path, sockaddr_un& address) {
  std::memset(&address, 0, sizeof address);
  address.sun_family = AF_UNIX;
  if (path.size() >= sizeof address.sun_path) return false;
  std::memcpy(address.sun_path, path.c_str(), path.size() + 1);
  return true;
}

/// A connected socket to `path`, or -1.
int connectTo(const std::string& path) {
  sockaddr_un address;
  if (!makeAddress(path, address)) return -1;
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return -1;
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

}  // namespace

std::string instanceSocketPath() {
  if (const char* dir = std::getenv("XDG_RUNTIME_DIR"); dir != nullptr && *dir == '/')
    return std::string(dir) + "/ghostspace.sock";
  return "/tmp/ghostspace-" + std::to_string(::getuid()) + ".sock";
}

bool handToRunningInstance(const std::vector<std::string>& inputs) {
  const int fd = connectTo(instanceSocketPath());
  if (fd < 0) return false;
  std::string message;
  for (const std::string& input : inputs) {
    std::string item = input;
    if (!base::isHttpUrl(item)) {
      std::error_code ec;
      const auto absolute = std::filesystem::absolute(item, ec);
      if (!ec) item = absolute.lexically_normal().string();
    }
    if (item.find('\n') != std::string::npos) continue;  // cannot be one line
    message += item + "\n";
  }
  bool ok = message.size() <= kMaxMessage;
  for (std::size_t sent = 0; ok && sent < message.size();) {
    const ssize_t n = ::send(fd, message.data() + sent, message.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) ok = false;
    sent += n > 0 ? static_cast<std::size_t>(n) : 0;
  }
  ::close(fd);
  return ok;
}

InstanceServer::InstanceServer() : path_(instanceSocketPath()) {
  sockaddr_un address;
  if (!makeAddress(path_, address)) return;
  // A socket file nobody answers on is left by an instance that died: replace it.
  if (std::filesystem::exists(path_)) {
    const int probe = connectTo(path_);
    if (probe >= 0) {
      ::close(probe);
      return;  // another window owns it
    }
    ::unlink(path_.c_str());
  }
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd < 0) return;
  const mode_t old = ::umask(0077);  // owner only
  const bool bound = ::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0;
  ::umask(old);
  if (!bound || ::listen(fd, 8) != 0) {
    ::close(fd);
    return;
  }
  fd_ = fd;
}

InstanceServer::~InstanceServer() {
  if (fd_ < 0) return;
  ::close(fd_);
  ::unlink(path_.c_str());
}

std::vector<std::string> InstanceServer::poll() {
  std::vector<std::string> inputs;
  if (fd_ < 0) return inputs;
  for (;;) {
    const int client = ::accept4(fd_, nullptr, nullptr, SOCK_CLOEXEC);
    if (client < 0) break;
    // The sender writes its lines and closes; read until then (at most 1 s, 64 KiB).
    std::string message;
    char buffer[4096];
    for (int waited = 0; message.size() < kMaxMessage && waited < 100;) {
      pollfd p{client, POLLIN, 0};
      if (::poll(&p, 1, 10) == 0) {
        ++waited;
        continue;
      }
      const ssize_t n = ::recv(client, buffer, sizeof buffer, 0);
      if (n <= 0) break;
      message.append(buffer, static_cast<std::size_t>(n));
    }
    ::close(client);
    for (auto& input : parseInstanceMessage(message)) inputs.push_back(std::move(input));
  }
  return inputs;
}

std::vector<std::string> parseInstanceMessage(std::string_view message) {
  std::vector<std::string> inputs;
  std::size_t at = 0;
  while (at < message.size()) {
    const std::size_t eol = message.find('\n', at);
    if (eol == std::string_view::npos) break;  // an unterminated last line is dropped
    if (eol > at) inputs.emplace_back(message.substr(at, eol - at));
    at = eol + 1;
  }
  return inputs;
}

}  // namespace gs::app
