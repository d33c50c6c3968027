// STUB (branch tsv): a minimal index reader and writer after the pinned layout, so that the
// viewer builds and tests before the writer branch (tsw) lands; replaced by its tileset.cpp.
#include <cstring>

#include "qnv/tileset.hpp"

namespace gs::qnv {

namespace {

template <typename T>
void put(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.append(b, sizeof(T));
}

struct Reader {
  std::string_view bytes;
  std::size_t at = 0;
  bool ok = true;
  template <typename T>
  T get() {
    T v{};
    if (at + sizeof(T) > bytes.size()) {
      ok = false;
      return v;
    }
    std::memcpy(&v, bytes.data() + at, sizeof(T));
    at += sizeof(T);
    return v;
  }
};

constexpr char kSignature[8] = {'\x89', 'Q', 'N', 'T', '\r', '\n', '\x1a', '\n'};

}  // namespace

std::string TilesetBrick::path() const {
  return "bricks/" + std::to_string(level) + "/" + std::to_string(x) + "_" + std::to_string(y) +
         "_" + std::to_string(z) + ".qnv";
}

std::string serializeTilesetIndex(const TilesetIndex& index) {
  std::string out(kSignature, 8);
  put<std::uint16_t>(out, 1);
  put<std::uint8_t>(out, index.depth);
  put<std::uint8_t>(out, 0);
  put<std::uint32_t>(out, static_cast<std::uint32_t>(index.bricks.size()));
  out += serializeHeader(index.header);
  for (const TilesetBrick& b : index.bricks) {
    put<std::uint8_t>(out, b.level);
    for (int i = 0; i < 3; ++i) put<std::uint8_t>(out, 0);
    put(out, b.x);
    put(out, b.y);
    put(out, b.z);
    for (int i = 0; i < 3; ++i) put(out, b.boundsMin[i]);
    for (int i = 0; i < 3; ++i) put(out, b.boundsMax[i]);
    put(out, b.vectorCount);
    for (std::uint32_t h : b.histogram) put(out, h);
    put(out, static_cast<std::uint32_t>(b.packetEnds.size()));
    put(out, b.fileBytes);
  }
  for (const TilesetBrick& b : index.bricks)
    for (std::uint64_t e : b.packetEnds) put(out, static_cast<std::uint32_t>(e));
  put(out, crc32(out));
  return out;
}

std::optional<TilesetIndex> parseTilesetIndex(std::string_view bytes, const std::string& name,
                                              std::string& error) {
  auto fail = [&](const std::string& why) -> std::optional<TilesetIndex> {
    error = name + ": " + why;
    return std::nullopt;
  };
  if (bytes.size() < 16 + kHeaderBytes + 4 || std::memcmp(bytes.data(), kSignature, 8) != 0)
    return fail("not a QNV tileset index");
  std::uint32_t crc = 0;
  std::memcpy(&crc, bytes.data() + bytes.size() - 4, 4);
  if (crc != crc32(bytes.substr(0, bytes.size() - 4))) return fail("index CRC mismatch");
  Reader r{bytes.substr(0, bytes.size() - 4), 8};
  if (r.get<std::uint16_t>() != 1) return fail("unknown tileset version");
  TilesetIndex index;
  index.depth = r.get<std::uint8_t>();
  r.get<std::uint8_t>();
  const std::uint32_t count = r.get<std::uint32_t>();
  if (count > (1u << 22) || std::uint64_t{count} * 120 > bytes.size())
    return fail("brick count does not fit the index");
  auto header = parseHeader(bytes.substr(16), name, error);
  if (!header) return std::nullopt;
  index.header = *header;
  r.at = 16 + kHeaderBytes;
  std::vector<std::uint32_t> packets(count);
  index.bricks.resize(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    TilesetBrick& b = index.bricks[i];
    b.level = r.get<std::uint8_t>();
    for (int k = 0; k < 3; ++k) r.get<std::uint8_t>();
    b.x = r.get<std::uint32_t>();
    b.y = r.get<std::uint32_t>();
    b.z = r.get<std::uint32_t>();
    for (int k = 0; k < 3; ++k) b.boundsMin[k] = r.get<float>();
    for (int k = 0; k < 3; ++k) b.boundsMax[k] = r.get<float>();
    b.vectorCount = r.get<std::uint64_t>();
    for (auto& h : b.histogram) h = r.get<std::uint32_t>();
    packets[i] = r.get<std::uint32_t>();
    b.fileBytes = r.get<std::uint64_t>();
    if (!r.ok) return fail("truncated brick records");
    if (b.level > index.depth) return fail("brick level above the depth");
    if (std::uint64_t{packets[i]} * 4 > bytes.size()) return fail("packet count too large");
  }
  for (std::uint32_t i = 0; i < count; ++i) {
    TilesetBrick& b = index.bricks[i];
    b.packetEnds.resize(packets[i]);
    std::uint64_t last = kHeaderBytes;
    for (auto& e : b.packetEnds) {
      e = r.get<std::uint32_t>();
      if (!r.ok || e <= last) return fail("packet offsets not increasing");
      last = e;
    }
    if (!b.packetEnds.empty() && last != b.fileBytes) return fail("last offset != file size");
  }
  if (r.at != r.bytes.size()) return fail("trailing bytes in the index");
  return index;
}

std::uint64_t brickPrefixBytes(const TilesetBrick& brick, const StreamHeader& header,
                               std::uint64_t records) {
  const std::uint64_t per = header.recordsPerPacket();
  if (records == 0 || per == 0 || brick.packetEnds.empty()) return kHeaderBytes;
  const std::uint64_t packets =
      std::min<std::uint64_t>((records + per - 1) / per, brick.packetEnds.size());
  return brick.packetEnds[packets - 1];
}

}  // namespace gs::qnv
