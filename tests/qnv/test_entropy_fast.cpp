// The fast layout of the entropy packet coding (WriteOptions::fastEntropy, payload flag
// bit 2, docs/qnv-format.md "Fast layout"): lossless at every packet size and lane count,
// frozen by a golden stream, close in size to the original layout, and safe on cut,
// damaged and hostile payloads.
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
using gs::qnv::packets::payloadBytes;
using gs::qnv::packets::plainDecoded;
using gs::qnv::packets::resealPacket;

namespace {

// Two overlapping soft spheres, n x (n - 4) x n/2 voxels.
Volume blob(std::uint32_t n) {
  return gs::qnv::packets::sampledVolume(
      {n, n - 4, n / 2}, [n](std::uint32_t x, std::uint32_t y, std::uint32_t z) {
        const float d = std::hypot(x - n * 0.4f, y - n * 0.45f, 2.0f * z - n * 0.5f);
        const float e = std::hypot(x - n * 0.65f, y - n * 0.5f, 2.0f * z - n * 0.4f);
        return 1000.0f / (1.0f + std::exp(d - n * 0.3f)) +
               600.0f / (1.0f + std::exp(0.5f * (e - n * 0.2f)));
      });
}

// A wavy sheet of 2 n^2 triangles in a few colours.
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
      const auto k = static_cast<std::uint8_t>(((i / 7) + (j / 5)) % 4 * 60);
      m.faceColors.push_back({k, 100, 50, 255});
      m.faceColors.push_back({k, 100, 50, 255});
    }
  return m;
}

const EncodedVectors& volumeVectors() {
  static const EncodedVectors e = encodeVolume(blob(40), {});
  return e;
}

const EncodedVectors& smallVectors() {  // the golden stream's: ~1000 vectors
  static const EncodedVectors e = [] {
    VolumeEncodeOptions options;
    options.selection.fraction = 0.5;
    return encodeVolume(blob(16), options);
  }();
  return e;
}

const EncodedVectors& surfaceVectors() {
  static const EncodedVectors e = encodeSurface(sheet(50), {});
  return e;
}

WriteOptions fast(std::uint32_t bytes, bool model = false) {
  WriteOptions o{bytes, PacketEncoding::entropy};
  o.fastEntropy = true;
  o.streamModel = model;
  return o;
}

std::string goldenPath(const char* name = "blob_entropy_fast.qnv") {
  return (gs::test::sourceDir() / "tests/qnv/golden" / name).string();
}

// The first payload bytes (flags, aMin, aBits, lanes) of a stream's fast entropy packets.
std::vector<std::array<unsigned char, 5>> fastPreambles(const std::string& s) {
  std::string why;
  const auto h = parseHeader(s, "fast.qnv", why);
  REQUIRE(h);
  std::vector<std::array<unsigned char, 5>> out;
  for (std::size_t at : packetStarts(s, h->headerBytes))
    if (s[at + 10] == 2 && (s[at + kPacketHeaderBytes] & 4)) {
      std::array<unsigned char, 5> p{};
      for (std::size_t i = 0; i < p.size(); ++i)
        p[i] = static_cast<unsigned char>(s[at + kPacketHeaderBytes + i]);
      out.push_back(p);
    }
  return out;
}

}  // namespace

TEST_CASE("fast entropy packets carry the same records as plain ones at every lane count",
          "[qnv][entropy][fast]") {
  std::set<int> lanes;
  for (const EncodedVectors* e : {&volumeVectors(), &surfaceVectors()}) {
    // 1, 6, 32, 40, 80, 172, 512, 2048 and 8191 records per packet: 1 to 16 rANS lanes.
    for (std::uint32_t bytes : {8u, 48u, 256u, 320u, 640u, 1376u, 4096u, 16384u, 65528u}) {
      for (bool model : {false, true}) {
        INFO("packet bytes " << bytes << ", model " << model << ", " << e->records.size());
        const std::string slow = writeStream(*e, {bytes, PacketEncoding::entropy});
        const std::string quick = writeStream(*e, fast(bytes, model));
        for (const auto& p : fastPreambles(quick)) lanes.insert(p[4]);
        if (bytes >= 1376 && !model) CHECK(quick.size() * 100 < slow.size() * 103);
        const DecodedStream a = plainDecoded(*e, bytes);
        const DecodedStream b = decodeStream(quick, 1000);
        REQUIRE(b.finished);
        CHECK(b.stats.packetsCorrupt == 0);
        CHECK(b.vectors == e->records.size());
        CHECK(a.byFirst == b.byFirst);
      }
    }
  }
  CHECK(lanes == std::set<int>{0, 1, 2, 3, 4});  // lanes 2^0 .. 2^4 all decoded
}

TEST_CASE("the fast layout's bit report accounts for every byte", "[qnv][entropy][fast]") {
  for (const EncodedVectors* e : {&volumeVectors(), &surfaceVectors()}) {
    const std::string s = writeStream(*e, fast(16384));
    const CodingBits bits = entropyCodingBits(*e, 16384, false, true);
    CHECK(std::abs(bits.total() / 8.0 - static_cast<double>(s.size() - kHeaderBytes)) < 1.0);
    CHECK(bits.framing < bits.total() / 20);
  }
}

TEST_CASE("fast entropy packets hold any records, off the grid and at the field limits",
          "[qnv][entropy][fast]") {
  std::mt19937_64 rng(11);
  EncodedVectors e = volumeVectors();
  std::vector<std::vector<std::uint64_t>> cases;
  cases.emplace_back();
  for (int i = 0; i < 3000; ++i) cases.back().push_back(rng());  // incompressible
  cases.push_back(std::vector<std::uint64_t>(500, 0x123456789abcdef0ull));
  cases.push_back({~std::uint64_t{0}, 0, packRecord({1023, 1023, 1023, 31, 63, 32767, 255}),
                   packRecord({0, 0, 0, 0, 0, 0, 0}), packRecord({1023, 0, 1023, 31, 0, 0, 255})});
  cases.emplace_back();  // on the grid but for a few, with a wide magnitude range
  for (std::size_t i = 0; i < 9000; ++i) {
    std::uint64_t r = e.records[i % e.records.size()];
    if (i % 97 == 0) r ^= std::uint64_t{1} << 54;
    cases.back().push_back((r & ~(std::uint64_t{32767} << 8)) | ((rng() % 32768) << 8));
  }
  cases.emplace_back();  // few distinct colours and directions, raw and constant fields
  for (std::size_t i = 0; i < 5000; ++i) {
    RecordFields f{};
    f.x = static_cast<std::uint16_t>(rng() % 1024);
    f.y = static_cast<std::uint16_t>(rng() % 1024);
    f.z = 7;
    f.theta = static_cast<std::uint8_t>(rng() % 32);
    f.phi = 5;
    f.a = static_cast<std::uint16_t>(rng() % 4);
    f.c = static_cast<std::uint8_t>(rng() % 256);
    cases.back().push_back(packRecord(f));
  }
  for (const auto& records : cases) {
    e.records = records;
    for (std::uint32_t bytes : {8u, 48u, 1376u, 4096u, 65528u}) {
      const DecodedStream a = plainDecoded(e, bytes);
      const DecodedStream b = decodeStream(writeStream(e, fast(bytes)), 1 << 16);
      REQUIRE(b.finished);
      CHECK(a.byFirst == b.byFirst);
    }
  }
}

TEST_CASE("the encoder reproduces the golden fast entropy stream byte for byte",
          "[qnv][entropy][fast][golden]") {
  // 64 records per packet: grid-coded positions, two rANS lanes whose states carry the
  // first 62 magnitude offset bits (flag bit 4).
  const std::string stream = writeStream(smallVectors(), fast(512));
  if (std::getenv("GS_WRITE_GOLDEN")) std::ofstream(goldenPath(), std::ios::binary) << stream;
  const std::string golden = gs::test::readBytes(goldenPath());
  REQUIRE(golden.size() == stream.size());
  CHECK(stream == golden);
  REQUIRE(packetStarts(golden, kHeaderBytes).size() == fastPreambles(golden).size());
  for (const auto& p : fastPreambles(golden)) {
    CHECK(p[0] == (1 | 4 | 16));  // grid, fast layout, states that carry bits
    CHECK(p[3] >= 1);             // aBits: 64 of them fill both lanes' 31 bits
    CHECK(p[4] == 1);             // 2 lanes
  }
  const DecodedStream a = plainDecoded(smallVectors(), 512);
  const DecodedStream b = decodeStream(golden, 4096);
  REQUIRE(b.finished);
  CHECK(a.byFirst == b.byFirst);
}

TEST_CASE("fast entropy streams written before flag bit 4 still decode, and are larger",
          "[qnv][entropy][fast][golden]") {
  // The same records written by the encoder before the states carried bits: states from
  // 2^16, four lanes, every magnitude offset in the bit part.
  const std::string v1 = gs::test::readBytes(goldenPath("blob_entropy_fast_v1.qnv"));
  REQUIRE(v1.size() > kHeaderBytes);
  for (const auto& p : fastPreambles(v1)) {
    CHECK(p[0] == (1 | 4));
    CHECK(p[4] == 2);
  }
  const DecodedStream a = plainDecoded(smallVectors(), 512);
  const DecodedStream b = decodeStream(v1, 4096);
  REQUIRE(b.finished);
  CHECK(b.stats.packetsCorrupt == 0);
  CHECK(a.byFirst == b.byFirst);
  // Each packet saves the carried bits less the bigger start states: 2 lanes, not 4.
  const std::string now = writeStream(smallVectors(), fast(512));
  CHECK(now.size() + 8 * fastPreambles(now).size() <= v1.size());
}

TEST_CASE("every truncation of a fast entropy stream keeps the whole packets before the cut",
          "[qnv][entropy][fast]") {
  EncodedVectors e = smallVectors();
  e.records.resize(200);
  const std::string s = writeStream(e, fast(512));
  const std::vector<std::size_t> starts = packetStarts(s, kHeaderBytes);
  REQUIRE(starts.size() == 4);
  std::size_t whole = 0;
  for (std::size_t len = 0; len <= s.size(); ++len) {
    while (whole < starts.size() &&
           (whole + 1 < starts.size() ? starts[whole + 1] : s.size()) <= len)
      ++whole;
    const DecodedStream p = decodeStream(std::string_view(s).substr(0, len), 333);
    REQUIRE(p.stats.packetsDecoded == (len < kHeaderBytes ? 0 : whole));
    REQUIRE(p.finished == (len == s.size()));
  }
}

TEST_CASE("a cut or damaged fast entropy payload under a valid CRC is rejected, never read past",
          "[qnv][entropy][fast]") {
  // 64 records (2 lanes), 172 (8 lanes) and 2048 (16 lanes, the SIMD path where the CPU
  // has it; every 13th cut and byte there) per packet, with and without a model.
  for (std::uint32_t bytes : {512u, 1376u, 16384u}) {
    const std::size_t stride = bytes == 16384 ? 13 : 1;
    for (bool model : {false, true}) {
      EncodedVectors e = bytes == 512 ? smallVectors() : volumeVectors();
      e.records.resize(std::min<std::size_t>(e.records.size(), bytes == 16384 ? 2100 : 1100));
      const std::string whole = writeStream(e, fast(bytes, model));
      std::string why;
      const std::vector<std::size_t> starts =
          packetStarts(whole, parseHeader(whole, "x", why)->headerBytes);
      REQUIRE(starts.size() >= 2);
      // The damaged packet and the two around it: the packets after them would only be
      // decoded again on every try (seconds under the sanitizers).
      const std::string s = starts.size() > 3 ? whole.substr(0, starts[3]) : whole;
      const std::size_t at = starts[1];
      const std::size_t payload = payloadBytes(s, at);
      const std::size_t total = decodeStream(s, 1 << 16).vectors;
      const std::size_t lost =
          static_cast<unsigned char>(s[at + 2]) + 256u * static_cast<unsigned char>(s[at + 3]);
      INFO("packet bytes " << bytes << ", model " << model << ", payload " << payload);
      std::size_t wrong = 0;
      for (std::size_t cut = 0; cut < payload; cut += stride) {
        std::string t = s.substr(0, at + kPacketHeaderBytes + cut) +
                        s.substr(at + kPacketHeaderBytes + payload);
        resealPacket(t, at, cut);
        const DecodedStream p = decodeStream(t, 1 << 16);
        wrong += p.stats.packetsCorrupt != 1 || p.vectors != total - lost;
      }
      CHECK(wrong == 0);
      std::size_t rejected = 0, bad = 0;
      for (std::size_t i = 0; i < payload; i += stride)
        for (unsigned char x : {0x01, 0x80, 0xff}) {
          std::string t = s;
          t[at + kPacketHeaderBytes + i] = static_cast<char>(t[at + kPacketHeaderBytes + i] ^ x);
          resealPacket(t, at, payload);
          const DecodedStream p = decodeStream(t, 1 << 16);
          bad += p.vectors + lost * p.stats.packetsCorrupt != total;
          rejected += p.stats.packetsCorrupt;
        }
      CHECK(bad == 0);
      CHECK(rejected > payload / stride);
    }
  }
}
