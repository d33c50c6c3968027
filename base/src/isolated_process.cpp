// A child process per piece of untrusted work (base/isolated_process.hpp).
#include "base/isolated_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <new>

namespace gs::base {

namespace {

constexpr char kData = 'D';
constexpr char kError = 'E';
constexpr std::size_t kHeader = 9;  // kind, then the length as 8 little-endian bytes

// The process's current virtual size (bytes), 0 when /proc does not say.
std::uint64_t virtualSize() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  if (!(statm >> pages)) return 0;
  return pages * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
}

void writeAll(int fd, const char* p, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) throw std::runtime_error("the reader's caller has gone");
    p += w;
    n -= static_cast<std::size_t>(w);
  }
}

void writeFrame(int fd, char kind, std::string_view bytes) {
  char header[kHeader];
  header[0] = kind;
  std::uint64_t n = bytes.size();
  for (int i = 0; i < 8; ++i) header[1 + i] = static_cast<char>((n >> (8 * i)) & 0xff);
  writeAll(fd, header, kHeader);
  writeAll(fd, bytes.data(), bytes.size());
}

[[noreturn]] void runChild(int fd, const std::function<void(FrameWriter&)>& work,
                           const IsolationLimits& limits, std::uint64_t inherited, pid_t parent) {
  // The child ends with the caller, even one that ends without its destructors (a
  // fuzzer's time-out, a crash).
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(1);
  ::signal(SIGPIPE, SIG_IGN);
  // A crash ends the child, which the caller reports: not the handlers the caller's
  // process installed (a test framework's, a sanitizer's), which would report it as the
  // caller's own.
  for (int s : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTRAP}) ::signal(s, SIG_DFL);
  // What the library prints ("Error allocating memory!") is not the user's business; the
  // error comes back as a frame. GS_ISOLATED_STDERR=1 keeps it, for debugging.
  if (const char* keep = std::getenv("GS_ISOLATED_STDERR"); !keep || std::string(keep) != "1") {
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null >= 0) {
      ::dup2(null, 1);
      ::dup2(null, 2);
      ::close(null);
    }
  }
  if (inherited > 0) {
    rlimit lim{};
    lim.rlim_cur = lim.rlim_max = static_cast<rlim_t>(inherited + limits.memoryBytes);
    ::setrlimit(RLIMIT_AS, &lim);
  }
  try {
    FrameWriter writer(fd);
    work(writer);
  } catch (const std::bad_alloc&) {
    try {
      writeFrame(fd, kError,
                 "ran out of its " + std::to_string(limits.memoryBytes >> 20) + " MiB of memory");
    } catch (...) {
    }
  } catch (const std::exception& e) {
    try {
      writeFrame(fd, kError, e.what());
    } catch (...) {
    }
  } catch (...) {
    try {
      writeFrame(fd, kError, "failed with an unknown exception");
    } catch (...) {
    }
  }
  ::_exit(0);
}

}  // namespace

void FrameWriter::write(std::string_view bytes) {
  writeFrame(fd_, kData, bytes);
}

IsolatedProcess::IsolatedProcess(const std::function<void(FrameWriter&)>& work,
                                 IsolationLimits limits)
    : limits_(limits) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw IsolationError(std::string("cannot start the reader process: pipe: ") +
                         std::strerror(errno));
  const std::uint64_t inherited = virtualSize();
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int err = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    throw IsolationError(std::string("cannot start the reader process: fork: ") +
                         std::strerror(err));
  }
  if (pid == 0) {
    ::close(fds[0]);
    runChild(fds[1], work, limits, inherited, parent);
  }
  ::close(fds[1]);
  fd_ = fds[0];
  pid_ = pid;
}

IsolatedProcess::~IsolatedProcess() {
  (void)reap(true);
}

int IsolatedProcess::reap(bool kill) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (pid_ <= 0) return -1;
  if (kill) ::kill(pid_, SIGKILL);
  int status = 0;
  pid_t w;
  while ((w = ::waitpid(pid_, &status, 0)) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  return w > 0 ? status : -1;
}

void IsolatedProcess::fail(const std::string& why) {
  (void)reap(true);
  throw IsolationError(why);
}

void IsolatedProcess::readExactly(char* dst, std::size_t n) {
  while (n > 0) {
    pollfd p{fd_, POLLIN, 0};
    const int ready = ::poll(&p, 1, limits_.idleSeconds * 1000);
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0)
      fail("the reader sent nothing for " + std::to_string(limits_.idleSeconds) +
           " s and was stopped");
    const ssize_t r = ::read(fd_, dst, n);
    if (r < 0 && errno == EINTR) continue;
    if (r > 0) {
      dst += r;
      n -= static_cast<std::size_t>(r);
      continue;
    }
    // The child closed its end: it exited or died. Say how.
    const int status = reap(false);
    if (status >= 0 && WIFSIGNALED(status))
      throw IsolationError("the reader ended by signal " + std::to_string(WTERMSIG(status)) + " (" +
                           strsignal(WTERMSIG(status)) + ")");
    throw IsolationError("the reader ended without an answer");
  }
}

std::string IsolatedProcess::next(std::uint64_t maxBytes) {
  if (fd_ < 0) throw IsolationError("the reader has ended");
  char header[kHeader];
  readExactly(header, kHeader);
  std::uint64_t n = 0;
  for (int i = 0; i < 8; ++i)
    n |= std::uint64_t{static_cast<unsigned char>(header[1 + i])} << (8 * i);
  const bool error = header[0] == kError;
  const std::uint64_t cap = error ? std::uint64_t{4096} : maxBytes;
  if (n > cap || (header[0] != kData && !error))
    fail("the reader sent a frame of " + std::to_string(n) + " bytes, more than " +
         std::to_string(cap));
  std::string bytes(static_cast<std::size_t>(n), '\0');
  readExactly(bytes.data(), bytes.size());
  if (error) fail(bytes);
  return bytes;
}

std::uint64_t isolationMemoryFor(std::uint64_t fileBytes) {
  const std::uint64_t gib = std::uint64_t{1} << 30;
  std::uint64_t want = gib + std::min(fileBytes, std::uint64_t{1} << 40) * 16;
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
  if (pages > 0 && pageSize > 0) {
    const std::uint64_t physical =
        static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(pageSize);
    want = std::min(want, physical / 4 * 3);
  }
  return std::max(want, gib);
}

}  // namespace gs::base
