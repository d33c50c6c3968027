#include "net/streams.hpp"

#include <algorithm>
#include <cmath>

namespace gs::net {

QnvStream::QnvStream(FetchRequest request, Sink sink, std::uint64_t firstSliceBytes)
    : request_(std::move(request)), sink_(std::move(sink)), decoder_(request_.url) {
  progress_.url = request_.url;
  progress_.kind = StreamKind::qnv;
  // A packet's place is its sequence number times the records per packet, both from the
  // stream: accept it only near what the bytes received can hold (a record is at least
  // 2 bytes even compressed), so that a hostile stream cannot make the consumer allocate
  // for billions of vectors.
  guarded_ = [this](std::uint64_t first, std::span<const qnv::DecodedVector> v) {
    const std::uint64_t limit = (fed_ + chunkBytes_) / 2 + 65536;
    if (first + v.size() > limit) {
      ++packetsDropped_;
      return;
    }
    coveredEnd_ = std::max<std::uint64_t>(coveredEnd_, first + v.size());
    sink_(first, v);
  };
  startTransfer(0, qnv::kHeaderBytes + firstSliceBytes);
}

QnvStream::~QnvStream() = default;

void QnvStream::setRecordSink(qnv::StreamDecoder::RecordSink sink) {
  decoder_.setRecordSink(
      [this, sink = std::move(sink)](std::uint64_t first, std::span<const std::uint64_t> records) {
        // As for vectors, with a splat (its records together) at least 2 bytes.
        const std::uint64_t limit =
            ((fed_ + chunkBytes_) / 2 + 65536) * decoder_.header()->recordsPerElement();
        if (first + records.size() > limit) {
          ++packetsDropped_;
          return;
        }
        coveredEnd_ = std::max<std::uint64_t>(coveredEnd_, first + records.size());
        sink(first, records);
      });
}

void QnvStream::want(std::uint64_t vectors) {
  progress_.wantedVectors = std::max(progress_.wantedVectors, vectors);
}

std::uint64_t QnvStream::bytesFor(std::uint64_t vectors) const {
  const auto& h = decoder_.header();
  if (!h) return qnv::kHeaderBytes;
  vectors = std::min(vectors, h->vectorCount);
  const std::uint64_t perPacket = h->recordsPerPacket();
  const std::uint64_t packets = (vectors + perPacket - 1) / perPacket;
  if (h->encoding == qnv::PacketEncoding::plain)
    return h->headerBytes + packets * (qnv::kPacketHeaderBytes + h->packetBytes);
  // Compact packets vary in size: extrapolate the bytes per packet seen so far, with a
  // margin; pump() asks again when the estimate fell short.
  const std::uint64_t seen = decoder_.stats().packetsDecoded + decoder_.stats().packetsCorrupt;
  const double perPacketBytes =
      seen > 0 ? static_cast<double>(fed_ - h->headerBytes) / static_cast<double>(seen)
               : static_cast<double>(qnv::kPacketHeaderBytes + h->packetBytes);
  return h->headerBytes +
         static_cast<std::uint64_t>(
             std::ceil(static_cast<double>(packets) * perPacketBytes * 1.1)) +
         qnv::kPacketHeaderBytes + h->packetBytes;
}

void QnvStream::startTransfer(std::uint64_t offset, std::uint64_t length) {
  FetchRequest r = request_;
  r.offset = offset;
  r.length = rangesIgnored_ ? 0 : length;
  requestedEnd_ = r.length == 0 ? UINT64_MAX : offset + length;
  transferOffset_ = offset;
  transfer_ = net::startTransfer(std::move(r));
  if (progress_.state == StreamState::idle) progress_.state = StreamState::loading;
}

bool QnvStream::pump(Allowance& allowance) {
  if (progress_.state == StreamState::done || progress_.state == StreamState::stopped ||
      progress_.state == StreamState::failed)
    return false;
  bool changed = false;
  if (transfer_) {
    chunk_.clear();
    transfer_->take(chunk_);
    if (!chunk_.empty()) {
      const std::size_t n =
          static_cast<std::size_t>(std::min<std::uint64_t>(chunk_.size(), allowance.remaining));
      allowance.remaining -= n;
      const bool hadHeader = decoder_.header().has_value();
      const std::uint64_t before = decoder_.stats().vectorsDecoded;
      chunkBytes_ = n;
      const bool usable = decoder_.feed(std::string_view(chunk_).substr(0, n), guarded_);
      chunkBytes_ = 0;
      fed_ += n;
      progress_.bytes = fed_;
      progress_.state = StreamState::loading;
      changed =
          decoder_.stats().vectorsDecoded != before || hadHeader != decoder_.header().has_value();
      if (!usable) {
        transfer_->cancel();
        end(StreamState::failed, decoder_.error());
        return true;
      }
      if (n < chunk_.size() || allowance.remaining == 0) {
        stop("stopped after " + std::to_string(fed_) + " bytes");
        return true;
      }
    }
    const TransferStatus s = transfer_->status();
    progress_.bytesPerSecond = s.bytesPerSecond;
    if (s.rangeIgnored) rangesIgnored_ = true;
    if (s.resourceSize >= 0) resourceSize_ = s.resourceSize;
    progress_.expectedBytes = resourceSize_;
    if (!s.finished() || s.received > fed_ - transferOffset_) return changed;  // bytes to take
    if (s.state == TransferState::failed) {
      decoder_.finish(guarded_);
      progress_.vectors = decoder_.stats().vectorsDecoded;
      end(StreamState::failed, s.error);
      return true;
    }
    if (s.state == TransferState::cancelled) {
      end(StreamState::stopped, progress_.url + ": cancelled");
      return true;
    }
    // A range answered with fewer bytes than asked: the resource ends here.
    if (requestedEnd_ != UINT64_MAX && fed_ < requestedEnd_)
      resourceSize_ = static_cast<std::int64_t>(fed_);
    transfer_.reset();
    changed = true;
  }
  // Between transfers: is the wanted prefix here, or the whole stream?
  const auto& h = decoder_.header();
  const std::uint64_t total = h ? h->vectorCount : 0;
  progress_.expectedVectors = total;
  progress_.vectors = decoder_.stats().vectorsDecoded;
  progress_.packetsLost =
      decoder_.stats().packetsCorrupt + decoder_.stats().packetsMissing + packetsDropped_;
  const bool atEnd = (resourceSize_ >= 0 && fed_ >= static_cast<std::uint64_t>(resourceSize_)) ||
                     requestedEnd_ == UINT64_MAX ||
                     (h && fed_ >= bytesFor(total) && h->encoding == qnv::PacketEncoding::plain);
  if (!h) {
    // The first slice ended without a complete header.
    if (atEnd || fed_ < requestedEnd_) {
      decoder_.finish(guarded_);
      end(StreamState::failed,
          decoder_.error().empty() ? progress_.url + ": no QNV header" : decoder_.error());
      return true;
    }
    startTransfer(fed_, qnv::kHeaderBytes - fed_);
    return changed;
  }
  if (atEnd) {
    const bool whole = decoder_.finish(guarded_);
    progress_.vectors = decoder_.stats().vectorsDecoded;
    progress_.packetsLost =
        decoder_.stats().packetsCorrupt + decoder_.stats().packetsMissing + packetsDropped_;
    std::string message;
    if (!whole && !decoder_.warnings().empty()) message = decoder_.warnings().back();
    end(StreamState::done, message);
    return true;
  }
  const std::uint64_t wanted = std::min(progress_.wantedVectors, total);
  // Arrived: vectors up to the highest placed; for plain packets, the bytes that hold the
  // prefix (whatever of them was damaged is lost, not fetched again).
  const bool plain = h->encoding == qnv::PacketEncoding::plain;
  if (coveredEnd_ >= wanted || (plain && fed_ >= bytesFor(wanted))) {
    progress_.state = StreamState::idle;
    return changed;
  }
  // At least 64 KiB more per request: a damaged stretch never turns into a storm of
  // tiny range requests.
  const std::uint64_t target = std::max(bytesFor(wanted), fed_ + 65536);
  startTransfer(fed_, target - fed_);
  return true;
}

void QnvStream::stop(const std::string& why) {
  if (transfer_) transfer_->cancel();
  decoder_.finish(guarded_);
  progress_.vectors = decoder_.stats().vectorsDecoded;
  end(StreamState::stopped, why);
}

void QnvStream::end(StreamState state, const std::string& message) {
  transfer_.reset();
  progress_.state = state;
  progress_.error = message;
}

}  // namespace gs::net
