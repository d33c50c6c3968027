#include <future>

#include "base/byte_order.hpp"
#include "compact_payload.hpp"
#include "entropy_payload.hpp"
#include "qnv/coding.hpp"
#include "qnv/error.hpp"
#include "qnv/stream.hpp"

namespace gs::qnv {

using base::appendLe;

namespace {

void appendPacketOnGrid(std::string& out, std::uint32_t sequence,
                        std::span<const std::uint64_t> records, PacketEncoding encoding,
                        const detail::PositionGrid& grid, bool fastEntropy,
                        const StreamHeader* gaussian = nullptr) {
  const std::size_t start = out.size();
  out.append("QP");
  appendLe<std::uint16_t>(out, static_cast<std::uint16_t>(records.size()));
  appendLe<std::uint32_t>(out, sequence);
  appendLe<std::uint16_t>(out, 0);  // payload bytes, patched below
  appendLe<std::uint8_t>(out, static_cast<std::uint8_t>(encoding));
  appendLe<std::uint8_t>(out, 0);
  appendLe<std::uint32_t>(out, 0);  // CRC, patched below
  const std::size_t payloadStart = out.size();
  if (encoding == PacketEncoding::compact || encoding == PacketEncoding::entropy) {
    if (gaussian)
      detail::appendGaussianCompactPayload(out, records, gaussian->recordsPerElement(), *gaussian);
    else if (encoding == PacketEncoding::compact)
      detail::appendCompactPayload(out, records);
    else
      detail::appendEntropyPayload(out, records, grid, nullptr, fastEntropy);
    // Incompressible records (or a zstd failure) fall back to plain for this packet, so
    // a payload never exceeds the plain size the decoder bounds it by.
    if (out.size() - payloadStart > records.size() * 8 || out.size() == payloadStart) {
      out.resize(payloadStart);
      out[start + 10] = static_cast<char>(PacketEncoding::plain);
      encoding = PacketEncoding::plain;
    }
  }
  if (encoding == PacketEncoding::plain)
    for (std::uint64_t r : records) appendLe<std::uint64_t>(out, r);
  const std::size_t payloadBytes = out.size() - payloadStart;
  std::string patch;
  appendLe<std::uint16_t>(patch, static_cast<std::uint16_t>(payloadBytes));
  out.replace(start + 8, 2, patch);
  const std::string_view covered(out.data() + start + 2, 10);
  std::uint32_t crc = crc32(covered);
  crc = crc32(std::string_view(out.data() + payloadStart, payloadBytes), crc);
  patch.clear();
  appendLe<std::uint32_t>(patch, crc);
  out.replace(start + 12, 4, patch);
}

}  // namespace

void appendPacket(std::string& out, std::uint32_t sequence, std::span<const std::uint64_t> records,
                  PacketEncoding encoding, const StreamHeader* header, bool fastEntropy) {
  appendPacketOnGrid(out, sequence, records, encoding,
                     header ? detail::PositionGrid::forHeader(*header) : detail::PositionGrid{},
                     fastEntropy,
                     header && header->kind == StreamKind::gaussian ? header : nullptr);
}

namespace {

// The stream for a header whose packetBytes, encoding, vectorCount and model are final.
std::string writePackets(const StreamHeader& header, std::span<const std::uint64_t> all,
                         bool fastEntropy) {
  std::string out = serializeHeader(header);
  const std::size_t per = header.recordsPerPacket();
  out.reserve(out.size() + all.size() * 8 + (all.size() / per + 1) * kPacketHeaderBytes);
  const detail::PositionGrid grid = detail::PositionGrid::forHeader(header);
  std::uint32_t sequence = 0;
  for (std::size_t first = 0; first < all.size(); first += per, ++sequence)
    appendPacketOnGrid(out, sequence, all.subspan(first, std::min(per, all.size() - first)),
                       header.encoding, grid, fastEntropy,
                       header.kind == StreamKind::gaussian ? &header : nullptr);
  return out;
}

}  // namespace

std::string writeStream(const EncodedVectors& vectors, const WriteOptions& options) {
  if (options.packetBytes < kMinPacketBytes || options.packetBytes > kMaxPacketBytes ||
      options.packetBytes % 8 != 0)
    throw InputError("packet size " + std::to_string(options.packetBytes) +
                     " bytes is not a multiple of 8 between " + std::to_string(kMinPacketBytes) +
                     " and " + std::to_string(kMaxPacketBytes));
  StreamHeader header = vectors.header;
  header.packetBytes = options.packetBytes;
  header.encoding = options.encoding;
  header.vectorCount = vectors.records.size();
  if (header.kind == StreamKind::gaussian) {
    const std::uint32_t words = header.recordsPerElement();
    if (options.packetBytes % (8 * words) != 0 || header.vectorCount % words != 0)
      throw InputError("packet size " + std::to_string(options.packetBytes) +
                       " bytes does not hold whole splats of " + std::to_string(8 * words) +
                       " bytes");
    if (header.encoding == PacketEncoding::entropy) header.encoding = PacketEncoding::compact;
    header.model.clear();
    return writePackets(header, vectors.records, false);
  }
  // A model the caller gives (say, one shared by the bricks of a space) is kept for
  // entropy packets when it decodes and no model is to be built; packets whose blocks
  // it lacks do without it.
  if (options.encoding != PacketEncoding::entropy || options.streamModel ||
      (!header.model.empty() && !detail::PositionGrid::forHeader(header).modelValid))
    header.model.clear();
  const std::span<const std::uint64_t> all(vectors.records);
  if (options.encoding != PacketEncoding::entropy || !options.streamModel)
    return writePackets(header, all, options.fastEntropy);
  // The model's saving is estimated per block size; the stream written each way decides,
  // so a model is kept only when it makes the stream smaller. The candidates (the occupied
  // blocks, then with their directions at a few block sizes) are written on threads of
  // their own beside the stream without a model; then the best one (or none) with shared
  // tables.
  std::vector<std::string> candidates = detail::streamModelCandidates(header, all);
  std::vector<std::future<std::string>> written;
  for (const std::string& model : candidates) {
    StreamHeader with = header;
    with.model = model;
    written.push_back(std::async(std::launch::async, [with, all, fast = options.fastEntropy] {
      return writePackets(with, all, fast);
    }));
  }
  std::string out = writePackets(header, all, options.fastEntropy);
  std::string best;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    std::string with = written[i].get();
    if (with.size() < out.size()) {
      out = std::move(with);
      best = candidates[i];
    }
  }
  header.model = detail::withSharedTables(header, all, best);
  if (header.model != best) {
    std::string with = writePackets(header, all, options.fastEntropy);
    if (with.size() < out.size()) out = std::move(with);
  }
  return out;
}

CodingBits entropyCodingBits(const EncodedVectors& vectors, std::uint32_t packetBytes,
                             bool streamModel, bool fastEntropy) {
  if (packetBytes < kMinPacketBytes || packetBytes > kMaxPacketBytes || packetBytes % 8 != 0)
    throw InputError("packet size " + std::to_string(packetBytes) + " bytes is out of range");
  StreamHeader header = vectors.header;
  header.model.clear();
  if (streamModel) {  // the model writeStream would keep
    WriteOptions options{packetBytes, PacketEncoding::entropy};
    options.streamModel = true;
    options.fastEntropy = fastEntropy;
    std::string error;
    header.model = parseHeader(writeStream(vectors, options), "model", error)->model;
  }
  const detail::PositionGrid grid = detail::PositionGrid::forHeader(header);
  detail::EntropyFieldBits bits;
  const std::size_t per = packetBytes / 8;
  std::string scratch;
  const std::span<const std::uint64_t> all(vectors.records);
  for (std::size_t first = 0; first < all.size(); first += per) {
    scratch.clear();
    detail::appendEntropyPayload(scratch, all.subspan(first, std::min(per, all.size() - first)),
                                 grid, &bits, fastEntropy);
    bits.framing += 8.0 * kPacketHeaderBytes;
  }
  CodingBits out;
  out.position = bits.position;
  out.direction = bits.direction;
  out.magnitude = bits.magnitude;
  out.color = bits.color;
  out.tables = bits.tables;
  out.framing = bits.framing;
  out.model = header.model.empty() ? 0.0 : 8.0 * static_cast<double>(header.model.size() + 8);
  out.blockPackets = bits.blockPackets;
  out.vectors = all.size();
  return out;
}

}  // namespace gs::qnv
