// An Xvfb server for window tests (test_window.cpp, test_window_navigation.cpp).
#pragma once

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

namespace gs::test {

/// An Xvfb server on a private display number for the life of the object.
class Xvfb {
 public:
  Xvfb() {
    if (!std::filesystem::exists("/usr/bin/Xvfb")) return;
    display_ = ":" + std::to_string(90 + ::getpid() % 800);
    pid_ = ::fork();
    if (pid_ == 0) {
      ::execl("/usr/bin/Xvfb", "Xvfb", display_.c_str(), "-screen", "0", "640x480x24", "-nolisten",
              "tcp", static_cast<char*>(nullptr));
      ::_exit(127);
    }
    // Wait for the server's socket.
    const std::string socket = "/tmp/.X11-unix/X" + display_.substr(1);
    for (int i = 0; i < 100 && !std::filesystem::exists(socket); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ~Xvfb() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  Xvfb(const Xvfb&) = delete;
  Xvfb& operator=(const Xvfb&) = delete;
  bool running() const { return pid_ > 0; }
  const std::string& display() const { return display_; }

 private:
  pid_t pid_ = -1;
  std::string display_;
};

}  // namespace gs::test
