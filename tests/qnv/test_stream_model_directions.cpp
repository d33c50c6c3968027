// Stream model kind 2 (docs/qnv-format.md, "Stream model"): the occupied blocks with their
// directions, and entropy packets with flag bit 3 that code theta and phi from their
// block's direction. Lossless in both layouts, frozen by a golden stream, and safe on cut,
// damaged and hostile models and payloads.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <set>

#include "qnv/coding.hpp"
#include "qnv/decoder.hpp"
#include "qnv/encoder.hpp"
#include "stream_support.hpp"
#include "test_support.hpp"

using namespace gs::qnv;
using gs::qnv::packets::DecodedStream;
using gs::qnv::packets::decodeStream;
using gs::qnv::packets::payloadBytes;
using gs::qnv::packets::resealPacket;

namespace {

// A rippled sphere shell in a 40 x 36 x 20 volume (spacing 1, 1, 2): gradients point
// every way, and neighbouring voxels agree.
const EncodedVectors& dirShellVectors() {
  static const EncodedVectors e =
      gs::qnv::packets::sphereShellVectors({40, 36, 20}, 19.5f, 17.5f, 19.0f, 13.0f, 0.8f, 0.06);
  return e;
}

// A latitude-longitude sphere of 2 * rings * (segments - 1) triangles, radius 10.
TriangleMesh dirSphere(int rings, int segments) {
  TriangleMesh m;
  const float pi = 3.14159265f;
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const float t = pi * i / rings, p = 2 * pi * j / segments;
      m.positions.push_back(
          {10 * std::sin(t) * std::cos(p), 10 * std::sin(t) * std::sin(p), 10 * std::cos(t)});
    }
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const auto a = static_cast<std::uint32_t>(i * segments + j),
                 b = static_cast<std::uint32_t>(i * segments + (j + 1) % segments);
      const std::uint32_t c = a + static_cast<std::uint32_t>(segments),
                          d = b + static_cast<std::uint32_t>(segments);
      if (i > 0) m.indices.insert(m.indices.end(), {a, c, b});
      if (i + 1 < rings) m.indices.insert(m.indices.end(), {b, c, d});
    }
  return m;
}

const EncodedVectors& dirSphereVectors() {
  static const EncodedVectors e = encodeSurface(dirSphere(90, 120), {});
  return e;
}

const EncodedVectors& dirSmallSphereVectors() {  // the golden stream's: 760 triangles
  static const EncodedVectors e = encodeSurface(dirSphere(20, 20), {});
  return e;
}

WriteOptions dirOptions(std::uint32_t bytes, bool fast) {
  WriteOptions w{bytes, PacketEncoding::entropy};
  w.streamModel = true;
  w.fastEntropy = fast;
  return w;
}

StreamHeader dirHeader(const std::string& s) {
  std::string why;
  const auto h = parseHeader(s, "dirs.qnv", why);
  REQUIRE(h);
  return *h;
}

// Starts of the packets whose entropy payload has flag bit 3 (directions from the blocks).
std::vector<std::size_t> directionPackets(const std::string& s) {
  std::vector<std::size_t> starts;
  for (std::size_t at = dirHeader(s).headerBytes; at + kPacketHeaderBytes <= s.size();
       at += kPacketHeaderBytes + payloadBytes(s, at))
    if (s[at + 10] == 2 && (s[at + kPacketHeaderBytes] & 8)) starts.push_back(at);
  return starts;
}

// Bits LSB first, as the entropy payload's bit part.
struct DirBits {
  std::string bytes;
  int used = 0;
  void put(std::uint32_t v, int n) {
    for (int i = 0; i < n; ++i, ++used) {
      if (used % 8 == 0) bytes += '\0';
      bytes.back() = static_cast<char>(bytes.back() | (((v >> i) & 1u) << (used % 8)));
    }
  }
};

// A model by hand: `kind`, blocks of 8^3 cells (b = 3) of a surface's 1024^3 cells, one
// occupied block, (0, 0, 0); its one chunk is an entropy payload (original layout, flags 0)
// of one record whose four fields are constants: gap token 0, theta delta `theta`, phi
// delta `phi`, colour 0. The block's direction is then (theta, phi).
std::string handModel(int kind, std::uint32_t theta, std::uint32_t phi) {
  std::string payload = {0, 0, 0, 0, 8, 0};       // flags, aMin, aBits, R = 8
  payload += std::string("\x00\x01\x00\x00", 4);  // lane 0 state 2^16, big-endian
  payload += std::string("\x00\x01\x00\x00", 4);  // lane 1
  DirBits bits;                                   // four tables, mode 0 (constant)
  bits.put(0, 4);
  bits.put(0, 5);
  bits.put(0, 4);
  bits.put(theta, 6);
  bits.put(0, 4);
  bits.put(phi, 6);
  bits.put(0, 4);
  bits.put(0, 8);
  payload += bits.bytes;                                         // 41 bits: 6 bytes
  std::string model = {static_cast<char>(kind), 3, 1, 0, 0, 0};  // kind, b, U = 1
  model += static_cast<char>(payload.size());
  model += '\0';
  return model + payload;
}

// 40 records in block (0, 0, 0) of a surface, all pointing at cell (5, 17).
EncodedVectors handRecords(const std::string& model) {
  EncodedVectors e;
  e.header.kind = StreamKind::surface;
  e.header.encoding = PacketEncoding::entropy;  // only entropy streams carry a model
  e.header.boundsMax = {1, 1, 1};
  e.header.magnitudeMin = 1;
  e.header.magnitudeMax = 2;
  e.header.model = model;
  for (std::uint16_t i = 0; i < 40; ++i) {
    RecordFields f;
    f.x = i % 8;
    f.y = static_cast<std::uint16_t>((i / 8) % 8);
    f.z = static_cast<std::uint16_t>(i % 3);
    f.theta = 5;
    f.phi = 17;
    f.a = static_cast<std::uint16_t>(1000 - i);
    e.records.push_back(packRecord(f));
  }
  return e;
}

std::string dirGoldenPath(const char* name = "sphere_model_directions.qnv") {
  return (gs::test::sourceDir() / "tests/qnv/golden" / name).string();
}

}  // namespace

TEST_CASE("kind-2 models keep every record in both layouts and make streams smaller",
          "[qnv][model][directions]") {
  for (const EncodedVectors* e : {&dirShellVectors(), &dirSphereVectors()}) {
    for (std::uint32_t bytes : {48u, 1376u, 16384u}) {
      const std::string plain = writeStream(*e, {bytes, PacketEncoding::plain});
      const DecodedStream a = decodeStream(plain);
      for (bool fast : {false, true}) {
        INFO("packet bytes " << bytes << ", fast " << fast << ", " << e->records.size()
                             << " vectors");
        WriteOptions none{bytes, PacketEncoding::entropy};
        none.fastEntropy = fast;
        const std::string entropy = writeStream(*e, none);
        const std::string modelled = writeStream(*e, dirOptions(bytes, fast));
        const StreamHeader h = dirHeader(modelled);
        CHECK(modelled.size() <= entropy.size());
        if (bytes < 16384 || e == &dirSphereVectors()) {  // (the shell is one packet there)
          REQUIRE(h.model.size() > 2);
          // These shapes' directions pay for their model (kind 2; bit 7: shared tables).
          CHECK((h.model[0] & 0x7f) == 2);
          CHECK(modelled.size() < entropy.size());
        }
        if (bytes >= 1376 && !h.model.empty()) CHECK(!directionPackets(modelled).empty());
        const DecodedStream b = decodeStream(modelled, 1000);
        REQUIRE(b.finished);
        CHECK(b.stats.packetsCorrupt == 0);
        CHECK(a.byFirst == b.byFirst);
        if (bytes >= 1376) {  // the report counts every byte (small packets may go plain)
          const CodingBits bits = entropyCodingBits(*e, bytes, true, fast);
          CHECK(std::abs(bits.total() / 8.0 - static_cast<double>(modelled.size() - kHeaderBytes)) <
                1.0);
        }
      }
    }
  }
}

TEST_CASE("a hand-made kind-2 model: its block's direction predicts, theta 32 and over refuses",
          "[qnv][model][directions]") {
  // The model's bytes as worked out above decode, in both kinds.
  CHECK(decodeStream(serializeHeader(handRecords(handModel(2, 5, 17)).header)).error.empty());
  CHECK(decodeStream(serializeHeader(handRecords(handModel(1, 0, 0)).header)).error.empty());
  // A direction outside theta's 32 cells, or any direction in kind 1, refuses the stream.
  for (const std::string& bad : {handModel(2, 32, 0), handModel(2, 63, 5), handModel(1, 5, 17),
                                 handModel(1, 0, 1), handModel(3, 5, 17)}) {
    const DecodedStream p = decodeStream(serializeHeader(handRecords(bad).header));
    CHECK(p.error.find("stream model does not decode") != std::string::npos);
  }
  for (bool fast : {false, true}) {
    INFO("fast " << fast);
    // Under the kind-2 model every record's direction is its block's: the packets code
    // theta and phi as constant zero deltas from it (flag bit 3).
    const EncodedVectors e = handRecords(handModel(2, 5, 17));
    WriteOptions w{16 * 8, PacketEncoding::entropy};
    w.fastEntropy = fast;
    const std::string s = writeStream(e, w);  // the given model is kept
    REQUIRE(dirHeader(s).model == e.header.model);
    const std::vector<std::size_t> withDirections = directionPackets(s);
    CHECK(withDirections.size() == 3);  // 16 + 16 + 8 records
    const DecodedStream a = gs::qnv::packets::plainDecoded(e, 16 * 8);
    const DecodedStream b = decodeStream(s);
    REQUIRE(b.finished);
    CHECK(a.byFirst == b.byFirst);
    // The same packets under a kind-1 model of the same block, or a kind-2 model with
    // another direction: flag bit 3 is refused without a kind-2 model; with one it is the
    // model's direction that comes out.
    StreamHeader h = dirHeader(s);
    const std::string packets = s.substr(h.headerBytes);
    h.model = handModel(1, 0, 0);
    const DecodedStream kind1 = decodeStream(serializeHeader(h) + packets);
    CHECK(kind1.error.empty());
    CHECK(kind1.vectors == 0);
    CHECK(kind1.stats.packetsCorrupt >= 1);  // (a run of damaged packets counts once)
    h.model = handModel(2, 6, 17);
    const DecodedStream other = decodeStream(serializeHeader(h) + packets);
    CHECK(other.vectors == 40);
    CHECK(other.byFirst != b.byFirst);
    // Flag bit 3 without bit 1 (blocks) is refused too.
    std::string t = s;
    const std::size_t at = withDirections[0];
    t[at + kPacketHeaderBytes] = static_cast<char>(t[at + kPacketHeaderBytes] & ~2);
    resealPacket(t, at, payloadBytes(t, at));
    const DecodedStream noBlocks = decodeStream(t);
    CHECK(noBlocks.stats.packetsCorrupt == 1);
    CHECK(noBlocks.vectors == 24);
  }
}

TEST_CASE("the encoder reproduces the golden kind-2 stream byte for byte",
          "[qnv][model][directions][golden]") {
  // 760 triangles of a sphere, 64 records per packet, the original layout.
  const std::string stream = writeStream(dirSmallSphereVectors(), dirOptions(512, false));
  if (std::getenv("GS_WRITE_GOLDEN")) std::ofstream(dirGoldenPath(), std::ios::binary) << stream;
  const std::string golden = gs::test::readBytes(dirGoldenPath());
  REQUIRE(golden.size() == stream.size());
  CHECK(stream == golden);
  const StreamHeader h = dirHeader(golden);
  REQUIRE(h.model.size() > 2);
  // Kind 2 with shared tables (bit 7; docs/qnv-format.md, "Shared tables").
  CHECK(static_cast<unsigned char>(h.model[0]) == 0x82);
  CHECK(directionPackets(golden).size() == 12);  // every packet
  const DecodedStream a = decodeStream(writeStream(dirSmallSphereVectors(), {512}));
  const DecodedStream b = decodeStream(golden, 333);
  REQUIRE(b.finished);
  CHECK(a.byFirst == b.byFirst);
}

TEST_CASE("kind-2 streams written before the shared low bits still decode, and are larger",
          "[qnv][model][directions][golden]") {
  // The sphere's triangles come in a few areas, so some packets' magnitude offsets share
  // low zero bits (docs/qnv-format.md, "Shared low bits"); the encoder before it sent them.
  const std::string v1 = gs::test::readBytes(dirGoldenPath("sphere_model_directions_v1.qnv"));
  const std::string now = gs::test::readBytes(dirGoldenPath());
  std::size_t shifted = 0;
  for (std::size_t at : directionPackets(v1))
    CHECK(static_cast<unsigned char>(v1[at + kPacketHeaderBytes + 3]) >> 4 == 0);
  for (std::size_t at : directionPackets(now))
    shifted += static_cast<unsigned char>(now[at + kPacketHeaderBytes + 3]) >> 4 != 0;
  CHECK(shifted > 0);
  CHECK(now.size() < v1.size());
  const DecodedStream a = decodeStream(writeStream(dirSmallSphereVectors(), {512}));
  const DecodedStream b = decodeStream(v1, 333);
  REQUIRE(b.finished);
  CHECK(b.stats.packetsCorrupt == 0);
  CHECK(a.byFirst == b.byFirst);
}

TEST_CASE("a hostile kind-2 model under a valid CRC is refused or decodes safely",
          "[qnv][model][directions]") {
  const std::string s = writeStream(dirSmallSphereVectors(), dirOptions(1376, false));
  const StreamHeader h = dirHeader(s);
  REQUIRE(h.model.size() > 2);
  REQUIRE(h.model[0] == 2);
  const std::string packets = s.substr(h.headerBytes);
  const std::size_t n = dirSmallSphereVectors().records.size(), per = 172, last = n % per;
  std::size_t refused = 0, tried = 0;
  auto attempt = [&](const std::string& model) {
    StreamHeader t = h;
    t.model = model;
    const DecodedStream p = decodeStream(serializeHeader(t) + packets, 999);
    ++tried;
    if (!p.error.empty()) {
      ++refused;
      CHECK(p.vectors == 0);
    } else {  // a model that still decodes: packets decode or are dropped whole
      CHECK(p.vectors <= n);
      CHECK((p.vectors % per == 0 || p.vectors % per == last));
    }
  };
  for (std::size_t cut = 1; cut < h.model.size(); ++cut) attempt(h.model.substr(0, cut));
  for (std::size_t i = 0; i < h.model.size(); ++i)
    for (unsigned char x : {0x01, 0x40, 0xff}) {
      std::string m = h.model;
      m[i] = static_cast<char>(m[i] ^ x);
      attempt(m);
    }
  CHECK(refused * 2 > tried);
}

TEST_CASE("a cut or damaged payload with flag bit 3 under a valid CRC is rejected, never read past",
          "[qnv][model][directions]") {
  for (bool fast : {false, true}) {
    for (std::uint32_t bytes : {512u, 4096u}) {          // 64 and 512 records per packet
      const std::size_t stride = bytes == 4096 ? 7 : 1;  // every 7th cut and byte there
      EncodedVectors e = dirShellVectors();
      e.records.resize(std::min<std::size_t>(e.records.size(), 1100));
      const std::string whole = writeStream(e, dirOptions(bytes, fast));
      const std::vector<std::size_t> starts = directionPackets(whole);
      REQUIRE(starts.size() >= 2);
      REQUIRE(decodeStream(whole).vectors == e.records.size());
      // The damaged packet and the two around it: the packets after them would only be
      // decoded again on every try (seconds under the sanitizers).
      const std::string s = starts.size() > 3 ? whole.substr(0, starts[3]) : whole;
      const std::size_t at = starts[1];
      const std::size_t payload = payloadBytes(s, at);
      const std::size_t total = decodeStream(s).vectors;
      const std::size_t lost =
          static_cast<unsigned char>(s[at + 2]) + 256u * static_cast<unsigned char>(s[at + 3]);
      INFO("packet bytes " << bytes << ", fast " << fast << ", payload " << payload);
      std::size_t wrong = 0;
      for (std::size_t cut = 0; cut < payload; cut += stride) {
        std::string t = s.substr(0, at + kPacketHeaderBytes + cut) +
                        s.substr(at + kPacketHeaderBytes + payload);
        resealPacket(t, at, cut);
        const DecodedStream p = decodeStream(t);
        wrong += p.stats.packetsCorrupt != 1 || p.vectors != total - lost;
      }
      CHECK(wrong == 0);
      std::size_t rejected = 0, bad = 0;
      for (std::size_t i = 0; i < payload; i += stride)
        for (unsigned char x : {0x01, 0x80, 0xff}) {
          std::string t = s;
          t[at + kPacketHeaderBytes + i] = static_cast<char>(t[at + kPacketHeaderBytes + i] ^ x);
          resealPacket(t, at, payload);
          const DecodedStream p = decodeStream(t);
          bad += p.vectors + lost * p.stats.packetsCorrupt != total;
          rejected += p.stats.packetsCorrupt;
        }
      CHECK(bad == 0);
      CHECK(rejected > payload / stride);
    }
  }
}

TEST_CASE("records of a partial block past a volume's far face refuse their packet",
          "[qnv][model][grid]") {
  // A 6 x 8 x 8 volume under the hand-made kind-1 model: one block of 8^3 indices, which
  // crosses the far x face (indices 6, 7 lie outside). 16 records with x index < 4 come
  // first (largest A), then 16 with x index 4 or 5.
  auto cell = [](std::uint32_t i, std::uint32_t dims) {
    return static_cast<std::uint16_t>(std::min<std::uint32_t>(1023, i * 1024 / (dims - 1)));
  };
  EncodedVectors e;
  e.header.kind = StreamKind::volume;
  e.header.encoding = PacketEncoding::entropy;
  e.header.volumeDims = {6, 8, 8};
  e.header.boundsMax = {5, 7, 7};
  e.header.magnitudeMin = 1;
  e.header.magnitudeMax = 2;
  e.header.model = handModel(1, 0, 0);
  for (std::uint16_t i = 0; i < 32; ++i) {
    RecordFields f;
    f.x = cell(i < 16 ? i % 4 : 4 + i % 2, 6);
    f.y = cell(i % 8, 8);
    f.z = cell((i / 2) % 8, 8);
    f.a = static_cast<std::uint16_t>(1000 - i);
    e.records.push_back(packRecord(f));
  }
  for (bool fast : {false, true}) {
    INFO("fast " << fast);
    WriteOptions w{16 * 8, PacketEncoding::entropy};
    w.fastEntropy = fast;
    const std::string s = writeStream(e, w);
    StreamHeader h = dirHeader(s);
    REQUIRE(h.model == e.header.model);
    const DecodedStream all = decodeStream(s);
    CHECK(all.vectors == 32);
    CHECK(all.stats.packetsCorrupt == 0);
    // The same packets in a 4 x 8 x 8 volume: the model's one block still covers it, but
    // the second packet's x indices 4 and 5 now lie past the far face.
    h.volumeDims = {4, 8, 8};
    h.boundsMax = {3, 7, 7};
    const DecodedStream narrower = decodeStream(serializeHeader(h) + s.substr(h.headerBytes));
    CHECK(narrower.error.empty());
    CHECK(narrower.vectors == 16);
    CHECK(narrower.stats.packetsCorrupt == 1);
  }
}
