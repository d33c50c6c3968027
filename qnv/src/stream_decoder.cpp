#include <algorithm>
#include <cstring>

#include "base/byte_order.hpp"
#include "compact_payload.hpp"
#include "entropy_payload.hpp"
#include "qnv/decoder.hpp"

namespace gs::qnv {

using base::loadLe;

namespace {
constexpr std::size_t kMaxWarnings = 100;
}

StreamDecoder::StreamDecoder(std::string name) : name_(std::move(name)) {}

void StreamDecoder::warn(std::string message) {
  if (warnings_.size() < kMaxWarnings) warnings_.push_back(name_ + ": " + std::move(message));
}

bool StreamDecoder::complete() const {
  return header_ && packetsReceived_ >= header_->packetCount() && stats_.packetsMissing == 0;
}

void StreamDecoder::compactBuffer() {
  if (offset_ == 0) return;
  if (offset_ == buffer_.size() || offset_ >= buffer_.size() / 2) {
    buffer_.erase(0, offset_);
    bufferBase_ += offset_;
    offset_ = 0;
  }
}

bool StreamDecoder::feed(std::string_view chunk, const Sink& sink) {
  if (!error_.empty()) return false;
  stats_.bytesFed += chunk.size();
  if (header_ && offset_ == buffer_.size()) {
    // Nothing pending: parse the chunk where it lies and keep only its unfinished tail.
    bufferBase_ += buffer_.size();
    buffer_.clear();
    offset_ = 0;
    view_ = chunk;
    parsePackets(sink);
    buffer_.assign(chunk.substr(offset_));
    bufferBase_ += offset_;
    offset_ = 0;
    view_ = buffer_;
    return true;
  }
  buffer_.append(chunk);
  if (!header_) {
    const std::string_view have(buffer_.data() + offset_, buffer_.size() - offset_);
    std::string why;
    if (have.size() < kHeaderBytes) {
      // Reject a wrong signature or version as soon as its bytes are here.
      const std::size_t sig = std::min(have.size(), kMagic.size());
      if (std::memcmp(have.data(), kMagic.data(), sig) != 0 ||
          (have.size() >= kMagic.size() + 2 &&
           loadLe<std::uint16_t>(have.data() + 8) != kFormatVersion)) {
        parseHeader(have, name_, why);
        error_ = why;
        return false;
      }
      return true;
    }
    std::optional<StreamHeader> header = parseHeader(have, name_, why);
    if (!header) {
      error_ = why;
      return false;
    }
    if (have.size() < header->headerBytes) return true;  // wait for the stream model
    auto grid =
        std::make_shared<const detail::PositionGrid>(detail::PositionGrid::forHeader(*header));
    if (!grid->modelValid) {
      error_ = name_ + ": QNV stream model does not decode";
      return false;
    }
    header_ = std::move(header);
    dequantizer_.emplace(*header_);
    vectorTables_ = std::make_shared<const detail::VectorTables>(*dequantizer_, *grid);
    grid_ = std::move(grid);
    offset_ += header_->headerBytes;
  }
  view_ = buffer_;
  parsePackets(sink);
  compactBuffer();
  return true;
}

bool StreamDecoder::parsePackets(const Sink& sink) {
  const StreamHeader& h = *header_;
  const std::uint32_t capacity = h.recordsPerPacket();
  const std::uint64_t packetCount = h.packetCount();
  const std::uint32_t perElement = h.recordsPerElement();
  const bool gaussian = h.kind == StreamKind::gaussian;
  auto skipDamaged = [&](const char* what) {
    if (!resyncing_) {
      resyncing_ = true;
      if (complete()) {
        warn(std::to_string(view_.size() - offset_) +
             " bytes of trailing garbage after the last packet at byte " +
             std::to_string(bufferBase_ + offset_));
      } else {
        ++stats_.packetsCorrupt;
        warn(std::string("damaged packet at byte ") + std::to_string(bufferBase_ + offset_) + " (" +
             what + "), skipped");
      }
    }
    ++offset_;
    ++stats_.bytesSkipped;
  };
  while (view_.size() - offset_ >= kPacketHeaderBytes) {
    const char* p = view_.data() + offset_;
    if (p[0] != 'Q' || p[1] != 'P') {
      skipDamaged("no packet sync");
      // Jump to the next possible sync byte.
      const void* q = std::memchr(view_.data() + offset_, 'Q', view_.size() - offset_);
      const std::size_t next =
          q ? static_cast<std::size_t>(static_cast<const char*>(q) - view_.data()) : view_.size();
      stats_.bytesSkipped += next - offset_;
      offset_ = next;
      continue;
    }
    const auto count = loadLe<std::uint16_t>(p + 2);
    const auto sequence = loadLe<std::uint32_t>(p + 4);
    const auto payloadBytes = loadLe<std::uint16_t>(p + 8);
    const auto encoding = static_cast<std::uint8_t>(p[10]);
    const bool plausible =
        count >= 1 && count <= capacity && encoding <= (gaussian ? 1 : 2) &&
        count % perElement == 0 && p[11] == 0 && payloadBytes <= std::size_t{count} * 8 &&
        (encoding != 0 || payloadBytes == std::size_t{count} * 8) && sequence < packetCount &&
        std::uint64_t{sequence} * capacity + count <= h.vectorCount &&
        (count == capacity || sequence + 1 == packetCount);
    if (!plausible) {
      skipDamaged("impossible packet header");
      continue;
    }
    const std::size_t packetBytes = kPacketHeaderBytes + payloadBytes;
    if (view_.size() - offset_ < packetBytes) {
      if (!finished_) break;  // wait for the rest of the packet
      skipDamaged("incomplete packet");
      continue;
    }
    const std::string_view payload(p + kPacketHeaderBytes, payloadBytes);
    const std::uint32_t crc = crc32(payload, crc32(std::string_view(p + 2, 10)));
    if (crc != loadLe<std::uint32_t>(p + 12)) {
      skipDamaged("CRC mismatch");
      continue;
    }
    scratch_.resize(gaussian ? 0 : count);
    if (gaussian) {
      records_.resize(count);
      if (encoding == 0) {
        for (std::size_t i = 0; i < count; ++i)
          records_[i] = loadLe<std::uint64_t>(payload.data() + 8 * i);
      } else if (!detail::decodeGaussianCompactPayload(payload, count, perElement, h,
                                                       records_.data())) {
        skipDamaged("undecodable compact payload");
        continue;
      }
    } else if (encoding == 2 && detail::isFastLayout(payload)) {
      // Straight to vectors, no records between (docs/qnv-format.md, "Fast layout").
      if (!detail::decodeFastVectors(payload, count, *grid_, *vectorTables_, scratch_.data())) {
        skipDamaged("undecodable entropy payload");
        continue;
      }
    } else if (encoding != 0) {
      records_.resize(count);
      if (encoding == 1 ? !detail::decodeCompactPayload(payload, count, records_.data())
                        : !detail::decodeEntropyPayload(payload, count, *grid_, records_.data())) {
        skipDamaged(encoding == 1 ? "undecodable compact payload" : "undecodable entropy payload");
        continue;
      }
      dequantizer_->decode(records_.data(), count, scratch_.data());
    } else {
      dequantizer_->decodeBytes(payload.data(), count, scratch_.data());
    }
    offset_ += packetBytes;
    resyncing_ = false;
    ++stats_.packetsDecoded;
    ++packetsReceived_;
    stats_.vectorsDecoded += count;
    if (!anyPacket_ || sequence > highestSequence_) highestSequence_ = sequence;
    anyPacket_ = true;
    stats_.packetsMissing =
        highestSequence_ + 1 > packetsReceived_ ? highestSequence_ + 1 - packetsReceived_ : 0;
    if (gaussian && recordSink_)
      recordSink_(std::uint64_t{sequence} * capacity,
                  std::span<const std::uint64_t>(records_.data(), count));
    if (sink && !gaussian)
      sink(std::uint64_t{sequence} * capacity, std::span<const DecodedVector>(scratch_));
  }
  return true;
}

bool StreamDecoder::finish(const Sink& sink) {
  if (finished_) return complete();
  finished_ = true;
  if (!error_.empty()) return false;
  if (!header_) {
    error_ = name_ + ": no QNV header (" + std::to_string(buffer_.size()) + " bytes)";
    return false;
  }
  // Whatever still waits for bytes is either a damaged packet with good ones behind it,
  // or simply the cut-off end of the stream: scan, and keep the scan's verdict only when
  // it found another good packet.
  const DecoderStats before = stats_;
  const std::size_t warningsBefore = warnings_.size();
  const std::size_t offsetBefore = offset_;
  view_ = buffer_;
  parsePackets(sink);
  if (stats_.packetsDecoded == before.packetsDecoded) {
    stats_ = before;
    warnings_.resize(warningsBefore);
    offset_ = offsetBefore;
  }
  const std::size_t tail = buffer_.size() - offset_;
  if (tail > 0) {
    stats_.bytesSkipped += tail;
    warn(std::to_string(tail) + " bytes at the end are not a whole packet");
    offset_ = buffer_.size();
  }
  if (!complete()) {
    std::string message = "stream ends after " + std::to_string(packetsReceived_) + " of " +
                          std::to_string(header_->packetCount()) + " packets";
    if (stats_.packetsCorrupt || stats_.packetsMissing)
      message += " (" + std::to_string(stats_.packetsCorrupt) + " damaged, " +
                 std::to_string(stats_.packetsMissing) + " missing)";
    warn(message);
  }
  return complete();
}

}  // namespace gs::qnv
