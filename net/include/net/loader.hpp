// The progressive loader of one session (a window or a snapshot): every world and QNV
// stream it opens, loaded in parallel on background transfers and consumed when pumped,
// under shared limits (docs/progressive-loading.md). A URL opened twice is loaded once
// and serves every caller.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "base/fetch.hpp"
#include "net/progress.hpp"
#include "net/streams.hpp"
#include "net/transfer.hpp"

namespace gs::net {

struct LoaderOptions {
  /// Bytes per second for each transfer at most (0: unlimited); --max-rate.
  double maxRate = 0.0;
  /// Bytes given to parsers and decoders in all, then every stream stops (0: no cap);
  /// --snapshot-at BYTES.
  std::uint64_t stopAfterBytes = 0;
  /// Limits on what content may make the loader fetch: bytes over all transfers, number
  /// of requests (range requests and resumes count), bytes of one resource.
  std::uint64_t maxTotalBytes = std::uint64_t{8} << 30;
  std::uint32_t maxRequests = 4096;
  std::uint64_t maxResourceBytes = std::uint64_t{4} << 30;
  double connectTimeout = 10.0;  // seconds
  double stallTimeout = 20.0;    // seconds
};

class Loader final : public base::Fetcher {
 public:
  explicit Loader(LoaderOptions options = {});
  ~Loader() override;

  /// The session's base::Fetcher (the one way content reads a resource): local and data:
  /// URLs as base::fetchLocally() reads them, at once; others by fetchWhole() (10 s at
  /// most) or fetchInBackground() as `mode` says, under the same rules and limits.
  base::Fetched fetch(const std::string& url, const std::string& referrer,
                      base::FetchMode mode) override;

  /// The world at `url` (a path, file:// or http(s):// URL already resolved), opened
  /// when first asked. `referrer` is the URL of the content that references it (empty for
  /// the user's own input): content from the network may not open local files. Null with
  /// `error` when refused.
  std::shared_ptr<WorldStream> world(const std::string& url, const std::string& referrer,
                                     std::string& error);
  /// The QNV stream at `url`, as world(). `sink` receives its vectors; it is used only
  /// by the call that opens the stream.
  std::shared_ptr<QnvStream> qnv(const std::string& url, const std::string& referrer,
                                 QnvStream::Sink sink, std::string& error);
  /// Reads a whole small resource (EXTERNPROTO file, texture) and waits for it: at most
  /// `timeout` seconds. False with `error` naming the URL when refused or failed.
  bool fetchWhole(const std::string& url, const std::string& referrer, std::string& bytes,
                  std::string& error, double timeout = 30.0);

  /// Fetches a whole small resource (a texture) without blocking: the first call starts
  /// the transfer. Returns true with `bytes` once it arrived (later calls return the same
  /// bytes at once); false with `error` empty while it is on its way, or set to the reason
  /// (naming the URL) when it failed or was refused.
  bool fetchInBackground(const std::string& url, const std::string& referrer, std::string& bytes,
                         std::string& error);

  /// Pumps every stream. Returns true when anything changed (scene grew, vectors or a
  /// header arrived, a stream ended, a background fetch completed).
  bool pump();
  /// Blocks until bytes may be waiting or `seconds` passed (for loops without a window).
  void wait(double seconds);
  /// Whether every stream is settled (nothing arriving without a new request).
  bool settled() const;
  /// Every stream in the order opened.
  std::vector<StreamProgress> progress() const;
  /// Ends every stream now (StreamState::stopped with `why`).
  void stopAll(const std::string& why);
  /// Why stopAll() ended the loads ("" before it did): consumers that run their own
  /// transfers (session::TilesetStream) end theirs too.
  const std::string& stopReason() const { return stopReason_; }
  /// How many of `wanted` bytes arrived at a consumer's own transfers may be used under
  /// LoaderOptions::stopAfterBytes (all without it): taken from the same allowance as the
  /// loader's own streams, so that --snapshot-at counts every byte. When the allowance is
  /// spent the next pump() stops every stream.
  std::uint64_t grant(std::uint64_t wanted);
  const LoaderOptions& options() const { return options_; }
  const FetchBudget& budget() const { return *budget_; }
  /// The request this loader would make for `url` referenced by `referrer`, under its
  /// rules (mayReference, local files only for local content) and limits (the shared
  /// budget, rate, timeouts): for consumers that run their own transfers (the range
  /// requests of tileset bricks). An empty url with `error` when refused.
  FetchRequest requestFor(const std::string& url, const std::string& referrer,
                          std::string& error) const;

 private:
  LoaderOptions options_;
  std::shared_ptr<FetchBudget> budget_;
  Allowance allowance_;
  bool capReached_ = false;
  std::string stopReason_;
  std::map<std::string, std::shared_ptr<WorldStream>> worlds_;
  std::map<std::string, std::shared_ptr<QnvStream>> qnvs_;
  /// One stream the loader opened: which map holds it, under which URL.
  struct StreamKey {
    enum class Kind { world, qnv } kind;
    std::string url;
    bool operator==(const StreamKey&) const = default;
  };
  std::vector<StreamKey> order_;  // every stream, in opening order
  struct Fetch {
    std::unique_ptr<Transfer> transfer;  // null once ended
    std::string bytes;
    std::string error;
    bool done = false;
  };
  std::map<std::string, Fetch> fetches_;
};

}  // namespace gs::net
