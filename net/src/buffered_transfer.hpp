// Private to net/: the part of a Transfer that both implementations share. A worker
// thread delivers bytes into a pending buffer and updates the status under one mutex;
// the consumer takes them. The derived class owns the worker thread and must cancel and
// join it in its own destructor (before this base is destroyed).
#pragma once

#include "net/transfer.hpp"

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>

namespace gs::net::detail {

class BufferedTransfer : public Transfer {
 public:
  /// `url` is the request's URL as given; it becomes status().effectiveUrl until the
  /// worker says otherwise.
  explicit BufferedTransfer(const std::string& url);
  ~BufferedTransfer() override = default;

  std::size_t take(std::string& out) override;
  TransferStatus status() const override;
  void cancel() override;
  void wait(double seconds) override;

 protected:
  using Clock = std::chrono::steady_clock;

  /// Worker side: appends `n` bytes to what take() hands over and counts them in
  /// status().received. Dropped silently once the transfer ended (e.g. cancelled).
  void deliver(const char* data, std::size_t n);
  /// Worker side: ends the transfer with `state` (done or failed) and `error`; does
  /// nothing when it already ended (a cancel() wins over a late failure).
  void finish(TransferState state, std::string error = {});
  /// Worker side: runs `f(TransferStatus&)` under the lock (to set expected, httpStatus...).
  template <class F>
  void update(F&& f) {
    std::lock_guard<std::mutex> lock(mutex_);
    f(status_);
  }
  /// Whether cancel() was called (cheap; safe from any thread).
  bool cancelRequested() const { return cancelled_.load(); }
  /// Sleeps `seconds` (fractional), waking early on cancel(); returns false if cancelled.
  bool sleepUnlessCancelled(double seconds);
  /// Sleeps until `done` bytes are due at `rate` bytes per second counted from `start`
  /// (at once when rate <= 0); returns false if cancelled.
  bool holdRate(Clock::time_point start, std::uint64_t done, double rate);

 private:
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::string pending_;
  TransferStatus status_;
  std::atomic<bool> cancelled_{false};
  const Clock::time_point start_;
  Clock::time_point end_;
};

/// A transfer that has already failed with `error` (bad scheme, refused, ...).
std::unique_ptr<Transfer> failedTransfer(const std::string& url, std::string error);

/// Local file or file:// URL (file_transfer.cpp). Checks allowLocal itself.
std::unique_ptr<Transfer> startFileTransfer(FetchRequest request);
/// http:// or https:// URL through libcurl (http_transfer.cpp).
std::unique_ptr<Transfer> startHttpTransfer(FetchRequest request);

/// Messages for a request refused by a FetchBudget, naming `url` and the limit.
std::string budgetRequestsError(const std::string& url, const FetchBudget& budget);
std::string budgetBytesError(const std::string& url, const FetchBudget& budget);

/// "N" for whole numbers of seconds, else "N.N": for messages.
std::string formatSeconds(double seconds);

}  // namespace gs::net::detail
