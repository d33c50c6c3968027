// The interior contributions of one share of a split tileset encode and their merge.
#include <algorithm>
#include <cstring>
#include <functional>
#include <tuple>

#include "base/byte_order.hpp"
#include "qnv/tileset_writer.hpp"

namespace gs::qnv {

using base::appendFloatLe;
using base::appendLe;
using base::loadFloatLe;
using base::loadLe;

namespace {

constexpr char kPartsMagic[8] = {'\x89', 'Q', 'N', 'P', '\r', '\n', '\x1a', '\n'};
constexpr std::size_t kNodeBytes = 24;
constexpr std::size_t kEntryBytes = 20;

}  // namespace

void writeInteriorParts(const std::vector<TilesetCell>& nodes,
                        const std::function<std::vector<InteriorEntry>(std::size_t)>& entriesOf,
                        const TilesetOptions& cut,
                        const std::function<void(std::string_view)>& sink) {
  std::string out(kPartsMagic, sizeof kPartsMagic);
  appendLe<std::uint32_t>(out, cut.brickVoxels);
  appendLe<std::uint64_t>(out, cut.brickVectors);
  appendLe<std::uint32_t>(out, static_cast<std::uint32_t>(nodes.size()));
  std::uint32_t crc = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const TilesetCell& node = nodes[i];
    const std::vector<InteriorEntry> entries = entriesOf(i);
    appendLe<std::uint8_t>(out, node.level);
    out.append(3, '\0');
    for (int a = 0; a < 3; ++a) appendLe<std::uint32_t>(out, node.cell[a]);
    appendLe<std::uint64_t>(out, entries.size());
    for (const InteriorEntry& e : entries) {
      appendFloatLe(out, e.magnitude);
      appendLe<std::uint64_t>(out, e.source);
      appendLe<std::uint64_t>(out, e.record);
    }
    crc = crc32(out, crc);
    sink(out);
    out.clear();
  }
  crc = crc32(out, crc);
  appendLe<std::uint32_t>(out, crc);
  sink(out);
}

std::string serializeInteriorParts(const InteriorParts& parts, const TilesetOptions& cut) {
  std::vector<TilesetCell> nodes;
  std::vector<const std::vector<InteriorEntry>*> lists;
  for (const auto& [node, entries] : parts) {
    nodes.push_back(node);
    lists.push_back(&entries);
  }
  std::string out;
  writeInteriorParts(
      nodes, [&](std::size_t i) { return *lists[i]; }, cut,
      [&](std::string_view bytes) { out.append(bytes); });
  return out;
}

std::optional<InteriorParts> parseInteriorParts(std::string_view bytes, const std::string& name,
                                                TilesetOptions& cut, std::string& error) {
  auto fail = [&](const std::string& why) -> std::optional<InteriorParts> {
    error = name + ": " + why;
    return std::nullopt;
  };
  if (bytes.size() < 28 || std::memcmp(bytes.data(), kPartsMagic, 8) != 0)
    return fail("not the interior part of a QNV tileset share (wrong signature or too short)");
  const std::size_t crcAt = bytes.size() - 4;
  if (crc32(bytes.substr(0, crcAt)) != loadLe<std::uint32_t>(bytes.data() + crcAt))
    return fail("damaged or truncated (CRC mismatch)");
  cut.brickVoxels = loadLe<std::uint32_t>(bytes.data() + 8);
  cut.brickVectors = loadLe<std::uint64_t>(bytes.data() + 12);
  if (cut.brickVoxels == 0 || cut.brickVectors == 0) return fail("impossible octree cut");
  const std::uint32_t nodes = loadLe<std::uint32_t>(bytes.data() + 20);
  InteriorParts parts;
  std::size_t at = 24;
  const TilesetCell* previous = nullptr;
  for (std::uint32_t i = 0; i < nodes; ++i) {
    if (crcAt - at < kNodeBytes) return fail("node " + std::to_string(i) + " is cut off");
    const char* p = bytes.data() + at;
    TilesetCell node;
    node.level = loadLe<std::uint8_t>(p);
    for (int a = 0; a < 3; ++a) node.cell[a] = loadLe<std::uint32_t>(p + 4 + 4 * a);
    const std::uint64_t count = loadLe<std::uint64_t>(p + 16);
    at += kNodeBytes;
    if (node.level > kTilesetMaxDepth || node.cell.x >> node.level || node.cell.y >> node.level ||
        node.cell.z >> node.level)
      return fail("node " + std::to_string(i) + " is not an octree cell");
    if (previous && !(*previous < node))
      return fail("node " + std::to_string(i) + " is out of order or listed twice");
    if (count > (crcAt - at) / kEntryBytes)
      return fail("node " + std::to_string(i) + " claims more entries than the file holds");
    std::vector<InteriorEntry>& entries = parts[node];
    entries.resize(count);
    for (InteriorEntry& e : entries) {
      const char* q = bytes.data() + at;
      e.magnitude = loadFloatLe(q);
      e.source = loadLe<std::uint64_t>(q + 4);
      e.record = loadLe<std::uint64_t>(q + 12);
      at += kEntryBytes;
    }
    previous = &parts.find(node)->first;
  }
  if (at != crcAt) return fail(std::to_string(crcAt - at) + " bytes after the last node");
  return parts;
}

BrickFile mergeInteriorNode(const TilesetCell& node, std::vector<InteriorEntry> entries,
                            const TilesetLayout& layout) {
  std::sort(entries.begin(), entries.end(), [](const InteriorEntry& a, const InteriorEntry& b) {
    return a.magnitude > b.magnitude || (a.magnitude == b.magnitude && a.source < b.source);
  });
  std::vector<std::uint64_t> records;
  records.reserve(entries.size());
  for (const InteriorEntry& e : entries) records.push_back(e.record);
  return writeBrick(node, layout.brickHeader(node, records.size()), records);
}

std::optional<std::vector<InteriorPartSpan>> scanInteriorParts(std::uint64_t size,
                                                               const PartReader& read,
                                                               const std::string& name,
                                                               TilesetOptions& cut,
                                                               std::string& error) {
  auto fail = [&](const std::string& why) -> std::optional<std::vector<InteriorPartSpan>> {
    error = name + ": " + why;
    return std::nullopt;
  };
  if (size < 28) return fail("not the interior part of a QNV tileset share (too short)");
  const std::uint64_t crcAt = size - 4;
  std::string piece;
  std::uint32_t crc = 0;
  for (std::uint64_t at = 0; at < crcAt;) {
    const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(crcAt - at, 1 << 20));
    piece.resize(n);
    read(at, n, piece.data());
    crc = crc32(piece, crc);
    at += n;
  }
  char head[24];
  read(0, sizeof head, head);
  char tail[4];
  read(crcAt, 4, tail);
  if (std::memcmp(head, kPartsMagic, 8) != 0)
    return fail("not the interior part of a QNV tileset share (wrong signature)");
  if (crc != loadLe<std::uint32_t>(tail)) return fail("damaged or truncated (CRC mismatch)");
  cut.brickVoxels = loadLe<std::uint32_t>(head + 8);
  cut.brickVectors = loadLe<std::uint64_t>(head + 12);
  if (cut.brickVoxels == 0 || cut.brickVectors == 0) return fail("impossible octree cut");
  const std::uint32_t nodes = loadLe<std::uint32_t>(head + 20);
  std::vector<InteriorPartSpan> spans;
  std::uint64_t at = 24;
  for (std::uint32_t i = 0; i < nodes; ++i) {
    if (crcAt - at < kNodeBytes) return fail("node " + std::to_string(i) + " is cut off");
    char p[kNodeBytes];
    read(at, kNodeBytes, p);
    InteriorPartSpan span;
    span.node.level = loadLe<std::uint8_t>(p);
    for (int a = 0; a < 3; ++a) span.node.cell[a] = loadLe<std::uint32_t>(p + 4 + 4 * a);
    span.count = loadLe<std::uint64_t>(p + 16);
    at += kNodeBytes;
    const TilesetCell& node = span.node;
    if (node.level > kTilesetMaxDepth || node.cell.x >> node.level || node.cell.y >> node.level ||
        node.cell.z >> node.level)
      return fail("node " + std::to_string(i) + " is not an octree cell");
    if (!spans.empty() && !(spans.back().node < node))
      return fail("node " + std::to_string(i) + " is out of order or listed twice");
    if (span.count > (crcAt - at) / kEntryBytes)
      return fail("node " + std::to_string(i) + " claims more entries than the file holds");
    span.offset = at;
    at += span.count * kEntryBytes;
    spans.push_back(span);
  }
  if (at != crcAt) return fail(std::to_string(crcAt - at) + " bytes after the last node");
  return spans;
}

std::vector<InteriorEntry> loadInteriorEntries(const InteriorPartSpan& span,
                                               const PartReader& read) {
  std::string bytes(static_cast<std::size_t>(span.count * kEntryBytes), '\0');
  read(span.offset, bytes.size(), bytes.data());
  std::vector<InteriorEntry> entries(static_cast<std::size_t>(span.count));
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const char* q = bytes.data() + i * kEntryBytes;
    entries[i].magnitude = loadFloatLe(q);
    entries[i].source = loadLe<std::uint64_t>(q + 4);
    entries[i].record = loadLe<std::uint64_t>(q + 12);
  }
  return entries;
}

std::vector<BrickFile> mergeInteriorParts(const std::vector<InteriorParts>& shares,
                                          const TilesetLayout& layout) {
  std::map<TilesetCell, std::vector<InteriorEntry>> nodes;
  for (const InteriorParts& share : shares)
    for (const auto& [node, entries] : share) {
      std::vector<InteriorEntry>& all = nodes[node];
      all.insert(all.end(), entries.begin(), entries.end());
    }
  std::vector<BrickFile> bricks;
  for (auto& [node, entries] : nodes)
    if (!entries.empty()) bricks.push_back(mergeInteriorNode(node, std::move(entries), layout));
  return bricks;
}

TilesetIndex assembleTilesetIndex(const TilesetLayout& layout, std::vector<TilesetBrick> bricks) {
  std::sort(bricks.begin(), bricks.end(), [](const TilesetBrick& a, const TilesetBrick& b) {
    return std::make_tuple(a.level, a.z, a.y, a.x) < std::make_tuple(b.level, b.z, b.y, b.x);
  });
  TilesetIndex index;
  index.depth = layout.depth();
  index.header = layout.templateHeader();
  index.header.vectorCount = 0;
  for (const TilesetBrick& b : bricks) index.header.vectorCount += b.vectorCount;
  index.bricks = std::move(bricks);
  return index;
}

TilesetFiles buildTileset(const SelectedVectors& selected, const TilesetOptions& options) {
  const TilesetLayout layout(selected.header, options);
  TilesetShareWriter writer(layout);
  for (const SourceVector& v : selected.vectors) writer.add(v);
  std::vector<BrickFile> bricks;
  for (const glm::uvec3& leaf : writer.openLeaves())
    if (auto brick = writer.finishLeaf(leaf)) bricks.push_back(std::move(*brick));
  for (BrickFile& b : mergeInteriorParts({writer.interior()}, layout))
    bricks.push_back(std::move(b));
  std::vector<TilesetBrick> records;
  for (const BrickFile& b : bricks) records.push_back(b.brick);
  TilesetFiles files;
  files.index = assembleTilesetIndex(layout, std::move(records));
  std::sort(bricks.begin(), bricks.end(), [](const BrickFile& a, const BrickFile& b) {
    return std::make_tuple(a.brick.level, a.brick.z, a.brick.y, a.brick.x) <
           std::make_tuple(b.brick.level, b.brick.z, b.brick.y, b.brick.x);
  });
  files.bricks = std::move(bricks);
  return files;
}

}  // namespace gs::qnv
