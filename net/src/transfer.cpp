#include "net/transfer.hpp"

#include "buffered_transfer.hpp"

#include "base/url.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>

namespace gs::net {

bool FetchBudget::startRequest() {
  std::uint32_t n = requests_.load();
  while (n < maxRequests_) {
    if (requests_.compare_exchange_weak(n, n + 1)) return true;
  }
  return false;
}

bool FetchBudget::addBytes(std::uint64_t n) {
  return total_.fetch_add(n) + n <= maxTotalBytes_;
}

std::unique_ptr<Transfer> startTransfer(FetchRequest request) {
  if (base::isHttpUrl(request.url)) return detail::startHttpTransfer(std::move(request));
  // Only "scheme://..." names a scheme here; anything else is a local path.
  const std::size_t n = base::schemeLength(request.url);
  const std::string scheme =
      n > 0 && request.url.compare(n, 3, "://") == 0 ? base::schemeOf(request.url) : "";
  if (scheme.empty() || scheme == "file") return detail::startFileTransfer(std::move(request));
  return detail::failedTransfer(request.url, request.url + ": unsupported URL scheme '" + scheme +
                                                 "' (only http, https and file are read)");
}

namespace detail {

BufferedTransfer::BufferedTransfer(const std::string& url) : start_(Clock::now()), end_(start_) {
  status_.effectiveUrl = url;
}

std::size_t BufferedTransfer::take(std::string& out) {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::size_t n = pending_.size();
  out.append(pending_);
  pending_.clear();
  return n;
}

TransferStatus BufferedTransfer::status() const {
  std::lock_guard<std::mutex> lock(mutex_);
  TransferStatus s = status_;
  const Clock::time_point end = s.finished() ? end_ : Clock::now();
  const double seconds = std::chrono::duration<double>(end - start_).count();
  s.bytesPerSecond = seconds > 0.0 ? static_cast<double>(s.received) / seconds : 0.0;
  return s;
}

void BufferedTransfer::cancel() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    cancelled_.store(true);
    if (status_.state == TransferState::running) {
      status_.state = TransferState::cancelled;
      end_ = Clock::now();
    }
  }
  cv_.notify_all();
}

void BufferedTransfer::wait(double seconds) {
  std::unique_lock<std::mutex> lock(mutex_);
  cv_.wait_for(lock, std::chrono::duration<double>(std::max(seconds, 0.0)),
               [&] { return !pending_.empty() || status_.finished(); });
}

void BufferedTransfer::deliver(const char* data, std::size_t n) {
  if (n == 0) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (status_.finished()) return;
    pending_.append(data, n);
    status_.received += n;
  }
  cv_.notify_all();
}

void BufferedTransfer::finish(TransferState state, std::string error) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (status_.finished()) return;
    status_.state = state;
    status_.error = std::move(error);
    end_ = Clock::now();
  }
  cv_.notify_all();
}

bool BufferedTransfer::sleepUnlessCancelled(double seconds) {
  std::unique_lock<std::mutex> lock(mutex_);
  return !cv_.wait_for(lock, std::chrono::duration<double>(std::max(seconds, 0.0)),
                       [&] { return cancelled_.load(); });
}

bool BufferedTransfer::holdRate(Clock::time_point start, std::uint64_t done, double rate) {
  if (rate <= 0.0) return !cancelRequested();
  const double due = static_cast<double>(done) / rate;
  for (;;) {
    const double wait = due - std::chrono::duration<double>(Clock::now() - start).count();
    if (wait <= 0.0) return !cancelRequested();
    // In slices, so that no duration conversion overflows for absurdly low rates.
    if (!sleepUnlessCancelled(std::min(wait, 3600.0))) return false;
  }
}

namespace {

// No worker: ended before it began.
class FailedTransfer : public BufferedTransfer {
 public:
  FailedTransfer(const std::string& url, std::string error) : BufferedTransfer(url) {
    finish(TransferState::failed, std::move(error));
  }
};

}  // namespace

std::unique_ptr<Transfer> failedTransfer(const std::string& url, std::string error) {
  return std::make_unique<FailedTransfer>(url, std::move(error));
}

std::string budgetRequestsError(const std::string& url, const FetchBudget& budget) {
  return url + ": refused: the limit of " + std::to_string(budget.maxRequests()) +
         " requests per session was reached";
}

std::string budgetBytesError(const std::string& url, const FetchBudget& budget) {
  return url + ": refused: more than the limit of " + std::to_string(budget.maxTotalBytes()) +
         " bytes per session were fetched";
}

std::string formatSeconds(double seconds) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", seconds);
  return buf;
}

}  // namespace detail
}  // namespace gs::net
