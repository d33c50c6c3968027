// The real window under Xvfb: it opens, draws a few frames through GLFW + ImGui and the
// same SceneRenderer as --snapshot, and closes cleanly. Skips when Xvfb is absent.
#include "process.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

namespace {

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

}  // namespace

TEST_CASE("the window opens a world, draws frames and closes", "[app][window]") {
  Xvfb x;
  if (!x.running()) {
    WARN("SKIPPED: /usr/bin/Xvfb is absent (install xvfb)");
    return;
  }
  const auto world = gs::test::sourceDir() / "assets/worlds/welcome.wrl";
  auto r = gs::test::runGhostspace({"--frames", "5", "--size", "320x240", world.string()},
                                   {"DISPLAY=" + x.display()});
  INFO(r.err);
  CHECK(r.exitCode == 0);
}

TEST_CASE("without a display the window fails with a clear message", "[app][window]") {
  auto r = gs::test::runGhostspace({"--frames", "1", "x.wrl"}, {"DISPLAY=:7777"});
  CHECK(r.exitCode == 1);
  CHECK(r.err.find("window") != std::string::npos);
}

TEST_CASE("a load error is reported in the window, which keeps running", "[app][window]") {
  Xvfb x;
  if (!x.running()) {
    WARN("SKIPPED: /usr/bin/Xvfb is absent (install xvfb)");
    return;
  }
  auto r = gs::test::runGhostspace({"--frames", "3", "/nonexistent/world.wrl"},
                                   {"DISPLAY=" + x.display()});
  CHECK(r.exitCode == 0);
}
