// A tiny HTTP/1.1 server of the tests' own, to produce the failures a real server rarely
// shows on demand: ignored ranges, connections reset or stalled midway, wrong lengths,
// redirects. One connection at a time on a background thread, 127.0.0.1, a port the
// kernel picks. POSIX sockets and the standard library only.
#pragma once

#include <atomic>
#include <cstddef>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace gs::test {

class FaultServer {
 public:
  /// What every request (any path) gets. "Serve" means: 200 with the whole body, or for
  /// "Range: bytes=a-" / "bytes=a-b" 206 with Content-Range (416 past the end).
  enum class Behaviour {
    serve,               // serve normally
    ignoreRanges,        // always 200 with the whole body
    resetMidway,         // serve, but reset (RST) the connection after `cutAfter` body bytes
    resetOnceThenServe,  // the first connection as resetMidway, later ones serve
    stall,               // headers and `cutAfter` body bytes, then silence until destroyed
    notFound,            // 404 Not Found
    serverError,         // 500 Internal Server Error
    wrongLengthShort,    // 200 whose Content-Length claims kMissing more bytes than sent
    redirect,            // 302 to "/target" on this server, which serves
    redirectToFile,      // 302 to file:///etc/passwd
  };
  /// A request as seen: its path and its Range header's value ("" when none).
  struct Request {
    std::string path;
    std::string range;
  };
  /// Bytes that Content-Length claims beyond the body in wrongLengthShort.
  static constexpr std::size_t kMissing = 100;

  /// Listens at once (ok() says whether it could) and serves on a background thread.
  FaultServer(std::string body, Behaviour behaviour, std::size_t cutAfter = 0);
  /// Stops within about 50 ms, even while stalling, and joins the thread.
  ~FaultServer();
  FaultServer(const FaultServer&) = delete;
  FaultServer& operator=(const FaultServer&) = delete;

  bool ok() const { return listenFd_ >= 0; }
  /// "http://127.0.0.1:PORT" + `path`.
  std::string url(const std::string& path = "/data.bin") const;
  /// The requests received so far, in order (redirected ones included).
  std::vector<Request> requests() const;

 private:
  void loop();
  void handle(int fd, int connection);
  bool readRequest(int fd, Request& request);
  bool sendAll(int fd, const std::string& bytes);
  void respond(int fd, int status, const std::string& reason, const std::string& headers,
               const std::string& content);
  void serve(int fd, const Request& request, bool honourRange, std::size_t cut);
  void closeNormally(int fd);
  void closeWithReset(int fd);

  const std::string body_;
  const Behaviour behaviour_;
  const std::size_t cutAfter_;
  int listenFd_ = -1;
  int port_ = 0;
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;
  std::vector<Request> requests_;
  std::thread thread_;
};

}  // namespace gs::test
