// The splat scene readers (splats/readers.hpp) on bunny_small in every encoding the peer,
// PlayCanvas splat-transform 3.7, writes (tests/data/splats/README.md), on hand-made PLY
// and SPZ files, and on damaged and hostile input.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "base/byte_order.hpp"
#include "base/gzip.hpp"
#include "splats/readers.hpp"
#include "test_support.hpp"

using namespace gs::splats;

namespace {

std::filesystem::path dataDir() {
  return gs::test::sourceDir() / "tests" / "data" / "splats";
}

std::string data(const std::string& file) {
  const std::string bytes = gs::test::readBytes(dataDir() / file);
  REQUIRE(!bytes.empty());
  return bytes;
}

const SideFileReader kNoFiles = [](const std::string&, std::string&, std::string& error) {
  error = "no side files";
  return false;
};

SideFileReader sogFolder() {
  return [](const std::string& relative, std::string& bytes, std::string& error) {
    bytes = gs::test::readBytes(dataDir() / "bunny_small_sog" / relative);
    if (bytes.empty()) error = "cannot read";
    return !bytes.empty();
  };
}

const GaussianCloud& reference() {
  static const GaussianCloud cloud = readPlyGaussians(data("bunny_small.ply"), "bunny_small.ply");
  return cloud;
}

/// The largest differences allowed: position (scene units, vector length), log scale,
/// 1 - |q1 . q2|, opacity, and shDc / shRest (vector length).
struct Tolerance {
  float position, logScale, rotation, opacity, dc, rest;
};

/// `cloud`'s splat matching reference splat i: the same index, or (`reordered`, for the
/// encodings splat-transform writes in Morton order) the one nearest in position, each
/// used once.
std::vector<std::size_t> match(const GaussianCloud& cloud, bool reordered) {
  const GaussianCloud& ref = reference();
  std::vector<std::size_t> m(ref.size());
  if (!reordered) {
    for (std::size_t i = 0; i < m.size(); ++i) m[i] = i;
    return m;
  }
  std::vector<char> used(cloud.size(), 0);
  for (std::size_t i = 0; i < ref.size(); ++i) {
    std::size_t best = 0;
    float bestDistance = 1e30f;
    for (std::size_t j = 0; j < cloud.size(); ++j) {
      const float d = glm::length(cloud.positions[j] - ref.positions[i]);
      if (d < bestDistance) bestDistance = d, best = j;
    }
    REQUIRE(!used[best]);  // a bijection, else the matching (or the reader) is wrong
    used[best] = 1;
    m[i] = best;
  }
  return m;
}

void requireClose(const GaussianCloud& cloud, const Tolerance& t, bool reordered, int degree) {
  const GaussianCloud& ref = reference();
  REQUIRE(cloud.size() == ref.size());
  REQUIRE(cloud.shDegree == degree);
  REQUIRE(cloud.shRest.size() == cloud.size() * static_cast<std::size_t>(cloud.shRestPerSplat()));
  const std::vector<std::size_t> m = match(cloud, reordered);
  float position = 0, logScale = 0, rotation = 0, opacity = 0, dc = 0, rest = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    const std::size_t j = m[i];
    position = std::max(position, glm::length(cloud.positions[j] - ref.positions[i]));
    for (int k = 0; k < 3; ++k)
      logScale =
          std::max(logScale, std::fabs(std::log(cloud.scales[j][k]) - std::log(ref.scales[i][k])));
    REQUIRE(std::fabs(glm::length(cloud.rotations[j]) - 1.0f) < 1e-5f);
    rotation = std::max(rotation, 1.0f - std::fabs(glm::dot(cloud.rotations[j], ref.rotations[i])));
    opacity = std::max(opacity, std::fabs(cloud.opacities[j] - ref.opacities[i]));
    dc = std::max(dc, glm::length(cloud.shDc[j] - ref.shDc[i]));
    for (int k = 0; k < cloud.shRestPerSplat(); ++k)
      rest = std::max(
          rest, glm::length(cloud.shRest[j * static_cast<std::size_t>(cloud.shRestPerSplat()) + k] -
                            ref.shRest[i * 3 + static_cast<std::size_t>(k)]));
  }
  CHECK(position <= t.position);
  CHECK(logScale <= t.logScale);
  CHECK(rotation <= t.rotation);
  CHECK(opacity <= t.opacity);
  CHECK(dc <= t.dc);
  CHECK(rest <= t.rest);
}

/// A binary little-endian Gaussian PLY of `n` splats with SH degree 3, every value
/// distinct: value v of splat i is i * 1000 + v * 0.01 (logits and logs included).
std::string syntheticPly(int n, const char* format = "binary_little_endian") {
  std::vector<std::string> names = {"x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2"};
  for (int k = 0; k < 45; ++k) names.push_back("f_rest_" + std::to_string(k));
  for (const char* p :
       {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"})
    names.push_back(p);
  std::string out = "ply\nformat " + std::string(format) +
                    " 1.0\ncomment made by test_readers\nelement vertex " + std::to_string(n) +
                    "\n";
  for (const auto& p : names) out += "property float " + p + "\n";
  out += "end_header\n";
  const bool ascii = std::string(format) == "ascii";
  for (int i = 0; i < n; ++i) {
    for (std::size_t v = 0; v < names.size(); ++v) {
      const float value = static_cast<float>(i) + static_cast<float>(v) * 0.01f;
      if (ascii) {
        out += std::to_string(value) + (v + 1 < names.size() ? " " : "\n");
      } else {
        std::uint32_t bits;
        std::memcpy(&bits, &value, 4);
        if (std::string(format) == "binary_big_endian") bits = gs::base::byteSwap(bits);
        gs::base::appendLe(out, bits);
      }
    }
  }
  return out;
}

/// A GLB like `glb` with its JSON text changed by `edit`.
std::string editGlb(const std::string& glb, const std::function<void(std::string&)>& edit) {
  REQUIRE(glb.size() > 20);
  const std::uint32_t jsonLength = gs::base::loadLe<std::uint32_t>(glb.data() + 12);
  std::string json = glb.substr(20, jsonLength);
  const std::string rest = glb.substr(20 + jsonLength);
  edit(json);
  while (json.size() % 4) json += ' ';
  std::string out = glb.substr(0, 12);
  gs::base::appendLe(out, static_cast<std::uint32_t>(json.size()));
  gs::base::appendLe(out, std::uint32_t{0x4E4F534A});
  out += json + rest;
  const std::uint32_t total = static_cast<std::uint32_t>(out.size());
  std::memcpy(out.data() + 8, &total, 4);
  return out;
}

/// A ZIP archive of `files` (name, bytes), every entry deflated: the raw deflate data cut
/// out of gs::test::gzip's member (10-byte header, 8-byte trailer of CRC-32 and size).
std::string deflatedZip(const std::vector<std::pair<std::string, std::string>>& files) {
  std::string zip, central;
  for (const auto& file : files) {
    const std::string& name = file.first;  // (clang 14 cannot capture structured bindings)
    const std::string& bytes = file.second;
    const std::string member = gs::test::gzip(bytes);
    REQUIRE(member.size() > 18);
    const std::string raw = member.substr(10, member.size() - 18);
    const std::uint32_t crc = gs::base::loadLe<std::uint32_t>(member.data() + member.size() - 8);
    const auto offset = static_cast<std::uint32_t>(zip.size());
    auto common = [&](std::string& out) {  // version needed .. extra length
      for (std::uint16_t v : {std::uint16_t{20}, std::uint16_t{0}, std::uint16_t{8},
                              std::uint16_t{0}, std::uint16_t{0}})
        gs::base::appendLe(out, v);
      gs::base::appendLe(out, crc);
      gs::base::appendLe(out, static_cast<std::uint32_t>(raw.size()));
      gs::base::appendLe(out, static_cast<std::uint32_t>(bytes.size()));
      gs::base::appendLe(out, static_cast<std::uint16_t>(name.size()));
      gs::base::appendLe(out, std::uint16_t{0});
    };
    gs::base::appendLe(zip, std::uint32_t{0x04034b50});
    common(zip);
    zip += name + raw;
    gs::base::appendLe(central, std::uint32_t{0x02014b50});
    gs::base::appendLe(central, std::uint16_t{20});
    common(central);
    for (std::uint16_t v : {std::uint16_t{0}, std::uint16_t{0}, std::uint16_t{0}})
      gs::base::appendLe(central, v);
    gs::base::appendLe(central, std::uint32_t{0});
    gs::base::appendLe(central, offset);
    central += name;
  }
  const auto cdOffset = static_cast<std::uint32_t>(zip.size());
  zip += central;
  gs::base::appendLe(zip, std::uint32_t{0x06054b50});
  for (std::uint16_t v :
       {std::uint16_t{0}, std::uint16_t{0}, static_cast<std::uint16_t>(files.size()),
        static_cast<std::uint16_t>(files.size())})
    gs::base::appendLe(zip, v);
  gs::base::appendLe(zip, static_cast<std::uint32_t>(central.size()));
  gs::base::appendLe(zip, cdOffset);
  gs::base::appendLe(zip, std::uint16_t{0});
  return zip;
}

void replace(std::string& text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("readPlyGaussians: bunny_small.ply holds the file's own values, activated") {
  const std::string bytes = data("bunny_small.ply");
  const std::size_t start = bytes.find("end_header\n") + 11;
  const GaussianCloud& c = reference();
  REQUIRE(c.size() == 3000);
  REQUIRE(c.shDegree == 1);
  // Record layout written by splat-transform: x y z rot_0..3 scale_0..2 opacity f_dc_0..2
  // f_rest_0..8 (see its header), 23 floats.
  REQUIRE(bytes.size() == start + 3000 * 23 * 4);
  for (std::size_t i : {std::size_t{0}, std::size_t{1234}, std::size_t{2999}}) {
    auto raw = [&](int k) {
      return gs::base::loadFloatLe(bytes.data() + start + (i * 23 + k) * 4);
    };
    CHECK(c.positions[i] == glm::vec3(raw(0), raw(1), raw(2)));
    const glm::quat q = glm::normalize(glm::quat(raw(3), raw(4), raw(5), raw(6)));
    CHECK(std::fabs(glm::dot(c.rotations[i], q)) == Approx(1.0f).epsilon(1e-6));
    CHECK(c.rotations[i].w == Approx(q.w).margin(1e-6));  // same sign too: w first
    for (int k = 0; k < 3; ++k) CHECK(c.scales[i][k] == Approx(std::exp(raw(7 + k))).epsilon(1e-5));
    CHECK(c.opacities[i] == Approx(sigmoid(raw(10))).epsilon(1e-6));
    CHECK(c.shDc[i] == glm::vec3(raw(11), raw(12), raw(13)));
    for (int k = 0; k < 3; ++k)  // channel-major f_rest to splat-major RGB
      CHECK(c.shRest[i * 3 + static_cast<std::size_t>(k)] ==
            glm::vec3(raw(14 + k), raw(17 + k), raw(20 + k)));
  }
}

TEST_CASE("readPlyGaussians: SH degree 3 in binary LE, binary BE and ascii") {
  for (const char* format : {"binary_little_endian", "binary_big_endian", "ascii"}) {
    INFO(format);
    const GaussianCloud c = readPlyGaussians(syntheticPly(3, format), "synthetic.ply");
    REQUIRE(c.size() == 3);
    REQUIRE(c.shDegree == 3);
    REQUIRE(c.shRest.size() == 45);
    for (std::size_t i = 0; i < 3; ++i) {
      auto v = [&](int k) { return static_cast<float>(i) + static_cast<float>(k) * 0.01f; };
      CHECK(c.positions[i].y == Approx(v(1)).margin(1e-5));
      CHECK(c.shDc[i].z == Approx(v(5)).margin(1e-5));
      for (int k = 0; k < 15; ++k) {
        const glm::vec3 rgb = c.shRest[i * 15 + static_cast<std::size_t>(k)];
        CHECK(rgb.r == Approx(v(6 + k)).margin(1e-5));
        CHECK(rgb.g == Approx(v(21 + k)).margin(1e-5));
        CHECK(rgb.b == Approx(v(36 + k)).margin(1e-5));
      }
      CHECK(c.opacities[i] == Approx(sigmoid(v(51))).margin(1e-6));
      CHECK(c.scales[i].z == Approx(std::exp(v(54))).epsilon(1e-5));
      const glm::quat q = glm::normalize(glm::quat(v(55), v(56), v(57), v(58)));
      CHECK(c.rotations[i].x == Approx(q.x).margin(1e-6));
    }
  }
}

TEST_CASE("readPlyGaussians: a 2DGS PLY without scale_2 gives flat Gaussians") {
  std::string ply = syntheticPly(2);
  replace(ply, "property float scale_2\n", "property float scale_X\n");
  const GaussianCloud c = readPlyGaussians(ply, "surfels.ply");
  CHECK(c.scales[0].z == 0.0f);
  CHECK(c.scales[1].x > 0.0f);
}

TEST_CASE("every encoding of bunny_small reads close to the .ply") {
  // Tolerances are the encodings' quantisation (max error half a step, times sqrt(3) for a
  // vector of three): SPZ positions 2^-12 fixed point, log scales 1/16, colour
  // 1 / (255 * 0.15); .compressed.ply 11/10-bit positions and log scales per 256-splat
  // chunk, 8-bit colour and opacity, SH 8 bits over [-4, 4]; SOG 16-bit log-positions,
  // 256-entry codebooks; .splat 8-bit colour, opacity and rotation, truncated on writing.
  SECTION("spz v4") {
    requireClose(readSpzGaussians(data("bunny_small.spz"), "bunny_small.spz"),
                 {2.2e-4f, 1.0f / 32 + 1e-4f, 1e-5f, 0.5f / 255 + 1e-5f, 0.023f, 0.004f}, false, 1);
  }
  SECTION("spz v3 (gzip)") {
    requireClose(readSpzGaussians(data("bunny_small_v3.spz"), "bunny_small_v3.spz"),
                 {2.2e-4f, 1.0f / 32 + 1e-4f, 1e-5f, 0.5f / 255 + 1e-5f, 0.023f, 0.004f}, false, 1);
  }
  SECTION("compressed.ply") {
    requireClose(readCompressedPlyGaussians(data("bunny_small.compressed.ply"),
                                            "bunny_small.compressed.ply"),
                 {1e-4f, 0.002f, 1e-5f, 0.5f / 255 + 1e-5f, 0.01f, 0.028f}, true, 1);
  }
  SECTION("sog bundle") {
    requireClose(readSogGaussians(data("bunny_small.sog"), "bunny_small.sog", kNoFiles),
                 {1e-5f, 0.015f, 2e-4f, 1.0f / 255 + 1e-5f, 0.01f, 0.004f}, true, 1);
  }
  SECTION("sog meta.json with its WebP files") {
    requireClose(readSogGaussians(data("bunny_small_sog/meta.json"), "meta.json", sogFolder()),
                 {1e-5f, 0.015f, 2e-4f, 1.0f / 255 + 1e-5f, 0.01f, 0.004f}, true, 1);
  }
  SECTION(".splat") {
    // Degree 0 (.splat has no SH): requireClose compares no shRest.
    requireClose(readSplatGaussians(data("bunny_small.splat"), "bunny_small.splat"),
                 {0.0f, 1e-5f, 5e-5f, 1.0f / 255 + 1e-5f, 0.024f, 0.0f}, false, 0);
  }
  SECTION("glb (KHR_gaussian_splatting, glTF axes turned back)") {
    const GaussianCloud c = readGltfGaussians(data("bunny_small.glb"), "bunny_small.glb", kNoFiles);
    requireClose(c, {1e-6f, 1e-5f, 1e-6f, 1e-6f, 1e-6f, 1e-6f}, false, 1);
    CHECK(c.colorSpace == ColorSpace::srgb);
    CHECK(c.kernel == Kernel::ellipse);
  }
  SECTION("readGaussians picks the reader") {
    for (const char* file :
         {"bunny_small.spz", "bunny_small_v3.spz", "bunny_small.compressed.ply", "bunny_small.sog",
          "bunny_small.splat", "bunny_small.glb", "bunny_small.ply"}) {
      INFO(file);
      CHECK(readGaussians(data(file), file, kNoFiles).size() == 3000);
    }
    CHECK(readGaussians(data("bunny_small_sog/meta.json"), "meta.json", sogFolder()).size() ==
          3000);
  }
}

TEST_CASE("readSpzGaussians: version 2 (first-three rotations) reads as version 3") {
  const std::string v3 = gs::base::gunzip(data("bunny_small_v3.spz"), std::size_t{1} << 24);
  const std::uint32_t n = gs::base::loadLe<std::uint32_t>(v3.data() + 8);
  REQUIRE(n == 3000);
  REQUIRE(gs::base::loadLe<std::uint32_t>(v3.data() + 4) == 3);
  const std::size_t rotations = 16 + n * (9 + 1 + 3 + 3);
  const GaussianCloud c3 = readSpzGaussians(data("bunny_small_v3.spz"), "v3.spz");
  std::string v2 = v3.substr(0, rotations);
  v2[4] = 2;
  for (std::size_t i = 0; i < n; ++i) {  // x y z of the quaternion with w >= 0, mapped to bytes
    glm::quat q = c3.rotations[i];
    if (q.w < 0) q = -q;
    for (float v : {q.x, q.y, q.z})
      v2 += static_cast<char>(
          static_cast<std::uint8_t>(std::clamp(std::round((v + 1.0f) * 127.5f), 0.0f, 255.0f)));
  }
  v2 += v3.substr(rotations + n * 4);
  const GaussianCloud c2 = readSpzGaussians(gs::test::gzip(v2), "v2.spz");
  REQUIRE(c2.size() == n);
  for (std::size_t i = 0; i < n; ++i) {
    CHECK(c2.positions[i] == c3.positions[i]);
    // 8 bits per x y z (error e <= sqrt(3) * 0.5 / 127.5 as a vector) and
    // w = sqrt(1 - |xyz|^2), whose error the square root magnifies near w = 0: w^2 is off
    // by up to 2e, so w by min(2e / 2w, sqrt(2e)); 1 - |q1 . q2| is about half the
    // squared difference (doubled: renormalising adds to it).
    const float e = std::sqrt(3.0f) * 0.5f / 127.5f, w = std::fabs(c3.rotations[i].w);
    const float dw = std::min(e / std::max(w, 1e-6f), std::sqrt(2.0f * e));
    const float tolerance = e * e + dw * dw;
    REQUIRE(1.0f - std::fabs(glm::dot(c2.rotations[i], c3.rotations[i])) < tolerance);
  }
  // Version 2 with a 4-byte rotation block fails its size check, not silently.
  std::string bad = v3;
  bad[4] = 2;
  bad.resize(16 + n * (9 + 1 + 3 + 3 + 3) + n * 9 - 1);
  CHECK_THROWS_AS(readSpzGaussians(gs::test::gzip(bad), "short.spz"), FormatError);
}

TEST_CASE("readSogGaussians: a .sog of deflated entries reads as the stored one") {
  std::vector<std::pair<std::string, std::string>> files;
  for (const char* f : {"means_l.webp", "means_u.webp", "quats.webp", "scales.webp", "sh0.webp",
                        "shN_centroids.webp", "shN_labels.webp", "meta.json"})
    files.emplace_back(f, data(std::string("bunny_small_sog/") + f));
  const std::string zip = deflatedZip(files);
  REQUIRE(detectSplatFormat(zip, "x") == SplatFormat::sog);
  const GaussianCloud deflated = readSogGaussians(zip, "deflated.sog", kNoFiles);
  const GaussianCloud folder =
      readSogGaussians(data("bunny_small_sog/meta.json"), "meta.json", sogFolder());
  REQUIRE(deflated.size() == folder.size());
  CHECK(deflated.positions == folder.positions);
  CHECK(deflated.shRest == folder.shRest);
  // Damage in the deflate data is an error, not garbage.
  std::string damaged = zip;
  damaged[60] = static_cast<char>(damaged[60] ^ 0x55);  // in means_l.webp's data
  CHECK_THROWS_AS(readSogGaussians(damaged, "damaged.sog", kNoFiles), FormatError);
  files.pop_back();  // no meta.json
  CHECK_THROWS_WITH(readSogGaussians(deflatedZip(files), "nometa.sog", kNoFiles),
                    Catch::Contains("ZIP entry 'meta.json' missing"));
}

TEST_CASE("readSogGaussians: a meta.json without its files names the missing one") {
  try {
    (void)readSogGaussians(data("bunny_small_sog/meta.json"), "scene/meta.json", kNoFiles);
    FAIL("no error");
  } catch (const FormatError& e) {
    CHECK(std::string(e.what()).find("scene/meta.json: cannot read 'means_l.webp'") == 0);
  }
  std::string meta = data("bunny_small_sog/meta.json");
  replace(meta, "\"version\":2", "\"version\":7");
  CHECK_THROWS_WITH(readSogGaussians(meta, "m.json", sogFolder()),
                    Catch::Contains("unsupported SOG version 7"));
}

TEST_CASE("readGltfGaussians: node transforms place the splats; colorSpace is read") {
  const std::string glb = data("bunny_small.glb");
  const GaussianCloud& a = reference();
  const glm::mat3 f(glm::vec3(-1, 0, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, 1));  // glTF <-> .ply
  const glm::quat r = glm::angleAxis(glm::radians(90.0f), glm::normalize(glm::vec3(0, 1, 1)));
  for (const glm::vec3 scale : {glm::vec3(2.0f), glm::vec3(2.0f, 1.0f, 0.5f)}) {
    INFO("scale " << scale.x << " " << scale.y << " " << scale.z);
    const GaussianCloud b = readGltfGaussians(
        editGlb(glb,
                [&](std::string& json) {
                  replace(json, "\"nodes\":[{\"mesh\":0}]",
                          "\"nodes\":[{\"mesh\":0,\"translation\":[1,2,3],\"rotation\":[" +
                              std::to_string(r.x) + "," + std::to_string(r.y) + "," +
                              std::to_string(r.z) + "," + std::to_string(r.w) + "],\"scale\":[" +
                              std::to_string(scale.x) + "," + std::to_string(scale.y) + "," +
                              std::to_string(scale.z) + "]}]");
                }),
        "moved.glb", kNoFiles);
    REQUIRE(b.size() == a.size());
    const glm::mat3 m = f * glm::mat3_cast(r) * glm::mat3(glm::scale(glm::mat4(1.0f), scale)) * f;
    const glm::vec3 t = f * glm::vec3(1, 2, 3);
    for (std::size_t i = 0; i < a.size(); i += 7) {
      REQUIRE(glm::length(b.positions[i] - (m * a.positions[i] + t)) < 1e-5f);
      const glm::mat3 want = m * covariance(a.scales[i], a.rotations[i]) * glm::transpose(m);
      const glm::mat3 got = covariance(b.scales[i], b.rotations[i]);
      float largest = 0, error = 0;
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) {
          largest = std::max(largest, std::fabs(want[c][k]));
          error = std::max(error, std::fabs(want[c][k] - got[c][k]));
        }
      REQUIRE(error <= 1e-4f * largest);
      if (scale.x == scale.y && scale.y == scale.z) {
        // The SH turn with the splat: colour seen along R d = colour along d before.
        const glm::mat3 turn = f * glm::mat3_cast(r) * f;
        for (const glm::vec3 d : {glm::vec3(0, 0, 1), glm::normalize(glm::vec3(1, -2, 0.5f))})
          REQUIRE(glm::length(shColor(b, i, turn * d) - shColor(a, i, d)) < 1e-4f);
      }
    }
  }
  // The same as .gltf JSON with an external buffer, read through the SideFileReader.
  const std::uint32_t jsonLength = gs::base::loadLe<std::uint32_t>(glb.data() + 12);
  std::string gltfJson = glb.substr(20, jsonLength);
  replace(gltfJson, "\"buffers\":[{\"byteLength\":288000}]",
          "\"buffers\":[{\"byteLength\":288000,\"uri\":\"bunny%20small.bin\"}]");
  const std::string bin = glb.substr(20 + jsonLength + 8);
  REQUIRE(detectSplatFormat(gltfJson, "bunny.gltf") == SplatFormat::gltf);
  std::string asked;
  const GaussianCloud fromJson = readGaussians(
      gltfJson, "bunny.gltf", [&](const std::string& relative, std::string& bytes, std::string&) {
        asked = relative;
        bytes = bin;
        return true;
      });
  CHECK(asked == "bunny small.bin");
  REQUIRE(fromJson.size() == a.size());
  CHECK(fromJson.positions[2999] == readGltfGaussians(glb, "b.glb", kNoFiles).positions[2999]);
  CHECK_THROWS_AS(readGaussians(gltfJson, "bunny.gltf", kNoFiles), FormatError);

  const GaussianCloud lin = readGltfGaussians(
      editGlb(
          glb,
          [](std::string& text) { replace(text, "srgb_rec709_display", "lin_rec709_display"); }),
      "linear.glb", kNoFiles);
  CHECK(lin.colorSpace == ColorSpace::linear);
  CHECK_THROWS_WITH(
      readGltfGaussians(
          editGlb(glb, [](std::string& text) { replace(text, "srgb_rec709_display", "acescg"); }),
          "aces.glb", kNoFiles),
      Catch::Contains("unsupported KHR_gaussian_splatting colorSpace 'acescg'"));
  CHECK_THROWS_AS(readGltfGaussians(editGlb(glb,
                                            [](std::string& text) {
                                              replace(text, "\"KHR_gaussian_splatting\":{",
                                                      "\"KHR_other\":{");
                                            }),
                                    "plain.glb", kNoFiles),
                  FormatError);
}

TEST_CASE("truncated splat files throw FormatError") {
  for (const char* file :
       {"bunny_small.ply", "bunny_small.compressed.ply", "bunny_small.spz", "bunny_small_v3.spz",
        "bunny_small.sog", "bunny_small.glb", "bunny_small.splat"}) {
    const std::string bytes = data(file);
    const SplatFormat format = detectSplatFormat(bytes, file);
    for (std::size_t length :
         {std::size_t{0}, std::size_t{1}, std::size_t{3}, std::size_t{15}, std::size_t{17},
          std::size_t{31}, std::size_t{100}, std::size_t{1001}, bytes.size() / 3 + 1,
          bytes.size() / 2 + 1, bytes.size() - 1}) {
      INFO(file << " cut to " << length << " bytes");
      const std::string cut = bytes.substr(0, length);
      CHECK_THROWS_AS(readGaussians(cut, file, kNoFiles), FormatError);
      // The format's own reader too, not only detection failing.
      switch (format) {
        case SplatFormat::ply:
          CHECK_THROWS_AS(readPlyGaussians(cut, file), FormatError);
          break;
        case SplatFormat::compressedPly:
          CHECK_THROWS_AS(readCompressedPlyGaussians(cut, file), FormatError);
          break;
        case SplatFormat::spz:
          CHECK_THROWS_AS(readSpzGaussians(cut, file), FormatError);
          break;
        case SplatFormat::sog:
          CHECK_THROWS_AS(readSogGaussians(cut, file, kNoFiles), FormatError);
          break;
        case SplatFormat::gltf:
          CHECK_THROWS_AS(readGltfGaussians(cut, file, kNoFiles), FormatError);
          break;
        case SplatFormat::splat:
          CHECK_THROWS_AS(readSplatGaussians(cut, file), FormatError);
          break;
        default:
          FAIL("undetected " << file);
      }
    }
  }
}

TEST_CASE("hostile counts are refused before anything is allocated") {
  std::string ply = syntheticPly(1);
  replace(ply, "element vertex 1", "element vertex 1000000000000");
  CHECK_THROWS_WITH(readPlyGaussians(ply, "huge.ply"), Catch::Contains("exceed the limit"));
  ply = syntheticPly(1);
  replace(ply, "element vertex 1", "element vertex 100000");
  CHECK_THROWS_WITH(readPlyGaussians(ply, "short.ply"),
                    Catch::Contains("short.ply: expected 23600000 bytes"));
  replace(ply, "binary_little_endian", "ascii");
  CHECK_THROWS_AS(readPlyGaussians(ply, "short_ascii.ply"), FormatError);
  replace(ply, "element vertex 100000", "element vertex -1");
  CHECK_THROWS_WITH(readPlyGaussians(ply, "neg.ply"), Catch::Contains("bad element count '-1'"));

  // SPZ v4 whose header and table of contents claim 2^28 splats, and a v3 one 2^31.
  std::string spz = data("bunny_small.spz");
  const std::uint32_t many = std::uint32_t{1} << 28;
  std::memcpy(spz.data() + 8, &many, 4);
  CHECK_THROWS_AS(readSpzGaussians(spz, "many.spz"), FormatError);
  std::string v3 = gs::base::gunzip(data("bunny_small_v3.spz"), std::size_t{1} << 24);
  const std::uint32_t tooMany = std::uint32_t{1} << 31;
  std::memcpy(v3.data() + 8, &tooMany, 4);
  CHECK_THROWS_WITH(readSpzGaussians(gs::test::gzip(v3), "toomany.spz"),
                    Catch::Contains("exceed the limit"));

  std::string meta = data("bunny_small_sog/meta.json");
  replace(meta, "\"count\":3000", "\"count\":1e300");
  CHECK_THROWS_WITH(readSogGaussians(meta, "nan.json", sogFolder()), Catch::Contains("'count'"));
  replace(meta, "\"count\":1e300", "\"count\":300000");
  CHECK_THROWS_WITH(readSogGaussians(meta, "big.json", sogFolder()),
                    Catch::Contains("texels for 300000 splats"));

  CHECK_THROWS_WITH(readSplatGaussians(std::string(33, '\0'), "odd.splat"),
                    Catch::Contains("odd.splat: expected a multiple of 32 bytes, got 33"));
}

TEST_CASE("detectSplatFormat names every encoding and no mesh") {
  CHECK(detectSplatFormat(data("bunny_small.ply"), "x") == SplatFormat::ply);
  CHECK(detectSplatFormat(data("bunny_small.compressed.ply"), "x") == SplatFormat::compressedPly);
  CHECK(detectSplatFormat(data("bunny_small.spz"), "x") == SplatFormat::spz);
  CHECK(detectSplatFormat(data("bunny_small_v3.spz"), "x") == SplatFormat::spz);
  CHECK(detectSplatFormat(data("bunny_small.sog"), "x") == SplatFormat::sog);
  CHECK(detectSplatFormat(data("bunny_small.sog").substr(0, 64), "scene.sog") == SplatFormat::sog);
  CHECK(detectSplatFormat(data("bunny_small_sog/meta.json"), "meta.json") == SplatFormat::sogMeta);
  CHECK(detectSplatFormat(data("bunny_small.glb"), "x") == SplatFormat::gltf);
  CHECK(detectSplatFormat(data("bunny_small.splat"), "a/b/bunny.SPLAT") == SplatFormat::splat);
  CHECK(detectSplatFormat(data("bunny_small.splat"), "bunny.bin") == SplatFormat::unknown);
  for (const char* mesh : {"cube_ascii.ply", "cube_le.ply", "cube_be.ply"}) {
    const std::string bytes =
        gs::test::readBytes(gs::test::sourceDir() / "assets" / "meshes" / mesh);
    REQUIRE(!bytes.empty());
    CHECK(detectSplatFormat(bytes, mesh) == SplatFormat::unknown);
    CHECK_THROWS_WITH(readGaussians(bytes, mesh, kNoFiles),
                      Catch::Contains("not a Gaussian splatting scene"));
    CHECK_THROWS_WITH(readPlyGaussians(bytes, mesh), Catch::Contains("property 'f_dc_0' missing"));
  }
  CHECK(detectSplatFormat("", "") == SplatFormat::unknown);
  CHECK(detectSplatFormat("{\"asset\":{\"version\":\"2.0\"}}", "a.gltf") == SplatFormat::unknown);
  CHECK_THROWS_AS(readGaussians("", "empty.spz", kNoFiles), FormatError);
  CHECK_THROWS_AS(readSpzGaussians("", "empty.spz"), FormatError);
  CHECK_THROWS_AS(readSplatGaussians("", "empty.splat"), FormatError);
  CHECK_THROWS_AS(readSogGaussians("", "empty.sog", kNoFiles), FormatError);
}

TEST_CASE("gltfDrawsOnlyGaussians tells a capture from a glTF with other primitives") {
  const std::string glb = data("bunny_small.glb");
  CHECK(gltfDrawsOnlyGaussians(glb));
  const std::uint32_t jsonLength = gs::base::loadLe<std::uint32_t>(glb.data() + 12);
  CHECK(gltfDrawsOnlyGaussians(glb.substr(0, 20 + jsonLength)));  // the JSON chunk is enough
  CHECK_FALSE(gltfDrawsOnlyGaussians(glb.substr(0, 20 + jsonLength / 2)));  // cut: not known
  const std::string json = glb.substr(20, jsonLength);
  CHECK(gltfDrawsOnlyGaussians(json));
  // A second mesh of triangles beside the splats: a world, not a capture.
  std::string mixed = json;
  const std::size_t meshes = mixed.find("\"meshes\":[");
  REQUIRE(meshes != std::string::npos);
  mixed.insert(meshes + 10, R"({"primitives":[{"attributes":{"POSITION":0}}]},)");
  CHECK_FALSE(gltfDrawsOnlyGaussians(mixed));
  CHECK_FALSE(gltfDrawsOnlyGaussians(R"({"asset":{"version":"2.0"},"meshes":[]})"));
  CHECK_FALSE(gltfDrawsOnlyGaussians(std::string(100, '[') + std::string(100, ']')));
  CHECK_FALSE(gltfDrawsOnlyGaussians("glTF"));
  CHECK_FALSE(gltfDrawsOnlyGaussians(""));
}
