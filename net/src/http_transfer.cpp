// http:// and https:// through one libcurl easy handle on a worker thread: redirects to
// http(s) only, gzip/deflate decoding when the whole resource is asked for, range
// requests (and servers that ignore them), stall detection, rate limiting, and resuming
// a transfer the network cut with a Range from the first missing byte.
#include "buffered_transfer.hpp"
#include "http_response.hpp"

#include <curl/curl.h>

#include "base/text.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <thread>

namespace gs::net::detail {
namespace {

std::once_flag curlInitOnce;

// Network failures after which asking for the rest can work.
bool resumable(CURLcode rc) {
  return rc == CURLE_PARTIAL_FILE || rc == CURLE_RECV_ERROR || rc == CURLE_SEND_ERROR ||
         rc == CURLE_GOT_NOTHING || rc == CURLE_OPERATION_TIMEDOUT || rc == CURLE_HTTP2 ||
         rc == CURLE_HTTP2_STREAM;
}

class HttpTransfer final : public BufferedTransfer {
 public:
  explicit HttpTransfer(FetchRequest request)
      : BufferedTransfer(request.url), request_(std::move(request)) {
    std::call_once(curlInitOnce, [] { curl_global_init(CURL_GLOBAL_DEFAULT); });
    multi_ = curl_multi_init();
    thread_ = std::thread([this] { run(); });
  }
  ~HttpTransfer() override {
    cancel();
    if (thread_.joinable()) thread_.join();
    if (multi_) curl_multi_cleanup(multi_);
  }
  /// Also wakes the worker from its wait for the network, so that it ends at once.
  void cancel() override {
    BufferedTransfer::cancel();
    if (multi_) curl_multi_wakeup(multi_);
  }

 private:
  // Why a callback stopped the transfer (curl then reports a write or callback error).
  enum class Stop { none, lengthReached, failed };

  // What one request (perform(), redirects included) saw so far.
  struct Attempt {
    std::uint64_t from = 0;  // first byte of the resource asked for
    bool ranged = false;     // sent a Range header
    bool connected = false;  // the stall clock runs only once connected
    bool decided = false;    // the final response's headers were checked
    ResponseHead head;       // of the last response (redirects and 1xx replace it)
    std::uint64_t drop = 0;  // bytes still to drop before delivering (range ignored)
    Clock::time_point lastData;
  };

  void run();
  CURLcode perform(CURL* h);
  void setOptions(CURL* h);
  bool decide(CURL* h);
  void fail(std::string message) {
    stop_ = Stop::failed;
    stopMessage_ = std::move(message);
  }
  bool pace(const char* p, std::size_t len);
  std::string networkError(CURLcode rc) const;
  std::string afterBytes() const;

  static std::size_t onWrite(char* p, std::size_t size, std::size_t n, void* self);
  static std::size_t onHeader(char* p, std::size_t size, std::size_t n, void* self);
  static int onProgress(void* self, curl_off_t, curl_off_t, curl_off_t, curl_off_t);
  static int onPrereq(void* self, char*, char*, int, int);

  const FetchRequest request_;
  CURLM* multi_ = nullptr;  // curl_multi_wakeup() is the one call made from other threads
  std::thread thread_;
  // Worker thread only:
  CURL* handle_ = nullptr;
  Attempt attempt_;
  std::uint64_t done_ = 0;  // bytes delivered, relative to request_.offset
  std::int64_t expected_ = -1;
  Clock::time_point start_ = Clock::now();
  int resumes_ = 0;
  Stop stop_ = Stop::none;
  std::string stopMessage_;
  char errorBuffer_[CURL_ERROR_SIZE] = {};
};

void HttpTransfer::setOptions(CURL* h) {
  curl_easy_setopt(h, CURLOPT_URL, request_.url.c_str());
  curl_easy_setopt(h, CURLOPT_NOSIGNAL, 1L);
  curl_easy_setopt(h, CURLOPT_PROTOCOLS_STR, "http,https");
  curl_easy_setopt(h, CURLOPT_FOLLOWLOCATION, 1L);
  curl_easy_setopt(h, CURLOPT_MAXREDIRS, request_.maxRedirects);
  curl_easy_setopt(h, CURLOPT_REDIR_PROTOCOLS_STR, "http,https");
  curl_easy_setopt(
      h, CURLOPT_CONNECTTIMEOUT_MS,
      static_cast<long>(std::clamp(std::ceil(request_.connectTimeout * 1000.0), 1.0, 1e9)));
  curl_easy_setopt(h, CURLOPT_USERAGENT, "GhostSpace");
  curl_easy_setopt(h, CURLOPT_ERRORBUFFER, errorBuffer_);
  curl_easy_setopt(h, CURLOPT_WRITEFUNCTION, &HttpTransfer::onWrite);
  curl_easy_setopt(h, CURLOPT_WRITEDATA, this);
  curl_easy_setopt(h, CURLOPT_HEADERFUNCTION, &HttpTransfer::onHeader);
  curl_easy_setopt(h, CURLOPT_HEADERDATA, this);
  curl_easy_setopt(h, CURLOPT_XFERINFOFUNCTION, &HttpTransfer::onProgress);
  curl_easy_setopt(h, CURLOPT_XFERINFODATA, this);
  curl_easy_setopt(h, CURLOPT_NOPROGRESS, 0L);
  curl_easy_setopt(h, CURLOPT_PREREQFUNCTION, &HttpTransfer::onPrereq);
  curl_easy_setopt(h, CURLOPT_PREREQDATA, this);
  if (request_.maxRate > 0.0) {
    const double rate = std::clamp(std::ceil(request_.maxRate), 1.0, 1e15);
    curl_easy_setopt(h, CURLOPT_MAX_RECV_SPEED_LARGE, static_cast<curl_off_t>(rate));
    // Small reads at low rates, so that delivery is smooth and the pauses curl makes to
    // hold the rate stay far below the stall timeout.
    curl_easy_setopt(h, CURLOPT_BUFFERSIZE,
                     static_cast<long>(std::clamp(rate / 20.0, 1024.0, 65536.0)));
  }
}

void HttpTransfer::run() {
  std::unique_ptr<CURL, void (*)(CURL*)> h(curl_easy_init(), &curl_easy_cleanup);
  if (!h || !multi_) {
    finish(TransferState::failed, request_.url + ": cannot start libcurl");
    return;
  }
  handle_ = h.get();
  setOptions(h.get());
  for (;;) {
    if (request_.budget && !request_.budget->startRequest()) {
      finish(TransferState::failed, budgetRequestsError(request_.url, *request_.budget));
      return;
    }
    attempt_ = Attempt{};
    attempt_.from = request_.offset + done_;
    attempt_.ranged = attempt_.from > 0 || request_.length > 0;
    attempt_.lastData = Clock::now();
    std::string range;
    if (attempt_.ranged) {
      range = std::to_string(attempt_.from) + "-";
      if (request_.length > 0) range += std::to_string(request_.offset + request_.length - 1);
    }
    // A range counts bytes of the identity encoding: ask for no content coding then.
    curl_easy_setopt(h.get(), CURLOPT_RANGE, attempt_.ranged ? range.c_str() : nullptr);
    curl_easy_setopt(h.get(), CURLOPT_ACCEPT_ENCODING, attempt_.ranged ? nullptr : "");
    errorBuffer_[0] = '\0';
    const std::uint64_t before = done_;
    const CURLcode rc = perform(h.get());

    char* effective = nullptr;
    if (curl_easy_getinfo(h.get(), CURLINFO_EFFECTIVE_URL, &effective) == CURLE_OK && effective)
      update([&](TransferStatus& s) { s.effectiveUrl = effective; });
    if (cancelRequested()) return;
    if (stop_ == Stop::lengthReached) {
      finish(TransferState::done);
      return;
    }
    if (stop_ == Stop::failed) {
      finish(TransferState::failed, stopMessage_);
      return;
    }
    if (rc == CURLE_OK) {
      // No body arrived (the decision is made on its first byte): check the status now.
      if (!attempt_.decided && !decide(h.get())) {
        finish(TransferState::failed, stopMessage_);
        return;
      }
      finish(TransferState::done);
      return;
    }
    if (resumable(rc) && done_ > before && resumes_ < request_.maxResumes) {
      ++resumes_;
      update([&](TransferStatus& s) { s.resumes = resumes_; });
      continue;
    }
    finish(TransferState::failed, networkError(rc));
    return;
  }
}

// curl_easy_perform() through the multi interface, to wake up on cancel() at once and to
// check for a stall every 100 ms whatever the network does.
CURLcode HttpTransfer::perform(CURL* h) {
  if (curl_multi_add_handle(multi_, h) != CURLM_OK) return CURLE_FAILED_INIT;
  CURLcode rc = CURLE_ABORTED_BY_CALLBACK;
  const double stall = request_.stallTimeout;
  for (;;) {
    int running = 0;
    if (curl_multi_perform(multi_, &running) != CURLM_OK) {
      rc = CURLE_FAILED_INIT;
      break;
    }
    if (running == 0) {
      int queued = 0;
      while (const CURLMsg* m = curl_multi_info_read(multi_, &queued))
        if (m->msg == CURLMSG_DONE && m->easy_handle == h) rc = m->data.result;
      break;
    }
    if (cancelRequested() || stop_ != Stop::none) break;
    if (attempt_.connected && stall > 0.0 &&
        std::chrono::duration<double>(Clock::now() - attempt_.lastData).count() > stall) {
      fail(request_.url + ": stalled: no data for " + formatSeconds(stall) + " s" + afterBytes());
      break;
    }
    curl_multi_poll(multi_, nullptr, 0, 100, nullptr);
  }
  curl_multi_remove_handle(multi_, h);
  return rc;
}

// On the final response's first body byte (or at the end when it has none): checks the
// status and works out what to drop and how much will come.
bool HttpTransfer::decide(CURL* h) {
  attempt_.decided = true;
  Attempt& a = attempt_;
  long code = 0;
  curl_easy_getinfo(h, CURLINFO_RESPONSE_CODE, &code);
  update([&](TransferStatus& s) { s.httpStatus = code; });
  if (code < 200 || code >= 300) {
    std::string message = request_.url + ": HTTP " + std::to_string(code);
    if (code == a.head.code && !a.head.reason.empty()) message += " " + a.head.reason;
    fail(message);
    return false;
  }
  const BodyPlan plan = planBody(a.head, code, a.ranged, a.from);
  if (!plan.error.empty()) {
    fail(request_.url + ": " + plan.error);
    return false;
  }
  const std::int64_t resourceSize = plan.resourceSize;
  const std::int64_t left = plan.left;  // bytes of this response still to deliver
  const bool rangeIgnored = plan.rangeIgnored;
  if (rangeIgnored) a.drop = plan.drop;
  if (left >= 0) {
    // Saturating: a server may claim a length near 2^63.
    const auto room = std::numeric_limits<std::int64_t>::max() - static_cast<std::int64_t>(done_);
    expected_ = static_cast<std::int64_t>(done_) + std::min(left, room);
    if (request_.length > 0)
      expected_ = std::min(expected_, static_cast<std::int64_t>(request_.length));
  } else if (resumes_ == 0) {
    expected_ = -1;
  }
  update([&](TransferStatus& s) {
    s.rangeIgnored = s.rangeIgnored || rangeIgnored;
    if (resourceSize >= 0 || s.resourceSize < 0) s.resourceSize = resourceSize;
    s.expected = expected_;
  });
  return true;
}

std::size_t HttpTransfer::onWrite(char* p, std::size_t size, std::size_t n, void* self) {
  auto* t = static_cast<HttpTransfer*>(self);
  const std::size_t total = size * n;
  Attempt& a = t->attempt_;
  a.lastData = Clock::now();
  if (t->cancelRequested()) return 0;
  if (!a.decided && !t->decide(t->handle_)) return 0;
  const FetchRequest& r = t->request_;
  if (r.budget && !r.budget->addBytes(total)) {
    t->fail(budgetBytesError(r.url, *r.budget));
    return 0;
  }
  const std::size_t skip = static_cast<std::size_t>(std::min<std::uint64_t>(a.drop, total));
  a.drop -= skip;
  std::size_t len = total - skip;
  if (r.length > 0)
    len = static_cast<std::size_t>(std::min<std::uint64_t>(len, r.length - t->done_));
  if (t->done_ + len > r.maxBytes) {
    t->fail(r.url + ": larger than the limit of " + std::to_string(r.maxBytes) + " bytes");
    return 0;
  }
  if (!t->pace(p + skip, len)) return 0;
  if (r.length > 0 && t->done_ >= r.length) {
    t->stop_ = Stop::lengthReached;
    return 0;
  }
  return total;
}

// Delivers `len` bytes; with maxRate, in small pieces each held back until it is due, so
// that delivery is smooth (curl's own limit, CURLOPT_MAX_RECV_SPEED_LARGE, only throttles
// the socket and lets whatever sits in the kernel's buffers through at once). False when
// cancelled meanwhile.
bool HttpTransfer::pace(const char* p, std::size_t len) {
  const double rate = request_.maxRate;
  if (rate <= 0.0) {
    deliver(p, len);
    done_ += len;
    return true;
  }
  const auto piece = static_cast<std::size_t>(std::clamp(rate / 20.0, 512.0, 65536.0));
  for (std::size_t at = 0; at < len;) {
    const std::size_t n = std::min(piece, len - at);
    deliver(p + at, n);
    done_ += n;
    at += n;
    if (!holdRate(start_, done_, rate)) return false;
    attempt_.lastData = Clock::now();  // the wait is ours, not a stall
  }
  return true;
}

std::size_t HttpTransfer::onHeader(char* p, std::size_t size, std::size_t n, void* self) {
  auto* t = static_cast<HttpTransfer*>(self);
  Attempt& a = t->attempt_;
  a.lastData = Clock::now();
  readHeaderLine(std::string_view(p, size * n), a.head);
  return size * n;
}

int HttpTransfer::onProgress(void* self, curl_off_t, curl_off_t, curl_off_t, curl_off_t) {
  return static_cast<HttpTransfer*>(self)->cancelRequested() ? 1 : 0;
}

int HttpTransfer::onPrereq(void* self, char*, char*, int, int) {
  auto* t = static_cast<HttpTransfer*>(self);
  t->attempt_.connected = true;
  t->attempt_.lastData = Clock::now();
  return CURL_PREREQFUNC_OK;
}

// " after N of M bytes" / " after N bytes" (nothing before the first byte).
std::string HttpTransfer::afterBytes() const {
  if (done_ == 0 && expected_ < 0) return {};
  std::string s = " after " + std::to_string(done_);
  if (expected_ >= 0) s += " of " + std::to_string(expected_);
  return s + " bytes";
}

std::string HttpTransfer::networkError(CURLcode rc) const {
  const std::string what = curl_easy_strerror(rc);
  const std::string detail = errorBuffer_;
  std::string message = request_.url + ": ";
  if (rc == CURLE_PARTIAL_FILE) {
    message += "connection closed" + afterBytes();
  } else if ((rc == CURLE_RECV_ERROR || rc == CURLE_SEND_ERROR) && done_ > 0) {
    message +=
        (detail.find("reset") != std::string::npos ? "connection reset" : "connection lost") +
        afterBytes() + " (" + (detail.empty() ? what : detail) + ")";
  } else if (rc == CURLE_OPERATION_TIMEDOUT && !attempt_.connected) {
    message += "cannot connect within " + formatSeconds(request_.connectTimeout) + " s (" +
               (detail.empty() ? what : detail) + ")";
  } else if (rc == CURLE_COULDNT_CONNECT || rc == CURLE_COULDNT_RESOLVE_HOST) {
    message += "cannot connect: " + what + (detail.empty() ? "" : " (" + detail + ")");
  } else {
    message += what + (detail.empty() || detail == what ? "" : " (" + detail + ")");
  }
  if (resumes_ > 0)
    message += " (resumed " + std::to_string(resumes_) + (resumes_ == 1 ? " time)" : " times)");
  return message;
}

}  // namespace

std::unique_ptr<Transfer> startHttpTransfer(FetchRequest request) {
  return std::make_unique<HttpTransfer>(std::move(request));
}

}  // namespace gs::net::detail
