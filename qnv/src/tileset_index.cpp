#include <algorithm>
#include <cmath>
#include <cstring>
#include <tuple>

#include "base/byte_order.hpp"
#include "qnv/tileset.hpp"

namespace gs::qnv {

using base::appendFloatLe;
using base::appendLe;
using base::loadFloatLe;
using base::loadLe;

namespace {

bool finite3(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool inside(const glm::vec3& v, const glm::vec3& lo, const glm::vec3& hi) {
  return v.x >= lo.x && v.y >= lo.y && v.z >= lo.z && v.x <= hi.x && v.y <= hi.y && v.z <= hi.z;
}

auto cellKey(const TilesetBrick& b) {
  return std::make_tuple(b.level, b.z, b.y, b.x);
}

std::string cellName(const TilesetBrick& b) {
  return "brick " + std::to_string(b.level) + "/" + std::to_string(b.x) + "_" +
         std::to_string(b.y) + "_" + std::to_string(b.z);
}

}  // namespace

std::string TilesetBrick::path() const {
  return "bricks/" + std::to_string(level) + "/" + std::to_string(x) + "_" + std::to_string(y) +
         "_" + std::to_string(z) + ".qnv";
}

std::string TilesetBrick::mergedPath() const {
  return "merged/" + std::to_string(level) + "/" + std::to_string(x) + "_" + std::to_string(y) +
         "_" + std::to_string(z) + ".qnv";
}

std::string serializeTilesetIndex(const TilesetIndex& index) {
  std::string out(reinterpret_cast<const char*>(kTilesetMagic.data()), kTilesetMagic.size());
  appendLe<std::uint16_t>(out, kTilesetVersion);
  appendLe<std::uint8_t>(out, index.depth);
  appendLe<std::uint8_t>(
      out, static_cast<std::uint8_t>(index.mergedCellsLog2 |
                                     (index.mergedEveryLevel ? kTilesetMergedEveryLevel : 0)));
  appendLe<std::uint32_t>(out, static_cast<std::uint32_t>(index.bricks.size()));
  out += serializeHeader(index.header);
  for (const TilesetBrick& b : index.bricks) {
    appendLe<std::uint8_t>(out, b.level);
    out.append(3, '\0');
    appendLe<std::uint32_t>(out, b.x);
    appendLe<std::uint32_t>(out, b.y);
    appendLe<std::uint32_t>(out, b.z);
    for (int i = 0; i < 3; ++i) appendFloatLe(out, b.boundsMin[i]);
    for (int i = 0; i < 3; ++i) appendFloatLe(out, b.boundsMax[i]);
    appendLe<std::uint64_t>(out, b.vectorCount);
    for (std::uint32_t h : b.histogram) appendLe<std::uint32_t>(out, h);
    appendLe<std::uint32_t>(out, static_cast<std::uint32_t>(b.packetEnds.size()));
    appendLe<std::uint64_t>(out, b.fileBytes);
  }
  for (const TilesetBrick& b : index.bricks)
    for (std::uint64_t end : b.packetEnds)
      appendLe<std::uint32_t>(out, static_cast<std::uint32_t>(end));
  appendLe<std::uint32_t>(out, crc32(out));
  return out;
}

std::optional<TilesetIndex> parseTilesetIndex(std::string_view bytes, const std::string& name,
                                              std::string& error) {
  auto fail = [&](const std::string& why) -> std::optional<TilesetIndex> {
    error = name + ": " + why;
    return std::nullopt;
  };
  const std::size_t sigBytes = std::min(bytes.size(), kTilesetMagic.size());
  if (std::memcmp(bytes.data(), kTilesetMagic.data(), sigBytes) != 0 || bytes.size() < 10)
    return fail("not a QNV tileset index (wrong signature)");
  const char* p = bytes.data();
  const auto version = loadLe<std::uint16_t>(p + 8);
  if (version != kTilesetVersion)
    return fail("QNV tileset index version " + std::to_string(version) + " is " +
                (version > kTilesetVersion ? "newer than" : "not") +
                " the version this build reads (" + std::to_string(kTilesetVersion) + ")");
  if (bytes.size() < kTilesetPreambleBytes + 4)
    return fail("truncated QNV tileset index (" + std::to_string(bytes.size()) + " bytes)");
  const std::size_t crcAt = bytes.size() - 4;
  if (crc32(bytes.substr(0, crcAt)) != loadLe<std::uint32_t>(p + crcAt))
    return fail("QNV tileset index is damaged or truncated (CRC mismatch)");

  TilesetIndex index;
  index.depth = loadLe<std::uint8_t>(p + 10);
  if (index.depth > kTilesetMaxDepth)
    return fail("octree depth " + std::to_string(index.depth) + " is more than " +
                std::to_string(kTilesetMaxDepth));
  const auto mergedByte = static_cast<std::uint8_t>(p[11]);
  index.mergedCellsLog2 = mergedByte & static_cast<std::uint8_t>(~kTilesetMergedEveryLevel);
  index.mergedEveryLevel = (mergedByte & kTilesetMergedEveryLevel) != 0;
  if (index.mergedCellsLog2 > kTilesetMaxMergedLog2)
    return fail("merged cells byte 11 is " + std::to_string(mergedByte) + ": log2 " +
                std::to_string(index.mergedCellsLog2) + " cells per axis, more than " +
                std::to_string(kTilesetMaxMergedLog2));
  if (index.mergedEveryLevel && index.mergedCellsLog2 == 0)
    return fail("merged cells byte 11 is " + std::to_string(mergedByte) +
                ": merged bricks at every level, of no cells");
  const auto brickCount = loadLe<std::uint32_t>(p + 12);
  if (brickCount > kTilesetMaxBricks)
    return fail(std::to_string(brickCount) + " bricks are more than the limit of " +
                std::to_string(kTilesetMaxBricks));
  std::string headerError;
  auto header =
      parseHeader(bytes.substr(16, kHeaderBytes), name + " (template header)", headerError);
  if (!header) {
    error = headerError;
    return std::nullopt;
  }
  index.header = *header;
  const StreamHeader& h = index.header;
  if (index.mergedEveryLevel && h.kind != StreamKind::gaussian)
    return fail("merged cells byte 11 is " + std::to_string(mergedByte) +
                ": merged bricks at every level are for Gaussian tilesets only");
  const std::uint64_t recordsEnd =
      kTilesetPreambleBytes + std::uint64_t{brickCount} * kTilesetBrickRecordBytes;
  if (recordsEnd > crcAt)
    return fail(std::to_string(brickCount) + " brick records do not fit in " +
                std::to_string(bytes.size()) + " bytes");

  const std::uint64_t per = h.recordsPerPacket();
  std::uint64_t total = 0, offsets = 0;
  index.bricks.resize(brickCount);
  std::vector<std::uint32_t> packetCounts(brickCount);
  for (std::uint32_t i = 0; i < brickCount; ++i) {
    const char* r = p + kTilesetPreambleBytes + std::size_t{i} * kTilesetBrickRecordBytes;
    TilesetBrick& b = index.bricks[i];
    b.level = loadLe<std::uint8_t>(r);
    b.x = loadLe<std::uint32_t>(r + 4);
    b.y = loadLe<std::uint32_t>(r + 8);
    b.z = loadLe<std::uint32_t>(r + 12);
    for (int k = 0; k < 3; ++k) b.boundsMin[k] = loadFloatLe(r + 16 + 4 * k);
    for (int k = 0; k < 3; ++k) b.boundsMax[k] = loadFloatLe(r + 28 + 4 * k);
    b.vectorCount = loadLe<std::uint64_t>(r + 40);
    for (std::size_t k = 0; k < kTilesetBands; ++k)
      b.histogram[k] = loadLe<std::uint32_t>(r + 48 + 4 * k);
    const auto packetCount = loadLe<std::uint32_t>(r + 112);
    b.fileBytes = loadLe<std::uint64_t>(r + 116);
    const std::string at = cellName(b);
    if (r[1] != 0 || r[2] != 0 || r[3] != 0) return fail(at + ": reserved bytes are not 0");
    if (b.level > index.depth)
      return fail(at + ": level " + std::to_string(b.level) + " is below the octree's depth " +
                  std::to_string(index.depth));
    const std::uint64_t cells = std::uint64_t{1} << b.level;
    if (b.x >= cells || b.y >= cells || b.z >= cells)
      return fail(at + ": cell coordinates are outside the " + std::to_string(cells) +
                  " cells per axis of level " + std::to_string(b.level));
    if (i > 0 && cellKey(index.bricks[i - 1]) == cellKey(b)) return fail(at + " is listed twice");
    if (i > 0 && cellKey(index.bricks[i - 1]) > cellKey(b))
      return fail(at + " is out of order (bricks are sorted by level, z, y, x)");
    if (!finite3(b.boundsMin) || !finite3(b.boundsMax) || b.boundsMin.x > b.boundsMax.x ||
        b.boundsMin.y > b.boundsMax.y || b.boundsMin.z > b.boundsMax.z)
      return fail(at + ": impossible bounding box");
    if (!inside(b.boundsMin, h.boundsMin, h.boundsMax) ||
        !inside(b.boundsMax, h.boundsMin, h.boundsMax))
      return fail(at + ": bounding box lies outside the tileset's box");
    if (b.vectorCount == 0) return fail(at + " holds no vectors");
    if (b.vectorCount > h.vectorCount - total)
      return fail(at + ": brick vector counts exceed the tileset's " +
                  std::to_string(h.vectorCount));
    total += b.vectorCount;
    std::uint64_t histogramSum = 0;
    for (std::uint32_t n : b.histogram) histogramSum += n;
    if (histogramSum != b.vectorCount)
      return fail(at + ": histogram counts " + std::to_string(histogramSum) + " vectors, not " +
                  std::to_string(b.vectorCount));
    if (packetCount != (b.vectorCount + per - 1) / per)
      return fail(at + ": " + std::to_string(packetCount) + " packets cannot hold " +
                  std::to_string(b.vectorCount) + " vectors of " + std::to_string(per) +
                  " per packet");
    offsets += packetCount;
    packetCounts[i] = packetCount;
  }
  if (total != h.vectorCount)
    return fail("bricks hold " + std::to_string(total) + " vectors, the template header says " +
                std::to_string(h.vectorCount));
  if (recordsEnd + offsets * 4 != crcAt)
    return fail(std::to_string(offsets) + " packet offsets do not match the " +
                std::to_string(crcAt - recordsEnd) + " bytes left for them");

  const char* o = p + recordsEnd;
  const std::uint64_t maxSpan = kPacketHeaderBytes + h.packetBytes;
  for (std::uint32_t i = 0; i < brickCount; ++i) {
    TilesetBrick& b = index.bricks[i];
    const std::uint64_t count = packetCounts[i];
    b.packetEnds.resize(count);
    std::uint64_t previous = kHeaderBytes;
    for (std::uint64_t k = 0; k < count; ++k, o += 4) {
      const std::uint64_t end = loadLe<std::uint32_t>(o);
      if (end <= previous + kPacketHeaderBytes || end - previous > maxSpan)
        return fail(cellName(b) + ": packet " + std::to_string(k) + " spans " +
                    (end > previous ? std::to_string(end - previous) : std::string("no")) +
                    " bytes, outside the " + std::to_string(kPacketHeaderBytes + 1) + ".." +
                    std::to_string(maxSpan) + " a packet takes");
      b.packetEnds[k] = end;
      previous = end;
    }
    if (previous != b.fileBytes)
      return fail(cellName(b) + ": its packets end at byte " + std::to_string(previous) +
                  ", not at the file's " + std::to_string(b.fileBytes) + " bytes");
  }
  return index;
}

std::uint64_t brickPrefixBytes(const TilesetBrick& brick, const StreamHeader& header,
                               std::uint64_t records) {
  if (records == 0) return kHeaderBytes;
  if (records >= brick.vectorCount || brick.packetEnds.empty()) return brick.fileBytes;
  const std::uint64_t per = std::max<std::uint64_t>(header.recordsPerPacket(), 1);
  const std::uint64_t packets =
      std::min<std::uint64_t>((records + per - 1) / per, brick.packetEnds.size());
  return brick.packetEnds[packets - 1];
}

}  // namespace gs::qnv
