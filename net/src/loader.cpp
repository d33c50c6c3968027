#include "net/loader.hpp"

#include "base/url.hpp"

#include <algorithm>
#include <chrono>
#include <thread>

namespace gs::net {

Loader::Loader(LoaderOptions options)
    : options_(options),
      budget_(std::make_shared<FetchBudget>(options.maxTotalBytes, options.maxRequests)) {
  if (options_.stopAfterBytes > 0) allowance_.remaining = options_.stopAfterBytes;
}

Loader::~Loader() = default;

FetchRequest Loader::requestFor(const std::string& url, const std::string& referrer,
                                std::string& error) const {
  FetchRequest r;
  r.url = url;
  if (!referrer.empty() && !base::mayReference(referrer, url, error)) {
    r.url.clear();
    return r;
  }
  // Content from the network never reads local files; the user's own input may.
  r.allowLocal = referrer.empty() || !base::isHttpUrl(referrer);
  r.maxBytes = options_.maxResourceBytes;
  r.connectTimeout = options_.connectTimeout;
  r.stallTimeout = options_.stallTimeout;
  r.maxRate = options_.maxRate;
  r.budget = budget_;
  return r;
}

std::shared_ptr<WorldStream> Loader::world(const std::string& url, const std::string& referrer,
                                           std::string& error) {
  FetchRequest r = requestFor(url, referrer, error);  // the rules first, then the cache
  if (r.url.empty()) return nullptr;
  if (auto it = worlds_.find(url); it != worlds_.end()) {
    // The user opening again what failed or was cut gets a fresh try.
    const StreamState state = it->second->progress().state;
    if (!referrer.empty() || (state != StreamState::failed && state != StreamState::stopped) ||
        capReached_)
      return it->second;
    worlds_.erase(it);
    std::erase(order_, StreamKey{StreamKey::Kind::world, url});
  }
  vrml::ParseOptions parse;
  // EXTERNPROTO files are small: fetched in the background under the same rules, the
  // statement that needs one waiting for it (the stream ends before this loader).
  parse.fetcher = this;
  parse.externProtosInBackground = true;  // a statement waits for its file, no frame does
  auto stream = std::make_shared<WorldStream>(std::move(r), std::move(parse));
  if (capReached_) stream->stop("stopped: the byte cap was reached before it started");
  worlds_[url] = stream;
  order_.push_back({StreamKey::Kind::world, url});
  return stream;
}

std::shared_ptr<QnvStream> Loader::qnv(const std::string& url, const std::string& referrer,
                                       QnvStream::Sink sink, std::string& error) {
  FetchRequest r = requestFor(url, referrer, error);  // the rules first, then the cache
  if (r.url.empty()) return nullptr;
  if (auto it = qnvs_.find(url); it != qnvs_.end()) return it->second;
  auto stream = std::make_shared<QnvStream>(std::move(r), std::move(sink));
  if (capReached_) stream->stop("stopped: the byte cap was reached before it started");
  qnvs_[url] = stream;
  order_.push_back({StreamKey::Kind::qnv, url});
  return stream;
}

base::Fetched Loader::fetch(const std::string& url, const std::string& referrer,
                            base::FetchMode mode) {
  if (std::optional<base::Fetched> local = base::fetchLocally(url, referrer))
    return std::move(*local);
  base::Fetched out;
  const bool ok = mode == base::FetchMode::whole
                      ? fetchWhole(url, referrer, out.bytes, out.error, 10.0)
                      : fetchInBackground(url, referrer, out.bytes, out.error);
  out.state = ok                  ? base::FetchState::ready
              : out.error.empty() ? base::FetchState::pending
                                  : base::FetchState::failed;
  return out;
}

bool Loader::fetchWhole(const std::string& url, const std::string& referrer, std::string& bytes,
                        std::string& error, double timeout) {
  FetchRequest r = requestFor(url, referrer, error);
  if (r.url.empty()) return false;
  r.maxBytes = std::min<std::uint64_t>(r.maxBytes, std::uint64_t{256} << 20);
  auto transfer = startTransfer(std::move(r));
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
  bytes.clear();
  for (;;) {
    transfer->take(bytes);
    const TransferStatus s = transfer->status();
    if (s.finished() && s.received <= bytes.size()) {
      if (s.state == TransferState::done) return true;
      error = s.error.empty() ? url + ": cancelled" : s.error;
      return false;
    }
    if (std::chrono::steady_clock::now() > deadline) {
      transfer->cancel();
      error = url + ": not complete after " + std::to_string(static_cast<int>(timeout)) + " s";
      return false;
    }
    transfer->wait(0.05);
  }
}

bool Loader::fetchInBackground(const std::string& url, const std::string& referrer,
                               std::string& bytes, std::string& error) {
  if (!referrer.empty() && !base::mayReference(referrer, url, error)) return false;
  auto it = fetches_.find(url);
  if (it == fetches_.end()) {
    Fetch f;
    FetchRequest r = requestFor(url, referrer, f.error);
    if (!r.url.empty()) {
      r.maxBytes = std::min<std::uint64_t>(r.maxBytes, std::uint64_t{256} << 20);
      f.transfer = startTransfer(std::move(r));
    }
    it = fetches_.emplace(url, std::move(f)).first;
  }
  Fetch& f = it->second;
  error = f.error;
  if (f.done) bytes = f.bytes;
  return f.done;
}

bool Loader::pump() {
  bool changed = false;
  for (auto& [url, f] : fetches_) {
    if (!f.transfer) continue;
    f.transfer->take(f.bytes);
    const TransferStatus s = f.transfer->status();
    if (!s.finished() || s.received > f.bytes.size()) continue;
    f.done = s.state == TransferState::done;
    if (!f.done) {
      f.error = s.error.empty() ? url + ": cancelled" : s.error;
      f.bytes.clear();
    }
    f.transfer.reset();
    changed = true;
  }
  for (auto& [url, w] : worlds_) changed |= w->pump(allowance_);
  for (auto& [url, q] : qnvs_) changed |= q->pump(allowance_);
  if (!capReached_ && options_.stopAfterBytes > 0 && allowance_.remaining == 0) {
    capReached_ = true;
    stopAll("stopped after " + std::to_string(options_.stopAfterBytes) + " bytes (--snapshot-at)");
    changed = true;
  }
  return changed;
}

void Loader::wait(double seconds) {
  // Transfers deliver on their own threads; a short sleep bounds the latency.
  std::this_thread::sleep_for(std::chrono::duration<double>(std::min(seconds, 0.01)));
}

bool Loader::settled() const {
  for (const auto& [url, f] : fetches_)
    if (f.transfer) return false;
  for (const auto& [url, w] : worlds_)
    if (!w->progress().settled()) return false;
  for (const auto& [url, q] : qnvs_)
    if (!q->progress().settled()) return false;
  return true;
}

std::vector<StreamProgress> Loader::progress() const {
  std::vector<StreamProgress> out;
  for (const StreamKey& key : order_) {
    if (key.kind == StreamKey::Kind::world)
      out.push_back(worlds_.at(key.url)->progress());
    else
      out.push_back(qnvs_.at(key.url)->progress());
  }
  return out;
}

std::uint64_t Loader::grant(std::uint64_t wanted) {
  const std::uint64_t n = std::min(wanted, allowance_.remaining);
  allowance_.remaining -= n;
  return n;
}

void Loader::stopAll(const std::string& why) {
  if (stopReason_.empty()) stopReason_ = why;
  for (auto& [url, f] : fetches_)
    if (f.transfer) {
      f.transfer->cancel();
      f.transfer.reset();
      f.error = url + ": " + why;
    }
  for (auto& [url, w] : worlds_)
    if (!w->progress().settled()) w->stop(why);
  for (auto& [url, q] : qnvs_)
    if (!q->progress().settled() || q->progress().state == StreamState::idle) q->stop(why);
}

}  // namespace gs::net
