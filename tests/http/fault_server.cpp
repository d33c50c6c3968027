#include "http/fault_server.hpp"

#include "base/text.hpp"

#include <arpa/inet.h>
#include <linux/sockios.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

namespace gs::test {
namespace {

using Clock = std::chrono::steady_clock;
constexpr std::size_t kNoCut = std::numeric_limits<std::size_t>::max();

using B = FaultServer::Behaviour;
struct Named {
  B behaviour;
  const char* name;
};
constexpr Named kNames[] = {
    {B::serve, "serve"},
    {B::ignoreRanges, "ignore-ranges"},
    {B::resetMidway, "reset"},
    {B::resetOnceThenServe, "reset-once"},
    {B::stall, "stall"},
    {B::notFound, "not-found"},
    {B::serverError, "server-error"},
    {B::wrongLengthShort, "short"},
    {B::redirect, "redirect"},
    {B::redirectToFile, "redirect-file"},
    {B::truncate, "truncate"},
    {B::wrongContentRange, "wrong-range"},
};

}  // namespace

const char* FaultServer::behaviourName(Behaviour behaviour) {
  for (const Named& n : kNames)
    if (n.behaviour == behaviour) return n.name;
  return "?";
}

bool FaultServer::behaviourFromName(const std::string& name, Behaviour& behaviour) {
  for (const Named& n : kNames)
    if (name == n.name) {
      behaviour = n.behaviour;
      return true;
    }
  return false;
}

FaultServer::FaultServer(std::string body, Behaviour behaviour, std::size_t cutAfter)
    : FaultServer(Config{"", std::move(body), {behaviour}, cutAfter}) {}

FaultServer::FaultServer(Config config) : config_(std::move(config)) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return;
  const int one = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(static_cast<std::uint16_t>(config_.port));
  socklen_t len = sizeof a;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || ::listen(fd, 16) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0) {
    ::close(fd);
    return;
  }
  listenFd_ = fd;
  port_ = ntohs(a.sin_port);
  thread_ = std::thread([this] { loop(); });
}

FaultServer::~FaultServer() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  if (listenFd_ >= 0) ::close(listenFd_);
}

std::string FaultServer::url(const std::string& path) const {
  return "http://127.0.0.1:" + std::to_string(port_) + path;
}

std::vector<FaultServer::Request> FaultServer::requests() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return requests_;
}

void FaultServer::loop() {
  int connection = 0;
  while (!stop_) {
    pollfd p{listenFd_, POLLIN, 0};
    if (::poll(&p, 1, 20) <= 0) continue;
    const int fd = ::accept4(listenFd_, nullptr, nullptr, SOCK_CLOEXEC);
    if (fd < 0) continue;
    handle(fd, connection++);
  }
}

bool FaultServer::readRequest(int fd, Request& request) {
  std::string in;
  const auto deadline = Clock::now() + std::chrono::seconds(5);
  while (in.find("\r\n\r\n") == std::string::npos) {
    if (stop_ || Clock::now() > deadline || in.size() > 65536) return false;
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 20) <= 0) continue;
    char buf[4096];
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) return false;
    in.append(buf, static_cast<std::size_t>(n));
  }
  // "GET /path HTTP/1.1", then headers.
  const auto sp1 = in.find(' '), sp2 = in.find(' ', sp1 + 1);
  if (sp1 == std::string::npos || sp2 == std::string::npos) return false;
  request.path = in.substr(sp1 + 1, sp2 - sp1 - 1);
  std::size_t pos = in.find("\r\n");
  while (pos != std::string::npos && pos + 2 < in.size()) {
    const auto next = in.find("\r\n", pos + 2);
    const std::string line = in.substr(pos + 2, next - pos - 2);
    const auto colon = line.find(':');
    if (colon != std::string::npos && gs::base::equalsNoCase(line.substr(0, colon), "range")) {
      const auto b = line.find_first_not_of(' ', colon + 1);
      request.range = b == std::string::npos ? "" : line.substr(b);
    }
    pos = next;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  requests_.push_back(request);
  return true;
}

bool FaultServer::sendAll(int fd, const std::string& bytes) {
  // Paced (Config::bytesPerSecond): pieces of a twentieth of a second, each sent once the
  // clock reaches the time its first byte is due.
  const double rate = config_.bytesPerSecond;
  const std::size_t piece =
      rate > 0.0 ? std::max<std::size_t>(512, static_cast<std::size_t>(rate / 20.0)) : bytes.size();
  const auto start = Clock::now();
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    if (stop_) return false;
    if (rate > 0.0) {
      const auto due = start + std::chrono::duration_cast<Clock::duration>(
                                   std::chrono::duration<double>(static_cast<double>(sent) / rate));
      if (Clock::now() < due) {
        std::this_thread::sleep_for(
            std::min<Clock::duration>(due - Clock::now(), std::chrono::milliseconds(20)));
        continue;
      }
    }
    pollfd p{fd, POLLOUT, 0};
    if (::poll(&p, 1, 20) <= 0) continue;
    if (p.revents & (POLLERR | POLLHUP)) return false;
    const std::size_t n = std::min(piece, bytes.size() - sent);
    const ssize_t done = ::send(fd, bytes.data() + sent, n, MSG_NOSIGNAL);
    if (done <= 0) return false;
    sent += static_cast<std::size_t>(done);
  }
  return true;
}

void FaultServer::respond(int fd, int status, const std::string& reason, const std::string& headers,
                          const std::string& content) {
  sendAll(fd,
          "HTTP/1.1 " + std::to_string(status) + " " + reason +
              "\r\nContent-Type: text/plain\r\nContent-Length: " + std::to_string(content.size()) +
              "\r\nConnection: close\r\n" + headers + "\r\n" + content);
  closeNormally(fd);
}

bool FaultServer::bodyOf(const std::string& path, std::string& body) const {
  if (config_.root.empty()) {
    body = config_.body;
    return true;
  }
  const std::string file = path.substr(0, path.find_first_of("?#"));
  if (file.empty() || file[0] != '/' || file.find("..") != std::string::npos) return false;
  std::error_code error;
  if (!std::filesystem::is_regular_file(config_.root + file, error)) return false;
  std::ifstream in(config_.root + file, std::ios::binary);
  if (!in) return false;
  body.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return static_cast<bool>(in) || in.eof();
}

// 200 or 206 (honouring "bytes=a-" and "bytes=a-b"); after `cut` body bytes the connection
// ends as `end` says instead of finishing. A `rangeShift` makes the answer 206 whatever was
// asked, its Content-Range starting that many bytes later than the bytes sent.
void FaultServer::serve(int fd, const Request& request, const std::string& body, bool honourRange,
                        std::size_t cut, End end, std::size_t rangeShift) {
  std::size_t first = 0, last = body.empty() ? 0 : body.size() - 1;
  bool ranged = rangeShift > 0;
  if (honourRange && !request.range.empty()) {
    unsigned long long a = 0, b = 0;
    const int n = std::sscanf(request.range.c_str(), "bytes=%llu-%llu", &a, &b);
    if (n >= 1) {
      if (a >= body.size()) {
        respond(fd, 416, "Range Not Satisfiable",
                "Content-Range: bytes */" + std::to_string(body.size()) + "\r\n", "");
        return;
      }
      ranged = true;
      first = static_cast<std::size_t>(a);
      if (n == 2) last = std::min(last, static_cast<std::size_t>(b));
    }
  }
  const std::string content = body.empty() ? "" : body.substr(first, last - first + 1);
  std::string head = ranged ? "HTTP/1.1 206 Partial Content\r\n" : "HTTP/1.1 200 OK\r\n";
  head += "Content-Type: application/octet-stream\r\nContent-Length: " +
          std::to_string(content.size()) + "\r\nConnection: close\r\n";
  if (ranged)
    head += "Content-Range: bytes " + std::to_string(first + rangeShift) + "-" +
            std::to_string(last + rangeShift) + "/" + std::to_string(body.size() + rangeShift) +
            "\r\n";
  head += "\r\n";
  if (cut == kNoCut || end == End::finish) {
    sendAll(fd, head + content);
    closeNormally(fd);
    return;
  }
  sendAll(fd, head + content.substr(0, std::min(cut, content.size())));
  if (end == End::reset)
    closeWithReset(fd);
  else if (end == End::stall)
    stall(fd);
  else
    closeNormally(fd);
}

// Silence after what was sent: until the server is destroyed, or with
// Config::stallSeconds >= 0 until then or until the client closes; then a normal close.
void FaultServer::stall(int fd) {
  const bool bounded = config_.stallSeconds >= 0.0;
  const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(config_.stallSeconds));
  while (!stop_ && (!bounded || Clock::now() < until)) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 20) <= 0 || !bounded) continue;  // unbounded: wait for the end anyway
    char buf[1024];
    if (::recv(fd, buf, sizeof buf, 0) <= 0) break;  // the client gave up
  }
  ::close(fd);
}

void FaultServer::handle(int fd, int connection) {
  Request request;
  if (!readRequest(fd, request)) {
    ::close(fd);
    return;
  }
  const std::vector<Behaviour>& plan = config_.plan;
  Behaviour behaviour =
      plan.empty() ? Behaviour::serve : plan[static_cast<std::size_t>(connection) % plan.size()];
  if (behaviour == Behaviour::resetOnceThenServe && plan.size() > 1)
    behaviour = Behaviour::resetMidway;
  if (config_.verbose)
    std::fprintf(stderr, "gs_fault_server: connection %d: GET %s%s%s: %s\n", connection,
                 request.path.c_str(),
                 request.range.empty() ? "" : " Range: ", request.range.c_str(),
                 behaviourName(behaviour));
  std::string body;
  if (behaviour != Behaviour::redirectToFile && behaviour != Behaviour::notFound &&
      behaviour != Behaviour::serverError && !bodyOf(request.path, body))
    behaviour = Behaviour::notFound;
  const std::size_t cut = config_.cutAfter;
  switch (behaviour) {
    case Behaviour::serve:
      serve(fd, request, body, true, kNoCut, End::finish);
      break;
    case Behaviour::ignoreRanges:
      serve(fd, request, body, false, kNoCut, End::finish);
      break;
    case Behaviour::resetMidway:
      serve(fd, request, body, true, cut, End::reset);
      break;
    case Behaviour::resetOnceThenServe:
      serve(fd, request, body, true, connection == 0 ? cut : kNoCut, End::reset);
      break;
    case Behaviour::truncate:
      serve(fd, request, body, true, cut, End::fin);
      break;
    case Behaviour::wrongContentRange:
      serve(fd, request, body, true, kNoCut, End::finish, std::max<std::size_t>(cut, 1));
      break;
    case Behaviour::stall:
      serve(fd, request, body, true, cut, End::stall);
      break;
    case Behaviour::notFound:
      respond(fd, 404, "Not Found", "", "not found\n");
      break;
    case Behaviour::serverError:
      respond(fd, 500, "Internal Server Error", "", "server error\n");
      break;
    case Behaviour::wrongLengthShort:
      sendAll(fd,
              "HTTP/1.1 200 OK\r\nContent-Type: application/octet-stream\r\n"
              "Content-Length: " +
                  std::to_string(body.size() + kMissing) + "\r\nConnection: close\r\n\r\n" + body);
      closeNormally(fd);
      break;
    case Behaviour::redirect:
      if (request.path == "/target")
        serve(fd, request, body, true, kNoCut, End::finish);
      else
        respond(fd, 302, "Found", "Location: " + url("/target") + "\r\n", "moved\n");
      break;
    case Behaviour::redirectToFile:
      respond(fd, 302, "Found", "Location: file:///etc/passwd\r\n", "moved\n");
      break;
  }
}

// FIN, then wait (briefly) for the client to close, so that no unread byte turns the
// close into a reset.
void FaultServer::closeNormally(int fd) {
  ::shutdown(fd, SHUT_WR);
  const auto deadline = Clock::now() + std::chrono::milliseconds(500);
  while (!stop_ && Clock::now() < deadline) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 20) <= 0) continue;
    char buf[1024];
    if (::recv(fd, buf, sizeof buf, 0) <= 0) break;
  }
  ::close(fd);
}

// Waits until the client acknowledged every byte sent (so the reset cannot discard them),
// then closes with SO_LINGER 0: the kernel sends RST instead of FIN.
void FaultServer::closeWithReset(int fd) {
  const auto deadline = Clock::now() + std::chrono::seconds(2);
  int queued = 1;
  while (!stop_ && Clock::now() < deadline && ::ioctl(fd, SIOCOUTQ, &queued) == 0 && queued > 0)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const linger l{1, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_LINGER, &l, sizeof l);
  ::close(fd);
}

}  // namespace gs::test
