// Incremental consumers of transfers (Nagasawa, "Beyond VRML", sections 1.2, 3.4, 3.6):
// a VRML97 world whose scene grows by each completed top-level node, and a QNV stream
// decoded packet by packet that fetches, with HTTP range requests, only the prefix of
// vectors the views ask for. Both are pumped on the thread that draws: pump() moves what
// arrived into the parser or decoder and never blocks.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "encodings/streaming_parser.hpp"
#include "net/progress.hpp"
#include "net/transfer.hpp"
#include "qnv/decoder.hpp"

namespace gs::net {

/// Bytes the consumers may still take (the --snapshot-at cap), shared by every stream of
/// a Loader; UINT64_MAX when there is no cap.
struct Allowance {
  std::uint64_t remaining = UINT64_MAX;
};

/// A VRML97 world (.wrl, gzip or not) read progressively.
class WorldStream {
 public:
  /// Starts the transfer of `request` at once; `parse` is given to the StreamingParser
  /// (its loader serves EXTERNPROTO URLs).
  WorldStream(FetchRequest request, vrml::ParseOptions parse);
  ~WorldStream();

  /// Moves the bytes that arrived into the parser (at most `allowance`), and retries a
  /// statement that waits for an EXTERNPROTO file (vrml::ParseOptions::
  /// externProtosInBackground): a world whose bytes all arrived ends only once no
  /// statement waits. Returns true when the scene grew or the stream ended.
  bool pump(Allowance& allowance);
  /// The scene so far. The object stays the same while it grows (root nodes appended in
  /// file order between pump() calls); it lives as long as the returned pointer.
  std::shared_ptr<const vrml::Scene> scene() const { return scene_; }
  StreamProgress progress() const { return progress_; }
  /// Ends the stream on purpose: the parse finishes with what arrived and the state is
  /// StreamState::stopped with `why` as its message.
  void stop(const std::string& why);
  /// Ends the stream and drops what has not been parsed: no root node is added after this
  /// call (the world was replaced: Browser.replaceWorld). The state is StreamState::stopped
  /// with `why`; a stream that already ended is left as it is.
  void abandon(const std::string& why);

 private:
  void end(StreamState state, const std::string& message);
  /// Pumps a stream whose transfer ended while a statement waited for an EXTERNPROTO.
  bool pumpWaiting();
  std::unique_ptr<Transfer> transfer_;
  /// Set when the transfer ended (done) while the parser waited for an EXTERNPROTO file:
  /// the state the stream ends in once it no longer waits.
  std::optional<StreamState> endWhenArrived_;
  std::shared_ptr<vrml::StreamingParser> parser_;
  std::shared_ptr<const vrml::Scene> scene_;
  StreamProgress progress_;
  std::string chunk_;
};

/// A .qnv stream read progressively: the first request fetches the header and a first
/// slice; later ones fetch, as range requests, the bytes up to the prefix of vectors
/// wanted (want()). A server that ignores ranges is streamed to the end instead.
class QnvStream {
 public:
  /// Receives the vectors of every good packet (stream index of its first vector).
  using Sink = qnv::StreamDecoder::Sink;

  /// Starts with a request for the header and the first `firstSliceBytes` of packets.
  QnvStream(FetchRequest request, Sink sink, std::uint64_t firstSliceBytes = 64 * 1024);
  ~QnvStream();

  /// Gives the records of a Gaussian stream's packets (qnv::StreamKind::gaussian, whose
  /// packets have no vectors for the Sink) to `sink`, under the same guard against
  /// hostile sequence numbers. Counts, for want(), are then records.
  void setRecordSink(qnv::StreamDecoder::RecordSink sink);
  /// Asks for the first `vectors` vectors of the stream (the largest); the stream keeps
  /// the largest prefix ever asked. Vectors beyond the stream's count are ignored.
  void want(std::uint64_t vectors);
  /// Moves arrived bytes into the decoder (at most `allowance`) and starts the next range
  /// request when the wanted prefix has not arrived. Returns true when vectors or the
  /// header arrived, or the stream ended.
  bool pump(Allowance& allowance);
  /// The stream header once it arrived.
  const std::optional<qnv::StreamHeader>& header() const { return decoder_.header(); }
  StreamProgress progress() const { return progress_; }
  /// Warnings of the decoder (damaged packets, truncation).
  const std::vector<std::string>& warnings() const { return decoder_.warnings(); }
  void stop(const std::string& why);

 private:
  /// Bytes from the start of the stream that hold the first `vectors` vectors (plain
  /// packets: exact; compact: estimated from the bytes per vector seen so far).
  std::uint64_t bytesFor(std::uint64_t vectors) const;
  void startTransfer(std::uint64_t offset, std::uint64_t length);
  void end(StreamState state, const std::string& message);

  FetchRequest request_;
  Sink sink_;
  qnv::StreamDecoder decoder_;
  std::unique_ptr<Transfer> transfer_;
  StreamProgress progress_;
  std::uint64_t fed_ = 0;             // bytes given to the decoder (from offset 0)
  std::uint64_t requestedEnd_ = 0;    // end of the bytes asked for so far
  std::uint64_t transferOffset_ = 0;  // first byte of the current transfer
  std::int64_t resourceSize_ = -1;
  bool rangesIgnored_ = false;
  /// End (exclusive) of the highest vector index delivered to the sink.
  std::uint64_t coveredEnd_ = 0;
  std::uint64_t chunkBytes_ = 0;  // bytes of the chunk being fed
  /// Packets dropped because their place lay far beyond the bytes received (a hostile
  /// sequence number must not size the consumer's arrays).
  std::uint64_t packetsDropped_ = 0;
  /// sink_ behind the guard above; used for every feed() and finish().
  Sink guarded_;
  std::string chunk_;
};

}  // namespace gs::net
