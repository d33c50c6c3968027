// A tiny HTTP/1.1 server of the tests' own, to produce the failures a real server rarely
// shows on demand: ignored ranges, connections reset, truncated or stalled midway, wrong
// lengths and Content-Ranges, redirects, a slow drip. One connection at a time on a
// background thread, 127.0.0.1, a port the kernel picks (or a given one). It serves one
// body given in memory for any path, or the files of a folder (the stand-alone
// gs_fault_server of the soak test, tests/http/fault_server_main.cpp). POSIX sockets and
// the standard library only.
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
    stall,               // serve `cutAfter` body bytes, then silence until destroyed (or
                         // Config::stallSeconds), then close
    notFound,            // 404 Not Found
    serverError,         // 500 Internal Server Error
    wrongLengthShort,    // 200 whose Content-Length claims kMissing more bytes than sent
    redirect,            // 302 to "/target" on this server, which serves
    redirectToFile,      // 302 to file:///etc/passwd
    truncate,            // serve, but close normally (FIN) after `cutAfter` body bytes
    wrongContentRange,   // 206 whose Content-Range starts max(cutAfter, 1) bytes later
                         // than the bytes sent (which start where the request asked)
  };
  /// Everything a server can be told. The defaults are those of the first constructor.
  struct Config {
    /// Folder whose files are served (the request's path below it, without query; a
    /// missing file or a path with ".." gets 404). Empty: `body` for every path.
    std::string root;
    std::string body;
    /// Connection i (counted from 0) behaves as plan[i % plan.size()]; empty: serve.
    /// resetOnceThenServe in a plan acts as resetMidway.
    std::vector<Behaviour> plan;
    /// Body bytes sent before the fault of resetMidway, stall, truncate (and the shift of
    /// wrongContentRange).
    std::size_t cutAfter = 0;
    /// Bytes per second at most of every response (a slow drip, sent in pieces of about a
    /// twentieth of a second, 512 bytes at least); 0: as fast as the socket takes them.
    double bytesPerSecond = 0.0;
    /// How long a stall lasts before the connection is closed (it ends earlier when the
    /// client closes); negative: until the server is destroyed, whatever the client does.
    double stallSeconds = -1.0;
    /// TCP port on 127.0.0.1; 0: one the kernel picks.
    int port = 0;
    /// One line per request on stderr: connection, path, Range, behaviour.
    bool verbose = false;
  };
  /// A request as seen: its path and its Range header's value ("" when none).
  struct Request {
    std::string path;
    std::string range;
  };
  /// Bytes that Content-Length claims beyond the body in wrongLengthShort.
  static constexpr std::size_t kMissing = 100;

  /// The behaviour's name on gs_fault_server's command line ("serve", "reset", "stall",
  /// "truncate", "wrong-range", "ignore-ranges", "reset-once", "not-found",
  /// "server-error", "short", "redirect", "redirect-file").
  static const char* behaviourName(Behaviour behaviour);
  /// The behaviour named `name` (as behaviourName); false when none is.
  static bool behaviourFromName(const std::string& name, Behaviour& behaviour);

  /// Listens at once (ok() says whether it could) and serves on a background thread.
  FaultServer(std::string body, Behaviour behaviour, std::size_t cutAfter = 0);
  explicit FaultServer(Config config);
  /// Stops within about 50 ms, even while stalling, and joins the thread.
  ~FaultServer();
  FaultServer(const FaultServer&) = delete;
  FaultServer& operator=(const FaultServer&) = delete;

  bool ok() const { return listenFd_ >= 0; }
  /// The port listened on (0 when not ok()).
  int port() const { return port_; }
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
  /// The body of `path`: Config::body, or the file below Config::root (false: 404).
  bool bodyOf(const std::string& path, std::string& body) const;
  /// How the response ends after `cut` body bytes (all of them when kNoCut).
  enum class End { finish, reset, fin, stall };
  void serve(int fd, const Request& request, const std::string& body, bool honourRange,
             std::size_t cut, End end, std::size_t rangeShift = 0);
  void stall(int fd);
  void closeNormally(int fd);
  void closeWithReset(int fd);

  const Config config_;
  int listenFd_ = -1;
  int port_ = 0;
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;
  std::vector<Request> requests_;
  std::thread thread_;
};

}  // namespace gs::test
