// Local files (a path or a file:// URL) read in chunks on a worker thread, so that the
// consumers see the same progressive delivery as over HTTP (and --max-rate can emulate a
// slow link on local files).
#include "buffered_transfer.hpp"

#include "base/text.hpp"
#include "base/url.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <thread>

namespace gs::net::detail {
namespace {

constexpr std::size_t kChunk = std::size_t{64} << 10;

// The local path of a path or file:// URL; false with `error` for a file URL naming
// another host.
bool localPath(const std::string& url, std::string& path, std::string& error) {
  constexpr std::size_t kPrefix = 7;  // "file://"
  if (!base::startsWithNoCase(url, "file://")) {
    path = url;
    return true;
  }
  const std::string rest = url.substr(kPrefix);
  const std::size_t slash = rest.find('/');
  const std::string host = base::toLower(rest.substr(0, slash));
  if (!host.empty() && host != "localhost") {
    error = url + ": file URLs naming another host ('" + host + "') are not supported";
    return false;
  }
  path = base::percentDecode(slash == std::string::npos ? std::string("/") : rest.substr(slash));
  return true;
}

class FileTransfer final : public BufferedTransfer {
 public:
  FileTransfer(FetchRequest request, std::string path)
      : BufferedTransfer(request.url), request_(std::move(request)), path_(std::move(path)) {
    thread_ = std::thread([this] { run(); });
  }
  ~FileTransfer() override {
    cancel();
    if (thread_.joinable()) thread_.join();
  }

 private:
  void run() {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(nullptr, &std::fclose);
    if (request_.budget && !request_.budget->startRequest()) {
      finish(TransferState::failed, budgetRequestsError(request_.url, *request_.budget));
      return;
    }
    f.reset(std::fopen(path_.c_str(), "rb"));
    if (!f) {
      finish(TransferState::failed, "cannot open '" + path_ + "': " + std::strerror(errno));
      return;
    }
    struct stat st {};
    std::int64_t size = -1;
    if (::fstat(fileno(f.get()), &st) == 0 && S_ISREG(st.st_mode)) size = st.st_size;
    if (size >= 0 && request_.offset > static_cast<std::uint64_t>(size)) {
      finish(TransferState::failed, "cannot read '" + path_ + "': offset " +
                                        std::to_string(request_.offset) + " is past its end (" +
                                        std::to_string(size) + " bytes)");
      return;
    }
    std::int64_t expected = -1;
    if (size >= 0) {
      std::uint64_t left = static_cast<std::uint64_t>(size) - request_.offset;
      if (request_.length > 0) left = std::min(left, request_.length);
      expected = static_cast<std::int64_t>(left);
    }
    update([&](TransferStatus& s) {
      s.resourceSize = size;
      s.expected = expected;
    });
    if (request_.offset > 0 &&
        ::fseeko(f.get(), static_cast<off_t>(request_.offset), SEEK_SET) != 0) {
      finish(TransferState::failed, "cannot seek in '" + path_ + "': " + std::strerror(errno));
      return;
    }
    copy(f.get());
  }

  void copy(std::FILE* f) {
    // A low rate gets small chunks (about 20 a second) so that delivery stays smooth.
    const double rate = request_.maxRate;
    std::size_t chunk = kChunk;
    if (rate > 0.0)
      chunk = static_cast<std::size_t>(std::clamp(rate / 20.0, 512.0, double{kChunk}));
    std::string buf(chunk, '\0');
    const auto start = Clock::now();
    std::uint64_t done = 0;
    for (;;) {
      if (cancelRequested()) return;
      std::size_t want = chunk;
      if (request_.length > 0) {
        if (done >= request_.length) break;
        want = static_cast<std::size_t>(std::min<std::uint64_t>(want, request_.length - done));
      }
      const std::size_t n = std::fread(buf.data(), 1, want, f);
      if (n == 0) {
        if (std::ferror(f)) {
          finish(TransferState::failed, "cannot read '" + path_ + "': " + std::strerror(errno));
          return;
        }
        break;
      }
      if (done + n > request_.maxBytes) {
        finish(TransferState::failed, request_.url + ": larger than the limit of " +
                                          std::to_string(request_.maxBytes) + " bytes");
        return;
      }
      if (request_.budget && !request_.budget->addBytes(n)) {
        finish(TransferState::failed, budgetBytesError(request_.url, *request_.budget));
        return;
      }
      deliver(buf.data(), n);
      done += n;
      // Hold the average: the next chunk leaves when `done` bytes are due at `rate`.
      if (!holdRate(start, done, rate)) return;
    }
    finish(TransferState::done);
  }

  const FetchRequest request_;
  const std::string path_;
  std::thread thread_;
};

}  // namespace

std::unique_ptr<Transfer> startFileTransfer(FetchRequest request) {
  if (!request.allowLocal)
    return failedTransfer(request.url, "local file '" + request.url +
                                           "' may not be read by content from the network");
  std::string path, error;
  if (!localPath(request.url, path, error)) return failedTransfer(request.url, error);
  return std::make_unique<FileTransfer>(std::move(request), std::move(path));
}

}  // namespace gs::net::detail
