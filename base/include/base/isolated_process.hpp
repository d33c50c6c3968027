// Work on untrusted bytes run in a child process with bounded memory and time, for the
// libraries that allocate what a file asks before checking it (OpenVDB: issue 42) and
// cannot be bounded from outside. The child is a fork() of the caller: it sees the
// caller's memory as it was, runs one function, sends its results back through a pipe
// as frames, and ends with _exit (no atexit handlers, no leak report). Its standard output
// and error go to /dev/null (GS_ISOLATED_STDERR=1 keeps them), and a fatal signal ends it
// without the handlers the caller installed. A child that
// runs out of memory, crashes, or sends nothing for too long ends the work with an
// IsolationError; the caller's process is never at risk.
//
// Linux (fork, pipe, setrlimit RLIMIT_AS, poll, waitpid, PR_SET_PDEATHSIG: the child dies
// with the caller). The child must not rely on other threads of the caller (only the
// forking thread exists in it): it may allocate, read files and start threads of its own.
// glibc's malloc is safe across fork; AddressSanitizer's allocator in clang/gcc 14 and
// earlier is not while another thread allocates (the child may wait forever on its lock,
// until the idle time-out stops it), which is why the fuzz targets that fork run without
// libFuzzer's RSS thread (tests/fuzz/run.sh).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace gs::base {

/// The child failed: its own error text (what the work threw), or what happened to it
/// ("ran out of its 2048 MiB of memory", "ended by signal 11", "sent nothing for 60 s").
class IsolationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct IsolationLimits {
  /// Address space the child may add to what it inherits (RLIMIT_AS = the caller's
  /// virtual size + this), bytes. Allocations past it fail in the child (std::bad_alloc).
  std::uint64_t memoryBytes = std::uint64_t{2} << 30;
  /// Seconds the caller waits for the next frame before killing the child (> 0).
  int idleSeconds = 120;
};

/// The child's end: frames written in order, each one message the caller receives whole.
class FrameWriter {
 public:
  explicit FrameWriter(int fd) : fd_(fd) {}
  /// Sends one frame of `bytes` (any size up to 2^40). Blocks while the pipe is full (the
  /// caller has not read yet). Throws std::runtime_error when the caller has gone.
  void write(std::string_view bytes);

 private:
  int fd_;
};

/// One child process and the frames it sends. Not copyable; the destructor kills the child
/// if it still runs and reaps it.
class IsolatedProcess {
 public:
  /// Forks a child that runs `work(writer)` under `limits` and then exits. What `work`
  /// throws (std::exception) reaches the caller as an IsolationError with its what()
  /// text, after the frames it sent before. Throws IsolationError when fork or pipe fails.
  IsolatedProcess(const std::function<void(FrameWriter&)>& work, IsolationLimits limits);
  ~IsolatedProcess();
  IsolatedProcess(const IsolatedProcess&) = delete;
  IsolatedProcess& operator=(const IsolatedProcess&) = delete;

  /// The next frame, at most `maxBytes` long. Throws IsolationError with the child's error
  /// text, "the reader ended without an answer" when it exited without another frame,
  /// "...ran out of its N MiB of memory" / "...ended by signal N" / "...sent nothing for
  /// N s" (the child is killed), or "...sent a frame of N bytes, more than M" when a frame
  /// is larger than maxBytes.
  std::string next(std::uint64_t maxBytes);

 private:
  [[noreturn]] void fail(const std::string& why);
  /// Closes the pipe and waits for the child (killing it first when `kill`); its wait
  /// status, or -1 when there was none to wait for.
  int reap(bool kill);
  void readExactly(char* dst, std::size_t n);

  int fd_ = -1;
  int pid_ = -1;
  IsolationLimits limits_;
};

/// The memory budget for a child reading `fileBytes` of input: 1 GiB plus 16 times the
/// input, at most three quarters of the machine's physical memory (and at least 1 GiB).
std::uint64_t isolationMemoryFor(std::uint64_t fileBytes);

}  // namespace gs::base
