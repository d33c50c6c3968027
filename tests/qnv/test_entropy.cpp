// The entropy packet coding (PacketEncoding::entropy, docs/qnv-format.md "Compact
// coding"): lossless on the 64-bit records at every packet size, frozen by a golden
// stream, and safe on cut, damaged and hostile payloads.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <random>
#include <set>

#include "qnv/coding.hpp"
#include "qnv/decoder.hpp"
#include "qnv/encoder.hpp"
#include "stream_support.hpp"
#include "test_support.hpp"

using namespace gs::qnv;
using gs::qnv::packets::DecodedStream;
using gs::qnv::packets::decodeStream;
using gs::qnv::packets::packetStarts;
using gs::qnv::packets::plainDecoded;
using gs::qnv::packets::resealPacket;

namespace {

// A blob: two overlapping spheres of different density, dims x dims-4 x dims/2 voxels,
// spacing 1, 1, 2 as in CThead.
Volume blobVolume(std::uint32_t n) {
  Volume v = gs::qnv::packets::sampledVolume(
      {n, n - 4, n / 2}, [n](std::uint32_t x, std::uint32_t y, std::uint32_t z) {
        const float dx = x - n * 0.4f, dy = y - n * 0.45f, dz = 2.0f * z - n * 0.5f;
        const float ex = x - n * 0.65f, ey = y - n * 0.5f, ez = 2.0f * z - n * 0.4f;
        return 1000.0f / (1.0f + std::exp(std::sqrt(dx * dx + dy * dy + dz * dz) - n * 0.3f)) +
               600.0f /
                   (1.0f + std::exp(0.5f * (std::sqrt(ex * ex + ey * ey + ez * ez) - n * 0.2f)));
      });
  v.origin = {-3.5f, 2.0f, 0.25f};
  return v;
}

// A wavy sheet of 2 * n * n triangles, colours from a few classes.
TriangleMesh sheet(int n) {
  TriangleMesh m;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      m.positions.push_back({static_cast<float>(i), static_cast<float>(j),
                             2.0f * std::sin(0.3f * i) * std::cos(0.2f * j) + 0.01f * i * j});
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const std::uint32_t a = i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
      m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
      const std::uint8_t k = static_cast<std::uint8_t>(((i / 7) + (j / 5)) % 4 * 60);
      m.faceColors.push_back({k, 100, 50, 255});
      m.faceColors.push_back({k, 100, 50, 255});
    }
  return m;
}

const EncodedVectors& volumeVectors() {
  static const EncodedVectors e = encodeVolume(blobVolume(40), {});
  return e;
}

// The golden stream's vectors: the larger half of a 16 x 12 x 8 blob, ~3 KB coded.
const EncodedVectors& smallVectors() {
  static const EncodedVectors e = [] {
    VolumeEncodeOptions options;
    options.selection.fraction = 0.5;
    return encodeVolume(blobVolume(16), options);
  }();
  return e;
}

const EncodedVectors& surfaceVectors() {
  static const EncodedVectors e = encodeSurface(sheet(50), {});
  return e;
}

std::string goldenPath() {
  return (gs::test::sourceDir() / "tests/qnv/golden/blob_entropy.qnv").string();
}

}  // namespace

TEST_CASE("entropy packets carry the same records as plain ones at every packet size",
          "[qnv][entropy]") {
  for (const EncodedVectors* e : {&volumeVectors(), &surfaceVectors()}) {
    for (std::uint32_t bytes : {8u, 48u, 1376u, 16384u, 65528u}) {
      INFO("packet bytes " << bytes << ", " << e->records.size() << " vectors");
      const std::string plain = writeStream(*e, {bytes, PacketEncoding::plain});
      const std::string entropy = writeStream(*e, {bytes, PacketEncoding::entropy});
      if (bytes >= 1376) CHECK(entropy.size() * 4 < plain.size() * 3);
      const DecodedStream a = decodeStream(plain, 1 << 16);
      const DecodedStream b = decodeStream(entropy, 1000);
      REQUIRE(b.finished);
      CHECK(b.stats.packetsCorrupt == 0);
      CHECK(b.vectors == e->records.size());
      CHECK(a.byFirst == b.byFirst);
    }
  }
}

TEST_CASE("entropy coding is smaller than compact coding on volumes and surfaces",
          "[qnv][entropy]") {
  for (const EncodedVectors* e : {&volumeVectors(), &surfaceVectors()}) {
    const std::string compact = writeStream(*e, {16384, PacketEncoding::compact});
    const std::string entropy = writeStream(*e, {16384, PacketEncoding::entropy});
    CHECK(entropy.size() < compact.size());
    const CodingBits bits = entropyCodingBits(*e, 16384);
    CHECK(bits.vectors == e->records.size());
    // The report accounts for every payload and packet header byte.
    CHECK(std::abs(bits.total() / 8.0 - static_cast<double>(entropy.size() - kHeaderBytes)) < 1.0);
  }
}

TEST_CASE("entropy packets hold any records, off the grid and at the field limits",
          "[qnv][entropy]") {
  std::mt19937_64 rng(7);
  EncodedVectors e = volumeVectors();  // a volume header: grid mode where it fits
  std::vector<std::vector<std::uint64_t>> cases;
  cases.emplace_back();
  for (int i = 0; i < 3000; ++i) cases.back().push_back(rng());             // incompressible: plain
  cases.push_back(std::vector<std::uint64_t>(500, 0x123456789abcdef0ull));  // one record
  cases.push_back({~std::uint64_t{0}, 0, packRecord({1023, 1023, 1023, 31, 63, 32767, 255}),
                   packRecord({0, 0, 0, 0, 0, 0, 0}), packRecord({1023, 0, 1023, 31, 0, 0, 255})});
  cases.emplace_back();  // on the grid but for a few, with a wide magnitude range
  for (std::size_t i = 0; i < 2000; ++i) {
    std::uint64_t r = e.records[i % e.records.size()];
    if (i % 97 == 0) r ^= std::uint64_t{1} << 54;
    cases.back().push_back((r & ~(std::uint64_t{32767} << 8)) | ((rng() % 32768) << 8));
  }
  for (const auto& records : cases) {
    e.records = records;
    for (std::uint32_t bytes : {8u, 48u, 1376u, 65528u}) {
      const DecodedStream a = plainDecoded(e, bytes);
      const DecodedStream b =
          decodeStream(writeStream(e, {bytes, PacketEncoding::entropy}), 1 << 16);
      REQUIRE(b.finished);
      CHECK(a.byFirst == b.byFirst);
    }
  }
}

TEST_CASE("the encoder reproduces the golden entropy stream byte for byte",
          "[qnv][entropy][golden]") {
  // 16 x 12 x 8 voxels, the larger half: grid-coded positions, rANS tables, 64 records
  // per packet.
  const std::string stream = writeStream(smallVectors(), {512, PacketEncoding::entropy});
  if (std::getenv("GS_WRITE_GOLDEN")) std::ofstream(goldenPath(), std::ios::binary) << stream;
  const std::string golden = gs::test::readBytes(goldenPath());
  REQUIRE(golden.size() == stream.size());
  CHECK(stream == golden);
  // Frozen facts: the header names the entropy coding, and so does every packet.
  CHECK(golden[11] == 2);
  for (std::size_t at : packetStarts(golden, kHeaderBytes)) {
    CHECK(golden[at + 10] == 2);
    CHECK(golden[at + kPacketHeaderBytes] == 1);  // flags: positions on the voxel grid
  }
  // It decodes to exactly the plain stream's vectors.
  const DecodedStream a = plainDecoded(smallVectors(), 512);
  const DecodedStream b = decodeStream(golden, 4096);
  REQUIRE(b.finished);
  CHECK(a.byFirst == b.byFirst);
}

TEST_CASE("every truncation of an entropy stream keeps the whole packets before the cut",
          "[qnv][entropy]") {
  EncodedVectors e = smallVectors();
  e.records.resize(200);  // 4 packets, the last one short: about 1.6 KB
  const std::string s = writeStream(e, {512, PacketEncoding::entropy});
  const std::vector<std::size_t> starts = packetStarts(s, kHeaderBytes);
  REQUIRE(starts.size() == 4);
  std::size_t whole = 0;  // packets wholly inside the prefix
  for (std::size_t len = 0; len <= s.size(); ++len) {
    while (whole < starts.size() &&
           (whole + 1 < starts.size() ? starts[whole + 1] : s.size()) <= len)
      ++whole;
    const DecodedStream p = decodeStream(std::string_view(s).substr(0, len), 333);
    REQUIRE(p.stats.packetsDecoded == (len < kHeaderBytes ? 0 : whole));
    REQUIRE(p.finished == (len == s.size()));
  }
}

TEST_CASE("a cut or damaged entropy payload under a valid CRC is rejected, never read past",
          "[qnv][entropy]") {
  const std::string s = writeStream(smallVectors(), {512, PacketEncoding::entropy});
  const std::size_t at = packetStarts(s, kHeaderBytes)[3];
  const std::size_t payload =
      static_cast<unsigned char>(s[at + 8]) + 256u * static_cast<unsigned char>(s[at + 9]);
  const std::size_t total = decodeStream(s, 1 << 16).vectors;
  const std::size_t lost = static_cast<unsigned char>(s[at + 2]);
  // Every shorter payload, resealed with a matching size and CRC: the packet is dropped.
  for (std::size_t cut = 0; cut < payload; ++cut) {
    std::string t =
        s.substr(0, at + kPacketHeaderBytes + cut) + s.substr(at + kPacketHeaderBytes + payload);
    resealPacket(t, at, cut);
    const DecodedStream p = decodeStream(t, 1 << 16);
    INFO("payload cut to " << cut << " of " << payload << " bytes");
    CHECK(p.stats.packetsCorrupt == 1);
    CHECK(p.vectors == total - lost);
  }
  // Every payload byte changed, resealed: rejected, or decoded to records that are still
  // records (the decoder checks ranges, not meaning); the other packets always decode.
  std::size_t rejected = 0;
  for (std::size_t i = 0; i < payload; ++i)
    for (unsigned char x : {0x01, 0x80, 0xff}) {
      std::string t = s;
      t[at + kPacketHeaderBytes + i] = static_cast<char>(t[at + kPacketHeaderBytes + i] ^ x);
      resealPacket(t, at, payload);
      const DecodedStream p = decodeStream(t, 1 << 16);
      CHECK(p.vectors + lost * p.stats.packetsCorrupt == total);
      rejected += p.stats.packetsCorrupt;
    }
  CHECK(rejected > payload);  // most damage is caught by the payload's own checks
}

TEST_CASE("unknown packet encodings are rejected", "[qnv][entropy]") {
  std::string s = writeStream(smallVectors(), {512, PacketEncoding::entropy});
  const std::size_t at = packetStarts(s, kHeaderBytes)[0];
  s[at + 10] = 3;  // an encoding this build does not know
  const std::size_t payload =
      static_cast<unsigned char>(s[at + 8]) + 256u * static_cast<unsigned char>(s[at + 9]);
  resealPacket(s, at, payload);
  const DecodedStream p = decodeStream(s, 1 << 16);
  CHECK(p.stats.packetsCorrupt == 1);
  CHECK(p.vectors == smallVectors().records.size() - 64);
  // A header announcing an unknown encoding is refused outright.
  StreamHeader h = smallVectors().header;
  std::string header = serializeHeader(h);
  header[11] = 3;
  const std::uint32_t crc = crc32(std::string_view(header).substr(0, kHeaderBytes - 4));
  for (int i = 0; i < 4; ++i) header[kHeaderBytes - 4 + i] = static_cast<char>(crc >> (8 * i));
  std::string why;
  CHECK_FALSE(parseHeader(header, "x.qnv", why));
  CHECK(why.find("unknown packet encoding 3") != std::string::npos);
}
