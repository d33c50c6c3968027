// Bytes arriving over time (Nagasawa, "Beyond VRML", sections 1.2 and 3.4): one
// interface for a local file read in chunks and an http:// or https:// URL fetched by
// libcurl on a background thread. The consumer polls: take() hands over what arrived since
// the last call, status() says how far the transfer is and why it ended. Nothing here
// parses content; the QNV decoder and the VRML streaming parser consume the bytes.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace gs::net {

/// Limits shared by every transfer of one session (a window, a snapshot): protects the
/// machine from content that references endless resources. Thread-safe.
class FetchBudget {
 public:
  FetchBudget(std::uint64_t maxTotalBytes, std::uint32_t maxRequests)
      : maxTotalBytes_(maxTotalBytes), maxRequests_(maxRequests) {}
  /// Counts one more request; false (and nothing counted) once maxRequests were made.
  bool startRequest();
  /// Counts `n` more bytes received; false once the total passes maxTotalBytes (the
  /// transfer that gets false must fail with a message naming the limit).
  bool addBytes(std::uint64_t n);
  std::uint64_t totalBytes() const { return total_.load(); }
  std::uint32_t requests() const { return requests_.load(); }
  std::uint64_t maxTotalBytes() const { return maxTotalBytes_; }
  std::uint32_t maxRequests() const { return maxRequests_; }

 private:
  const std::uint64_t maxTotalBytes_;
  const std::uint32_t maxRequests_;
  std::atomic<std::uint64_t> total_{0};
  std::atomic<std::uint32_t> requests_{0};
};

/// What to fetch and under which limits.
struct FetchRequest {
  /// http:// or https:// URL, file:// URL or a local path (see allowLocal).
  std::string url;
  /// First byte wanted (HTTP: "Range: bytes=offset-"). A server that ignores the range
  /// (answers 200) still works: the bytes before `offset` are read and dropped.
  std::uint64_t offset = 0;
  /// Bytes wanted from `offset`; 0 = to the end of the resource. The transfer ends as
  /// done after this many bytes even when the server sends more.
  std::uint64_t length = 0;
  /// The transfer fails ("... larger than the limit of N bytes") past this many bytes.
  std::uint64_t maxBytes = std::uint64_t{1} << 31;
  /// Seconds to wait for the connection (DNS, TCP, TLS); then fails naming the URL.
  double connectTimeout = 10.0;
  /// Seconds without a single byte (once connected; checked about every 0.1 s) after which
  /// the transfer fails as stalled. A stall is not resumed. HTTP only.
  double stallTimeout = 20.0;
  /// Bytes per second delivered at most (0: unlimited); emulates a slow link
  /// (--max-rate), for files as well as HTTP. Delivery is paced in pieces of about
  /// maxRate / 20 bytes (512 at least), so a consumer sees a steady trickle.
  double maxRate = 0.0;
  /// HTTP redirects followed at most (to http or https URLs only).
  long maxRedirects = 8;
  /// Times a transfer cut by the network after some bytes is resumed with a Range
  /// request from the first missing byte before it fails. Only an attempt that delivered
  /// new bytes is resumed (a server that keeps cutting at the same place fails at once).
  /// A resume that is answered 200 drops the bytes already delivered.
  int maxResumes = 2;
  /// Whether a local path or file:// URL may be read. False for every URL that content
  /// from the network references (a remote world never reads local files).
  bool allowLocal = true;
  /// Optional shared limits, for files as well as HTTP: each request (each resume too)
  /// takes one request from it, every byte received counts (also bytes dropped before
  /// `offset`). A refused request fails before it connects or opens anything, with a
  /// message naming the limit.
  std::shared_ptr<FetchBudget> budget;
};

enum class TransferState { running, done, failed, cancelled };

/// A snapshot of a transfer. Byte counts are of the body as delivered to take() (after
/// HTTP content decoding), relative to FetchRequest::offset.
struct TransferStatus {
  TransferState state = TransferState::running;
  std::uint64_t received = 0;      // bytes delivered (take() may not have taken them yet)
  std::int64_t expected = -1;      // bytes this transfer will deliver when known (not for a
                                   // gzip-encoded body), else -1
  std::int64_t resourceSize = -1;  // size of the whole resource when known, else -1
  long httpStatus = 0;             // last HTTP status (0 for files)
  bool rangeIgnored = false;       // the server answered 200 to a Range request
  int resumes = 0;                 // times the transfer was resumed with a Range
  double bytesPerSecond = 0.0;     // average over the transfer so far
  std::string effectiveUrl;        // after redirects
  /// Why the transfer failed, naming the URL: "http://h/x.wrl: HTTP 404 Not Found",
  /// "http://h/x.qnv: connection reset after 1200 of 5000 bytes (...)", "...: connection
  /// closed after 1200 of 5000 bytes", "...: stalled: no data for 20 s after 1200 of
  /// 5000 bytes", "...: larger than the limit of N bytes", "...: refused: ...",
  /// "cannot open 'x': ...". A failure after resumes ends with "(resumed N times)".
  std::string error;
  bool finished() const { return state != TransferState::running; }
};

/// One running transfer. All members are thread-safe. Destroying it cancels and joins
/// its thread.
class Transfer {
 public:
  virtual ~Transfer() = default;
  /// Appends the bytes delivered since the last call to `out`; returns their number.
  virtual std::size_t take(std::string& out) = 0;
  virtual TransferStatus status() const = 0;
  /// Stops the transfer soon (state becomes cancelled unless it already ended).
  virtual void cancel() = 0;
  /// Blocks until bytes are waiting to be taken, the transfer ended, or `seconds` passed.
  virtual void wait(double seconds) = 0;
};

/// Starts fetching `request` on a background thread: HTTP(S) through libcurl (redirects,
/// gzip/deflate Content-Encoding decoded when no range is asked, timeouts, resume), local
/// files in 64 KiB chunks. Never throws for network or file problems: they end the
/// transfer as failed with TransferStatus::error. A URL with another scheme ("ftp://"),
/// a file:// URL naming another host, or a local one when allowLocal is false, is failed
/// already when this returns. A file URL is percent-decoded; a plain path is not.
std::unique_ptr<Transfer> startTransfer(FetchRequest request);

}  // namespace gs::net
