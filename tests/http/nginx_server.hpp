// A real HTTP server for tests: nginx (Debian's nginx-light) in the foreground on
// 127.0.0.1 and a free port, serving a temporary root folder that the test fills. Self-
// contained (POSIX, the standard library, Catch2 and test_support) so that any test suite can
// compile this file in.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace gs::test {

/// Starts nginx on construction and stops it (SIGTERM, then SIGKILL) on destruction.
/// Everything it writes (pid, logs, temp folders, the served root) lives in a fresh
/// temporary folder that is removed afterwards.
///
/// Served: root() at "/" (no Content-Encoding); the same files under "/gz/" (an alias of
/// the root) with gzip Content-Encoding for .wrl, .qnv, .txt and unknown types
/// (gzip_min_length 1) when the client accepts it.
/// Types: .wrl model/vrml, .qnv model/x-qnv, .txt text/plain, .html text/html, others
/// application/octet-stream. Range requests work on every static file (206).
class NginxServer {
 public:
  /// Starts nginx (/usr/sbin/nginx, or $GS_NGINX) and waits (up to about 5 s) until its
  /// port accepts connections. When nginx is missing or does not start, ok() is false and
  /// test::missingFixture() names nginx and why (a failure under CI, else a ctest skip);
  /// tests then return early.
  NginxServer();
  ~NginxServer();
  NginxServer(const NginxServer&) = delete;
  NginxServer& operator=(const NginxServer&) = delete;

  /// Whether nginx runs (if not, see the missing-fixture report it left).
  bool ok() const { return pid_ > 0; }
  /// The folder served at "/": write files there before fetching them.
  std::filesystem::path root() const { return dir_ / "root"; }
  /// "http://127.0.0.1:PORT" + `path` (`path` starts with '/').
  std::string url(const std::string& path) const;
  /// The TCP port nginx listens on.
  int port() const { return port_; }
  /// The access log so far, one line per request:
  /// `METHOD URI STATUS BODY_BYTES_SENT "RANGE" "CONTENT_ENCODING"` (an empty header is
  /// "-"). nginx writes a line just after a response ends, so this waits (up to 2 s)
  /// until there are at least `minLines` lines.
  std::vector<std::string> accessLog(std::size_t minLines = 0) const;
  /// The body bytes sent over all requests of `accessLog()` lines (their 4th field).
  static std::uint64_t bodyBytes(const std::vector<std::string>& accessLog);
  /// Writes `bytes` to root()/`relative` (folders created as needed).
  void writeFile(const std::string& relative, const std::string& bytes) const;

 private:
  bool start(std::string& why);
  void stop();

  std::filesystem::path dir_;
  pid_t pid_ = -1;
  int port_ = 0;
};

}  // namespace gs::test
