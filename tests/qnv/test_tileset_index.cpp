// The tileset index (index.qnvt): round trip, prefix ranges, and hostile indexes whose
// counts and ranges lie (docs/qnv-format.md, "Tilesets").
#include <catch2/catch.hpp>

#include <cstring>
#include <functional>

#include "base/byte_order.hpp"
#include "qnv/tileset.hpp"

using namespace gs::qnv;

namespace {

// A depth-1 index: the root with 5 vectors and one leaf with 2, packets of 2 records.
TilesetIndex sampleIndex() {
  TilesetIndex index;
  index.depth = 1;
  StreamHeader& h = index.header;
  h.kind = StreamKind::surface;
  h.packetBytes = 16;
  h.vectorCount = 7;
  h.boundsMin = {0, 0, 0};
  h.boundsMax = {2, 2, 2};
  h.magnitudeMin = 1.0f;
  h.magnitudeMax = 8.0f;
  TilesetBrick root;
  root.boundsMin = {0, 0, 0};
  root.boundsMax = {2, 2, 2};
  root.vectorCount = 5;
  root.histogram[15] = 1;
  root.histogram[3] = 4;
  root.packetEnds = {1132 + 32, 1132 + 64, 1132 + 88};
  root.fileBytes = 1132 + 88;
  TilesetBrick leaf;
  leaf.level = 1;
  leaf.x = 1;
  leaf.z = 1;
  leaf.boundsMin = {1, 0, 1};
  leaf.boundsMax = {2, 1, 2};
  leaf.vectorCount = 2;
  leaf.histogram[0] = 2;
  leaf.packetEnds = {1132 + 30};  // an entropy packet: shorter than plain
  leaf.fileBytes = 1132 + 30;
  index.bricks = {root, leaf};
  return index;
}

std::string fixCrc(std::string bytes) {
  bytes.resize(bytes.size() - 4);
  gs::base::appendLe<std::uint32_t>(bytes, crc32(bytes));
  return bytes;
}

// The index with `edit` applied to its fields, serialized (a writer that lies).
std::string lying(const std::function<void(TilesetIndex&)>& edit) {
  TilesetIndex index = sampleIndex();
  edit(index);
  return serializeTilesetIndex(index);
}

std::string rejection(const std::string& bytes) {
  std::string error;
  const auto parsed = parseTilesetIndex(bytes, "t/index.qnvt", error);
  CHECK_FALSE(parsed);
  CHECK(error.rfind("t/index.qnvt", 0) == 0);
  return error;
}

}  // namespace

TEST_CASE("a tileset index survives a round trip", "[qnv][tileset]") {
  const TilesetIndex index = sampleIndex();
  const std::string bytes = serializeTilesetIndex(index);
  REQUIRE(bytes.size() == 16 + 1132 + 2 * 124 + 4 * 4 + 4);
  CHECK(bytes.compare(0, 8, "\x89QNT\r\n\x1a\n") == 0);
  std::string error;
  const auto parsed = parseTilesetIndex(bytes, "index.qnvt", error);
  REQUIRE(parsed);
  CHECK(error.empty());
  CHECK(parsed->depth == 1);
  CHECK(parsed->header.vectorCount == 7);
  CHECK(parsed->header.packetBytes == 16);
  REQUIRE(parsed->bricks.size() == 2);
  const TilesetBrick& leaf = parsed->bricks[1];
  CHECK(leaf.level == 1);
  CHECK(leaf.x == 1);
  CHECK(leaf.y == 0);
  CHECK(leaf.z == 1);
  CHECK(leaf.boundsMin == glm::vec3(1, 0, 1));
  CHECK(leaf.boundsMax == glm::vec3(2, 1, 2));
  CHECK(leaf.histogram == index.bricks[1].histogram);
  CHECK(leaf.packetEnds == index.bricks[1].packetEnds);
  CHECK(leaf.fileBytes == 1162);
  CHECK(leaf.path() == "bricks/1/1_0_1.qnv");
  CHECK(parsed->bricks[0].path() == "bricks/0/0_0_0.qnv");
  CHECK(serializeTilesetIndex(*parsed) == bytes);
}

TEST_CASE("brickPrefixBytes names the bytes of a brick's first records", "[qnv][tileset]") {
  const TilesetIndex index = sampleIndex();
  const TilesetBrick& root = index.bricks[0];
  CHECK(brickPrefixBytes(root, index.header, 0) == 1132);
  CHECK(brickPrefixBytes(root, index.header, 1) == 1164);
  CHECK(brickPrefixBytes(root, index.header, 2) == 1164);
  CHECK(brickPrefixBytes(root, index.header, 3) == 1196);
  CHECK(brickPrefixBytes(root, index.header, 5) == 1220);
  CHECK(brickPrefixBytes(root, index.header, 99) == 1220);
}

TEST_CASE("an empty tileset index is valid", "[qnv][tileset]") {
  TilesetIndex index;
  std::string error;
  const auto parsed = parseTilesetIndex(serializeTilesetIndex(index), "e.qnvt", error);
  REQUIRE(parsed);
  CHECK(parsed->bricks.empty());
}

TEST_CASE("hostile tileset indexes are rejected with a sentence", "[qnv][tileset][hostile]") {
  const std::string good = serializeTilesetIndex(sampleIndex());
  std::string bad = good;
  bad[3] = 'V';
  CHECK(rejection(bad).find("wrong signature") != std::string::npos);
  bad = good;
  bad[8] = 2;
  CHECK(rejection(bad).find("version 2 is newer") != std::string::npos);
  bad = good;
  bad[200] ^= 1;
  CHECK(rejection(bad).find("CRC mismatch") != std::string::npos);
  CHECK(rejection(good.substr(0, 100)).find("truncated") != std::string::npos);
  CHECK(rejection(good + "x").find("CRC mismatch") != std::string::npos);

  CHECK(rejection(lying([](TilesetIndex& i) { i.depth = 13; })).find("depth 13") !=
        std::string::npos);
  bad = good;
  gs::base::appendLe<std::uint32_t>(bad, 0);
  bad.replace(12, 4, std::string("\x00\x00\x40\x00", 4));  // 2^22 bricks
  CHECK(rejection(fixCrc(bad)).find("do not fit") != std::string::npos);
  bad = good;
  bad.replace(12, 4, std::string("\x01\x00\x40\x00", 4));  // 2^22 + 1 bricks
  CHECK(rejection(fixCrc(bad)).find("more than the limit") != std::string::npos);
  CHECK(rejection(lying([](TilesetIndex& i) { i.depth = 0; })).find("below the octree") !=
        std::string::npos);
  CHECK(rejection(lying([](TilesetIndex& i) { i.bricks[1].x = 2; })).find("outside the 2") !=
        std::string::npos);
  CHECK(rejection(lying([](TilesetIndex& i) { i.bricks[1] = i.bricks[0]; })).find("listed twice") !=
        std::string::npos);
  CHECK(rejection(lying([](TilesetIndex& i) {
          std::swap(i.bricks[0], i.bricks[1]);
        })).find("out of order") != std::string::npos);
  CHECK(rejection(lying([](TilesetIndex& i) {
          i.bricks[1].boundsMin.x = 3;
        })).find("impossible bounding box") != std::string::npos);
  CHECK(rejection(lying([](TilesetIndex& i) {
          i.bricks[1].boundsMax.y = NAN;
        })).find("impossible bounding box") != std::string::npos);
  CHECK(rejection(lying([](TilesetIndex& i) {
          i.bricks[1].boundsMax.y = 2.5f;
        })).find("outside the tileset's box") != std::string::npos);
  CHECK(rejection(lying([](TilesetIndex& i) {
          i.bricks[1].histogram[0] = 3;
        })).find("histogram counts 3 vectors, not 2") != std::string::npos);
  CHECK(rejection(lying([](TilesetIndex& i) {
          i.header.vectorCount = 8;
        })).find("bricks hold 7 vectors, the template header says 8") != std::string::npos);
  CHECK(rejection(lying([](TilesetIndex& i) {
          i.header.vectorCount = 6;
        })).find("exceed the tileset's 6") != std::string::npos);
  CHECK(rejection(lying([](TilesetIndex& i) {
          i.bricks[1].vectorCount = 0;
          i.bricks[1].histogram[0] = 0;
          i.header.vectorCount = 5;
        })).find("holds no vectors") != std::string::npos);
  CHECK(rejection(lying([](TilesetIndex& i) {
          i.bricks[0].packetEnds.pop_back();
        })).find("2 packets cannot hold 5 vectors") != std::string::npos);
  CHECK(rejection(lying([](TilesetIndex& i) {
          i.bricks[0].packetEnds = {1164, 1150, 1220};
        })).find("packet 1 spans no bytes") != std::string::npos);
  CHECK(rejection(lying([](TilesetIndex& i) {
          i.bricks[0].packetEnds = {1164, 1180, 1220};
        })).find("packet 1 spans 16 bytes") != std::string::npos);
  CHECK(rejection(lying([](TilesetIndex& i) {
          i.bricks[0].packetEnds = {1140, 1196, 1220};
        })).find("packet 0 spans 8 bytes") != std::string::npos);
  CHECK(rejection(lying([](TilesetIndex& i) {
          i.bricks[0].packetEnds = {1164, 1200, 1220};
        })).find("packet 1 spans 36 bytes, outside the 17..32") != std::string::npos);
  CHECK(rejection(lying([](TilesetIndex& i) {
          i.bricks[0].fileBytes = 1221;
        })).find("not at the file's 1221 bytes") != std::string::npos);
  bad = good;
  bad[16 + 10] = 7;  // the template header's kind, its CRC now wrong too
  CHECK(rejection(bad).find("CRC mismatch") != std::string::npos);
  CHECK(rejection(lying([](TilesetIndex& i) {
          i.header.packetBytes = 12;
        })).find("(template header)") != std::string::npos);
  bad = good;
  bad[11] = 8;  // merged cells per axis: 2^8 is more than kTilesetMaxMergedLog2 allows
  CHECK(rejection(fixCrc(bad)).find("merged cells byte 11 is 8") != std::string::npos);
  bad[11] = 4;  // 16 merged cells per axis: read back as such
  std::string error;
  const auto merged = parseTilesetIndex(fixCrc(bad), "t/index.qnvt", error);
  REQUIRE(merged);
  CHECK(merged->mergedCellsLog2 == 4);
  CHECK_FALSE(merged->mergedEveryLevel);
  CHECK(serializeTilesetIndex(*merged) == fixCrc(bad));
  // Bit 7: merged bricks at every interior level, for Gaussian tilesets only (one is read
  // back in tests/app/test_ooc_tileset_cli.cpp); this index is of a surface.
  bad[11] = static_cast<char>(0x85);
  CHECK(rejection(fixCrc(bad))
            .find("byte 11 is 133: merged bricks at every level are for "
                  "Gaussian tilesets only") != std::string::npos);
  // deepestMergedLevel(5) is 1; with bit 7 every level below the depth has one.
  TilesetIndex every = *merged;
  every.mergedCellsLog2 = 5;
  every.mergedEveryLevel = true;
  every.depth = 4;
  CHECK(every.hasMerged(3));
  CHECK_FALSE(every.hasMerged(4));
  CHECK(static_cast<std::uint8_t>(serializeTilesetIndex(every)[11]) == 0x85);
  every.mergedEveryLevel = false;
  CHECK_FALSE(every.hasMerged(2));
  CHECK(every.hasMerged(1));
  bad[11] = static_cast<char>(0x80);  // every level of no cells
  CHECK(rejection(fixCrc(bad)).find("byte 11 is 128: merged bricks at every level, of no cells") !=
        std::string::npos);
  bad[11] = static_cast<char>(0x88);
  CHECK(rejection(fixCrc(bad)).find("byte 11 is 136: log2 8") != std::string::npos);
}

TEST_CASE("truncated and bit-flipped tileset indexes never crash", "[qnv][tileset][hostile]") {
  const std::string good = serializeTilesetIndex(sampleIndex());
  std::string error;
  for (std::size_t n = 0; n < good.size(); ++n) {
    CHECK_FALSE(parseTilesetIndex(good.substr(0, n), "t", error));
    // Truncations with a fresh CRC reach the count checks.
    if (n >= 4) (void)parseTilesetIndex(fixCrc(good.substr(0, n)), "t", error);
  }
  for (std::size_t bit = 0; bit < good.size() * 8; ++bit) {
    std::string flipped = good;
    flipped[bit / 8] = static_cast<char>(flipped[bit / 8] ^ (1 << (bit % 8)));
    CHECK_FALSE(parseTilesetIndex(flipped, "t", error));
    (void)parseTilesetIndex(fixCrc(flipped), "t", error);
  }
}
