// The one way content asks for a resource's bytes (docs/progressive-loading.md, "One way
// to fetch"): an EXTERNPROTO file, a texture, a movie, a sound, a Script url, an Inline
// read whole, a glTF buffer. Every reader asks a Fetcher; the rules of what may be read
// are applied once, in fetchLocally() and net::Loader (whose fetch() starts with it).
// Streams (a world growing while it arrives, a QNV stream, tileset bricks) are the third
// mode, served by net::Loader::world / qnv / requestFor under the same rules.
#pragma once

#include <functional>
#include <optional>
#include <string>

namespace gs::base {

/// How long a reader may wait.
enum class FetchMode {
  /// Wait until the bytes arrived or failed (up to the fetcher's time-out, 10 s for
  /// net::Loader): for a parse that needs them now (EXTERNPROTO under a blocking parse).
  whole,
  /// Never wait: the first call starts the transfer and answers FetchState::pending; a
  /// later call (after the session's pump) answers ready or failed. For what a frame
  /// draws (textures, movies, sounds, Inline worlds read whole).
  background,
};

enum class FetchState {
  ready,    ///< Fetched::bytes holds the resource.
  pending,  ///< on its way (FetchMode::background only): ask again later.
  failed,   ///< Fetched::error says which URL and why (missing, HTTP error, time-out).
  refused,  ///< the rules forbid it (content from the network naming a local file).
};

/// A fetcher's answer.
struct Fetched {
  FetchState state = FetchState::failed;
  std::string bytes;  ///< the whole resource when state == ready
  std::string error;  ///< "URL: why" when failed or refused
  bool ready() const { return state == FetchState::ready; }
  bool pending() const { return state == FetchState::pending; }
};

/// Reads resources for the content of one session (a window, a snapshot, a test).
class Fetcher {
 public:
  virtual ~Fetcher() = default;
  /// The bytes behind `url` (already resolved: a local path, file:, http(s): or data:
  /// URL), named by the content at `referrer` (its URL; empty for the user's own input,
  /// which may read anything). Never throws for a bad URL or a failed transfer.
  virtual Fetched fetch(const std::string& url, const std::string& referrer, FetchMode mode) = 0;
};

/// The part of the rules that needs no network, shared by every Fetcher: a URL that
/// `referrer` may not reference (base::mayReference: content from http(s) reads only
/// http(s) and data: URLs) is refused; a data: URL is decoded (RFC 2397); a local path or
/// file: URL is read (at most 2 GiB). Empty (nullopt) when `url` needs the network.
std::optional<Fetched> fetchLocally(const std::string& url, const std::string& referrer);

/// The local file a reader may read itself (a worker thread reading a large movie or
/// sound file): the path of a plain path or file: URL that `referrer` may reference. ""
/// for other URLs (data:, http(s): ask a Fetcher), and "" with `error` set when the
/// rules refuse it. fetchLocally() reads what this names.
std::string localFileFor(const std::string& url, const std::string& referrer, std::string& error);

/// A Fetcher without a network: fetchLocally(), and any other URL fails with "URL: only
/// local files can be read without a network loader". Stateless; the fetcher readers
/// use when they were given none (tests, `ghostspace encode`, a parse of a local file).
class LocalFetcher final : public Fetcher {
 public:
  Fetched fetch(const std::string& url, const std::string& referrer, FetchMode mode) override;
};

/// A Fetcher that answers through a function: for tests, fuzz targets (which refuse every
/// URL) and embedders with a store of their own. The function applies whatever rules it
/// wants; fetchLocally() is not called for it.
class CallbackFetcher final : public Fetcher {
 public:
  using Callback =
      std::function<Fetched(const std::string& url, const std::string& referrer, FetchMode mode)>;
  explicit CallbackFetcher(Callback callback) : callback_(std::move(callback)) {}
  Fetched fetch(const std::string& url, const std::string& referrer, FetchMode mode) override {
    return callback_(url, referrer, mode);
  }

 private:
  Callback callback_;
};

/// A failed Fetched with `error` (the callbacks' usual answer).
inline Fetched fetchFailed(std::string error) {
  return {FetchState::failed, {}, std::move(error)};
}

/// A ready Fetched holding `bytes`.
inline Fetched fetchReady(std::string bytes) {
  return {FetchState::ready, std::move(bytes), {}};
}

/// `fetcher` when not null, else one shared LocalFetcher.
Fetcher& fetcherOr(Fetcher* fetcher);

}  // namespace gs::base
