#include "http/nginx_server.hpp"

#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>

namespace gs::test {
namespace {

/// nginx itself: GS_NGINX when set (tests of the missing-fixture rule point it elsewhere).
std::string nginxProgram() {
  return fixtureProgram("GS_NGINX", "/usr/sbin/nginx");
}

sockaddr_in loopback(int port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  return a;
}

// A port that was free a moment ago (the kernel's pick for port 0).
int freePort() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return 0;
  sockaddr_in a = loopback(0);
  int port = 0;
  socklen_t len = sizeof a;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) == 0)
    port = ntohs(a.sin_port);
  ::close(fd);
  return port;
}

bool accepts(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return false;
  sockaddr_in a = loopback(port);
  const bool ok = ::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  ::close(fd);
  return ok;
}

std::string readText(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string config(const std::filesystem::path& dir, int port) {
  const std::string d = dir.string();
  std::ostringstream c;
  c << "daemon off;\nmaster_process off;\nworker_processes 1;\n"
    << "pid " << d << "/nginx.pid;\n"
    << "error_log " << d << "/error.log warn;\n"
    << "events { worker_connections 64; }\n"
    << "http {\n"
    << "  types { text/html html; text/plain txt; model/vrml wrl; model/x-qnv qnv; }\n"
    << "  default_type application/octet-stream;\n"
    << "  log_format gs '$request_method $uri $status $body_bytes_sent \"$http_range\" "
       "\"$sent_http_content_encoding\"';\n"
    << "  access_log " << d << "/access.log gs;\n"
    << "  client_body_temp_path " << d << "/tmp/client_body;\n"
    << "  proxy_temp_path " << d << "/tmp/proxy;\n"
    << "  fastcgi_temp_path " << d << "/tmp/fastcgi;\n"
    << "  uwsgi_temp_path " << d << "/tmp/uwsgi;\n"
    << "  scgi_temp_path " << d << "/tmp/scgi;\n"
    << "  keepalive_timeout 5;\n"
    << "  server {\n"
    << "    listen 127.0.0.1:" << port << ";\n"
    << "    root " << d << "/root;\n"
    << "    location /gz/ {\n"
    << "      alias " << d << "/root/;\n"
    << "      gzip on;\n"
    << "      gzip_types text/plain model/vrml model/x-qnv application/octet-stream;\n"
    << "      gzip_min_length 1;\n"
    << "    }\n"
    << "  }\n"
    << "}\n";
  return c.str();
}

}  // namespace

NginxServer::NginxServer() {
  std::string why;
  const std::string nginx = nginxProgram();
  if (::access(nginx.c_str(), X_OK) != 0) {
    missingFixture("nginx: " + nginx + " is absent (install nginx-light)");
    return;
  }
  std::string tmpl = (std::filesystem::temp_directory_path() / "gs-nginx-XXXXXX").string();
  if (!::mkdtemp(tmpl.data())) {
    missingFixture("nginx: cannot make a temporary folder for it");
    return;
  }
  dir_ = tmpl;
  std::filesystem::create_directories(dir_ / "root");
  std::filesystem::create_directories(dir_ / "tmp");
  for (int tries = 0; tries < 3; ++tries) {
    if (start(why)) return;
  }
  missingFixture("nginx did not start: " + why);
}

NginxServer::~NginxServer() {
  stop();
  if (!dir_.empty()) {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
}

bool NginxServer::start(std::string& why) {
  port_ = freePort();
  if (port_ == 0) {
    why = "no free port";
    return false;
  }
  const std::filesystem::path conf = dir_ / "nginx.conf";
  {
    std::ofstream out(conf);
    out << config(dir_, port_);
  }
  // Everything the child needs is built before fork() (only exec-safe calls after it).
  const std::string prefix = dir_.string() + "/", confText = conf.string(),
                    errorLog = (dir_ / "error.log").string(),
                    output = (dir_ / "output.log").string();
  std::vector<char*> argv = {const_cast<char*>("nginx"),          const_cast<char*>("-p"),
                             const_cast<char*>(prefix.c_str()),   const_cast<char*>("-c"),
                             const_cast<char*>(confText.c_str()), const_cast<char*>("-e"),
                             const_cast<char*>(errorLog.c_str()), nullptr};
  const std::string program = nginxProgram();
  const pid_t pid = ::fork();
  if (pid < 0) {
    why = "fork failed";
    return false;
  }
  if (pid == 0) {
    const int fd = ::open(output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      ::dup2(fd, 1);
      ::dup2(fd, 2);
      ::close(fd);
    }
    ::execv(program.c_str(), argv.data());
    ::_exit(127);
  }
  pid_ = pid;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (std::chrono::steady_clock::now() < deadline) {
    int st = 0;
    if (::waitpid(pid_, &st, WNOHANG) == pid_) {
      pid_ = -1;
      why = "it exited: " + readText(dir_ / "output.log") + readText(dir_ / "error.log");
      return false;
    }
    if (accepts(port_)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  why = "port " + std::to_string(port_) + " did not accept connections within 5 s";
  stop();
  return false;
}

void NginxServer::stop() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(3);
  int st = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if (::waitpid(pid_, &st, WNOHANG) == pid_) {
      pid_ = -1;
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(pid_, SIGKILL);
  ::waitpid(pid_, &st, 0);
  pid_ = -1;
}

std::string NginxServer::url(const std::string& path) const {
  return "http://127.0.0.1:" + std::to_string(port_) + path;
}

std::vector<std::string> NginxServer::accessLog(std::size_t minLines) const {
  std::vector<std::string> lines;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  for (;;) {
    lines.clear();
    std::istringstream in(readText(dir_ / "access.log"));
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    if (lines.size() >= minLines || std::chrono::steady_clock::now() > deadline) return lines;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

void NginxServer::writeFile(const std::string& relative, const std::string& bytes) const {
  const std::filesystem::path p = root() / relative;
  std::filesystem::create_directories(p.parent_path());
  std::ofstream out(p, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::uint64_t NginxServer::bodyBytes(const std::vector<std::string>& accessLog) {
  std::uint64_t sent = 0;
  for (const std::string& line : accessLog) {
    std::istringstream fields(line);
    std::string method, uri, status;
    std::uint64_t n = 0;
    fields >> method >> uri >> status >> n;
    sent += n;
  }
  return sent;
}

}  // namespace gs::test
