// The stream model block (docs/qnv-format.md, "Stream model"): the occupied blocks of
// space in the header, so that entropy packets code positions among them. Lossless,
// smaller, and safe on cut, flipped and hostile model sections.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <set>

#include "qnv/coding.hpp"
#include "qnv/decoder.hpp"
#include "qnv/encoder.hpp"
#include "stream_support.hpp"

using namespace gs::qnv;
using gs::qnv::packets::DecodedStream;
using gs::qnv::packets::decodeStream;
using gs::qnv::packets::plainDecoded;

namespace {

// A hollow sphere shell in a 48 x 44 x 24 volume (spacing 1, 1, 2): its gradient sits
// on a thin surface, most blocks of the box stay empty.
const EncodedVectors& shellVectors() {
  static const EncodedVectors e =
      gs::qnv::packets::sphereShellVectors({48, 44, 24}, 20.0f, 22.0f, 22.0f, 15.0f, 0.0f, 0.05);
  return e;
}

// A paraboloid cap of 2 * n * n triangles in a box it mostly leaves empty.
const EncodedVectors& capVectors() {
  static const EncodedVectors e = [] {
    TriangleMesh m;
    const int n = 60;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        const float x = i - n / 2.0f, y = j - n / 2.0f;
        m.positions.push_back({x, y, 0.02f * (x * x + y * y)});
      }
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const std::uint32_t a = i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
        m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
      }
    return encodeSurface(m, {});
  }();
  return e;
}

std::string withModel(const EncodedVectors& e, std::uint32_t packetBytes) {
  WriteOptions w{packetBytes, PacketEncoding::entropy};
  w.streamModel = true;
  return writeStream(e, w);
}

unsigned modelKind(const std::string& s) {
  std::string why;
  const auto h = parseHeader(s, "model.qnv", why);
  REQUIRE(h);
  return h->model.empty() ? 0u : static_cast<unsigned char>(h->model[0]);
}

std::size_t headerBytesOf(const std::string& s) {
  std::string why;
  const auto h = parseHeader(s, "model.qnv", why);
  REQUIRE(h);
  return h->headerBytes;
}

}  // namespace

TEST_CASE("a stream model shrinks entropy streams and keeps every record", "[qnv][model]") {
  for (const EncodedVectors* e : {&shellVectors(), &capVectors()}) {
    for (std::uint32_t bytes : {48u, 1376u, 16384u}) {
      INFO("packet bytes " << bytes << ", " << e->records.size() << " vectors");
      const std::string plain = writeStream(*e, {bytes, PacketEncoding::plain});
      const std::string entropy = writeStream(*e, {bytes, PacketEncoding::entropy});
      const std::string modelled = withModel(*e, bytes);
      const std::size_t headerBytes = headerBytesOf(modelled);
      CHECK(modelled.size() <= entropy.size());
      if (bytes <= 1376 || e == &shellVectors()) {  // these shapes leave most blocks empty
        CHECK(headerBytes > kHeaderBytes);
        CHECK(modelled.size() < entropy.size());
      }
      const DecodedStream a = decodeStream(plain, 1 << 16);
      const DecodedStream b = decodeStream(modelled, 999);
      REQUIRE(b.finished);
      CHECK(b.stats.packetsCorrupt == 0);
      CHECK(a.byFirst == b.byFirst);
      // The report counts the model section and every packet byte (at 48 bytes some
      // packets fall back to plain, which it does not follow).
      const CodingBits bits = entropyCodingBits(*e, bytes, true);
      // Packets code positions among blocks exactly when the model has them (kind 1 or 2;
      // a model of shared tables alone is kind 0x80).
      const bool blocks = headerBytes > kHeaderBytes && (modelKind(modelled) & 0x7f) != 0;
      CHECK((bits.blockPackets > 0) == blocks);
      if (bytes >= 1376)
        CHECK(std::abs(bits.total() / 8.0 - static_cast<double>(modelled.size() - kHeaderBytes)) <
              1.0);
    }
  }
}

TEST_CASE("streams without a model and other codings keep the 1132-byte header", "[qnv][model]") {
  for (auto coding : {PacketEncoding::plain, PacketEncoding::compact}) {
    WriteOptions w{1376, coding};
    w.streamModel = true;  // ignored: only entropy packets use a model
    CHECK(headerBytesOf(writeStream(shellVectors(), w)) == kHeaderBytes);
  }
  CHECK(headerBytesOf(writeStream(shellVectors(), {1376, PacketEncoding::entropy})) ==
        kHeaderBytes);
  // Random positions fill every block: no model pays, none is written.
  EncodedVectors e = capVectors();
  std::mt19937_64 rng(11);
  for (std::uint64_t& r : e.records)
    r = (r & ((std::uint64_t{1} << 34) - 1)) | (rng() & ~((std::uint64_t{1} << 34) - 1));
  CHECK(headerBytesOf(withModel(e, 16384)) == kHeaderBytes);
  // A plain header claiming a longer header is refused.
  StreamHeader h = shellVectors().header;
  h.model.assign(std::size_t{1}, 'x');  // (operator= of a literal trips GCC 12 -Wrestrict)
  std::string header = serializeHeader(h);
  header[11] = 0;  // plain packets
  const std::uint32_t crc = crc32(std::string_view(header).substr(0, kHeaderBytes - 4));
  for (int i = 0; i < 4; ++i) header[kHeaderBytes - 4 + i] = static_cast<char>(crc >> (8 * i));
  std::string why;
  CHECK_FALSE(parseHeader(header, "x.qnv", why));
  CHECK(why.find("header size") != std::string::npos);
}

TEST_CASE("every truncation of a stream with a model keeps the whole packets before the cut",
          "[qnv][model]") {
  // 300 vectors under the model of all of them (a model given with the header is kept).
  EncodedVectors e = shellVectors();
  std::string why;
  e.header.model = parseHeader(withModel(e, 1376), "model.qnv", why)->model;
  REQUIRE(!e.header.model.empty());
  e.records.resize(300);
  const std::string s = writeStream(e, {512, PacketEncoding::entropy});
  const std::size_t headerBytes = headerBytesOf(s);
  REQUIRE(headerBytes > kHeaderBytes);
  const DecodedStream whole = decodeStream(s, 1 << 16);
  REQUIRE(whole.finished);
  std::size_t previous = 0;
  for (std::size_t len = 0; len <= s.size(); ++len) {
    const DecodedStream p = decodeStream(std::string_view(s).substr(0, len), 97);
    INFO("prefix of " << len << " bytes");
    REQUIRE(p.error.empty() == (len >= headerBytes));
    if (len < headerBytes) REQUIRE(p.vectors == 0);
    REQUIRE(p.vectors >= previous);  // packets only ever arrive
    REQUIRE(p.finished == (len == s.size()));
    previous = p.vectors;
  }
  CHECK(previous == 300);
}

TEST_CASE("every flipped bit of the model section refuses the stream", "[qnv][model]") {
  const std::string s = withModel(shellVectors(), 16384);
  const std::size_t headerBytes = headerBytesOf(s);
  REQUIRE(headerBytes > kHeaderBytes);
  for (std::size_t i = kHeaderBytes; i < headerBytes; ++i)
    for (int bit = 0; bit < 8; ++bit) {
      std::string t = s;
      t[i] = static_cast<char>(t[i] ^ (1 << bit));
      const DecodedStream p = decodeStream(t, 1 << 16);
      INFO("byte " << i << " bit " << bit);
      REQUIRE_FALSE(p.error.empty());
      REQUIRE(p.vectors == 0);
    }
}

TEST_CASE("a hostile model under a valid CRC is refused or decodes safely", "[qnv][model]") {
  const std::string s = withModel(capVectors(), 1376);
  std::string why;
  const auto h = parseHeader(s, "model.qnv", why);
  REQUIRE(h);
  REQUIRE(!h->model.empty());
  const std::string packets = s.substr(h->headerBytes);
  std::size_t refused = 0, tried = 0;
  auto attempt = [&](const std::string& model) {
    StreamHeader t = *h;
    t.model = model;
    const DecodedStream p = decodeStream(serializeHeader(t) + packets, 1 << 16);
    const std::size_t per = 172, last = capVectors().records.size() % per;
    ++tried;
    if (!p.error.empty()) {
      ++refused;
      CHECK(p.vectors == 0);
    } else {  // a model that still decodes: packets decode or are dropped whole
      CHECK(p.vectors <= capVectors().records.size());
      CHECK((p.vectors % per == 0 || p.vectors % per == last));
    }
  };
  for (std::size_t cut = 1; cut < h->model.size(); ++cut) attempt(h->model.substr(0, cut));
  for (std::size_t i = 0; i < h->model.size(); ++i)
    for (unsigned char x : {0x01, 0x40, 0xff}) {
      std::string m = h->model;
      m[i] = static_cast<char>(m[i] ^ x);
      attempt(m);
    }
  CHECK(refused * 2 > tried);  // most damage is caught by the model's own checks
}

TEST_CASE("damaged packets of a stream with a model cost only their own vectors", "[qnv][model]") {
  const std::string s = withModel(shellVectors(), 1376);
  const std::size_t headerBytes = headerBytesOf(s);
  const std::size_t total = decodeStream(s, 1 << 16).vectors;
  std::size_t at = headerBytes, packet = 0;
  while (at + kPacketHeaderBytes <= s.size()) {
    const std::size_t payload =
        static_cast<unsigned char>(s[at + 8]) + 256u * static_cast<unsigned char>(s[at + 9]);
    const std::size_t count =
        static_cast<unsigned char>(s[at + 2]) + 256u * static_cast<unsigned char>(s[at + 3]);
    if (packet++ % 3 == 0) {
      std::string t = s;
      t[at + kPacketHeaderBytes + payload / 2] ^= 0x10;
      const DecodedStream p = decodeStream(t, 1400);
      CHECK(p.stats.packetsCorrupt == 1);
      CHECK(p.vectors == total - count);
    }
    at += kPacketHeaderBytes + payload;
  }
  CHECK(packet > 3);
}

TEST_CASE("shared tables in the model replace the packets' own and keep every record",
          "[qnv][model][shared]") {
  for (const EncodedVectors* e : {&shellVectors(), &capVectors()}) {
    // Small packets (these shapes hold 2,500-3,000 vectors): tables there cost most.
    for (std::uint32_t bytes : {688u, 1376u}) {
      INFO("packet bytes " << bytes << ", " << e->records.size() << " vectors");
      const DecodedStream plain = plainDecoded(*e, bytes);
      for (bool fast : {false, true}) {
        WriteOptions options{bytes, PacketEncoding::entropy};
        options.streamModel = true;
        options.fastEntropy = fast;
        const std::string s = writeStream(*e, options);
        std::string why;
        const auto h = parseHeader(s, "shared.qnv", why);
        REQUIRE(h);
        REQUIRE(!h->model.empty());
        // The kind byte says: shared tables follow (bit 7; docs/qnv-format.md).
        CHECK((static_cast<unsigned char>(h->model[0]) & 0x80u) != 0);
        const DecodedStream d = decodeStream(s, 777);
        REQUIRE(d.finished);
        CHECK(d.stats.packetsCorrupt == 0);
        CHECK(d.byFirst == plain.byFirst);
        // The packets' tables shrink to references.
        const CodingBits own = entropyCodingBits(*e, bytes, false, fast);
        const CodingBits shared = entropyCodingBits(*e, bytes, true, fast);
        CHECK(shared.tables * 2 < own.tables);
        CHECK(shared.total() < own.total());
      }
    }
  }
}
