// PlayCanvas SOG (readers.hpp): meta.json (version 2) and lossless WebP textures, one
// texel per splat: means_l/means_u (16-bit position between mins and maxs of
// sign(x) ln(|x| + 1)), quats (smallest three, tag 252 + index of the largest), scales
// (three indices into a 256-entry codebook of log scales), sh0 (three indices into a
// codebook of f_dc, alpha the opacity) and optional shN (a 16-bit label per splat into a
// palette of centroids, themselves indices into a codebook). A .sog is a ZIP of them.
// Decoded as splat-transform 3.7's readSogSourceV2 does (the file's own axes,
// Transform.PLY). The legacy version 1 layout is refused.
#include <webp/decode.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "reader_support.hpp"
#include "zip_reader.hpp"

namespace gs::splats {

namespace {

using detail::fail;
using nlohmann::json;

constexpr std::size_t kMaxMetaBytes = std::size_t{16} << 20;
constexpr std::size_t kMaxImageBytes = std::size_t{1} << 30;

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  std::size_t pixels() const {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  }
};

/// Decodes WebP `bytes` to RGBA, refusing (FormatError naming `file`) a picture of more
/// than `maxPixels` before allocating it.
Image decodeWebp(const std::string& bytes, std::size_t maxPixels, std::string_view name,
                 const std::string& file) {
  Image img;
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
  if (!WebPGetInfo(data, bytes.size(), &img.width, &img.height) || img.width <= 0 ||
      img.height <= 0)
    fail(name, "'" + file + "' is not a WebP image");
  if (img.pixels() > maxPixels)
    fail(name, "'" + file + "' is " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                   ", more than the " + std::to_string(maxPixels) + " pixels the scene needs");
  img.rgba.resize(img.pixels() * 4);
  if (!WebPDecodeRGBAInto(data, bytes.size(), img.rgba.data(), img.rgba.size(), img.width * 4))
    fail(name, "'" + file + "': damaged WebP data");
  return img;
}

/// Numbers of the JSON array `j` (exactly `n` of them unless n is 0), else FormatError.
std::vector<float> numbers(const json& j, std::size_t n, std::string_view name, const char* what) {
  if (!j.is_array() || (n != 0 && j.size() != n))
    fail(name, std::string("meta.json: '") + what + "' must be an array of " + std::to_string(n) +
                   " numbers");
  std::vector<float> out;
  for (const json& v : j) {
    if (!v.is_number()) fail(name, std::string("meta.json: '") + what + "' holds a non-number");
    out.push_back(detail::toFloat(v.get<double>()));
  }
  return out;
}

std::string fileName(const json& group, std::size_t k, std::string_view name, const char* what) {
  if (!group.is_object() || !group.contains("files") || !group["files"].is_array() ||
      group["files"].size() <= k || !group["files"][k].is_string())
    fail(name, std::string("meta.json: '") + what + ".files' must name " + std::to_string(k + 1) +
                   " file(s)");
  return group["files"][k].get<std::string>();
}

const json& member(const json& meta, const char* key, std::string_view name) {
  if (!meta.contains(key) || !meta[key].is_object())
    fail(name, std::string("meta.json: '") + key + "' missing");
  return meta[key];
}

float invLog(float v) {
  const float e = std::exp(std::fabs(v)) - 1.0f;
  return v < 0 ? -e : e;
}

/// A SOG scene's meta.json values and its textures decoded (4 bytes a texel), from which
/// any range of splats is decoded.
struct Sog {
  std::size_t count = 0;
  std::vector<float> mins, maxs, scaleBook, colorBook, shBook;
  Image lo, hi, q, s, c0, centroids, labels;
  int degree = 0;
  std::size_t paletteCount = 0, coeffs = 0;
  /// The textures' files: means_l, means_u, quats, scales, sh0, then, with SH bands, the
  /// centroids and the labels.
  std::vector<std::string> files;
  std::size_t maxPixels = 0;  // of a per-splat texture
};

/// Each splat's texel of each per-splat texture, from the first splat decoded on (4 bytes a
/// splat; labels null without SH bands).
struct SogTexels {
  const std::uint8_t *lo, *hi, *q, *s, *c0, *labels;
};

/// Reads meta.json `metaText` (its textures not loaded). FormatError naming `name` for a
/// bad meta.json.
Sog loadSogMeta(std::string_view metaText, std::string_view name) {
  Sog sog;
  if (metaText.size() > kMaxMetaBytes) fail(name, "meta.json is larger than 16 MiB");
  const json meta = json::parse(metaText.begin(), metaText.end(), nullptr, false);
  if (meta.is_discarded() || !meta.is_object()) fail(name, "meta.json is not a JSON object");
  if (!meta.contains("version"))
    fail(name, "SOG version 1 (no 'version' in meta.json) is not supported");
  if (!meta["version"].is_number_integer() || meta["version"].get<std::int64_t>() != 2)
    fail(name, "unsupported SOG version " + meta["version"].dump());
  if (!meta.contains("count") || !meta["count"].is_number_integer())
    fail(name, "meta.json: 'count' missing or not an integer");
  const std::int64_t count64 = meta["count"].get<std::int64_t>();
  if (count64 <= 0) fail(name, "expected at least one splat, got " + std::to_string(count64));
  if (static_cast<std::uint64_t>(count64) > kMaxSplats)
    fail(name,
         std::to_string(count64) + " splats exceed the limit of " + std::to_string(kMaxSplats));
  const std::size_t count = sog.count = static_cast<std::size_t>(count64);

  const json& means = member(meta, "means", name);
  sog.mins = numbers(means.value("mins", json()), 3, name, "means.mins");
  sog.maxs = numbers(means.value("maxs", json()), 3, name, "means.maxs");
  const json& scales = member(meta, "scales", name);
  sog.scaleBook = numbers(scales.value("codebook", json()), 256, name, "scales.codebook");
  const json& sh0 = member(meta, "sh0", name);
  sog.colorBook = numbers(sh0.value("codebook", json()), 256, name, "sh0.codebook");
  const json& quats = member(meta, "quats", name);

  // Per-splat textures: the writer makes them about sqrt(count) square, padded to 4.
  sog.maxPixels =
      2 * count + 4096 + 64 * static_cast<std::size_t>(std::sqrt(static_cast<double>(count)));
  sog.files = {fileName(means, 0, name, "means"), fileName(means, 1, name, "means"),
               fileName(quats, 0, name, "quats"), fileName(scales, 0, name, "scales"),
               fileName(sh0, 0, name, "sh0")};
  int& degree = sog.degree;
  std::size_t& coeffs = sog.coeffs;
  if (meta.contains("shN") && !meta["shN"].is_null()) {
    const json& shN = member(meta, "shN", name);
    if (!shN.contains("bands") || !shN["bands"].is_number_integer() ||
        shN["bands"].get<std::int64_t>() < 0 || shN["bands"].get<std::int64_t>() > 3)
      fail(name, "meta.json: 'shN.bands' must be 0..3");
    degree = static_cast<int>(shN["bands"].get<std::int64_t>());
    if (!shN.contains("count") || !shN["count"].is_number_integer() ||
        shN["count"].get<std::int64_t>() < 0 || shN["count"].get<std::int64_t>() > 65536)
      fail(name, "meta.json: 'shN.count' must be 0..65536");
    sog.paletteCount = static_cast<std::size_t>(shN["count"].get<std::int64_t>());
    if (degree > 0) {
      coeffs = static_cast<std::size_t>(shCoefficients(degree) - 1);
      sog.shBook = numbers(shN.value("codebook", json()), 256, name, "shN.codebook");
      sog.files.push_back(fileName(shN, 0, name, "shN"));
      sog.files.push_back(fileName(shN, 1, name, "shN"));
    }
  }
  return sog;
}

/// Reads meta.json `metaText` and decodes the textures `load` gives by name. FormatError
/// naming `name` for a bad meta.json, a missing or damaged texture, or one too small or
/// too large for the count.
Sog loadSog(std::string_view metaText, std::string_view name,
            const std::function<std::string(const std::string&)>& load) {
  Sog sog = loadSogMeta(metaText, name);
  auto texture = [&](const std::string& file) {
    Image img = decodeWebp(load(file), sog.maxPixels, name, file);
    if (img.pixels() < sog.count)
      fail(name, "'" + file + "' holds " + std::to_string(img.pixels()) + " texels for " +
                     std::to_string(sog.count) + " splats");
    return img;
  };
  sog.lo = texture(sog.files[0]);
  sog.hi = texture(sog.files[1]);
  sog.q = texture(sog.files[2]);
  sog.s = texture(sog.files[3]);
  sog.c0 = texture(sog.files[4]);
  if (sog.coeffs > 0) {
    const std::string& cFile = sog.files[5];
    sog.centroids = decodeWebp(load(cFile), 64 * sog.coeffs * 1024, name, cFile);
    if (static_cast<std::size_t>(sog.centroids.width) != 64 * sog.coeffs)
      fail(name, "expected '" + cFile + "' " + std::to_string(64 * sog.coeffs) +
                     " texels wide, got " + std::to_string(sog.centroids.width));
    sog.labels = texture(sog.files[6]);
  }
  return sog;
}

/// Decodes n splats of `sog` from their texels `t` into `cloud` (allocated for n at its
/// degree), with the SH centroids of sog.centroids.
void decodeSplats(const Sog& sog, const SogTexels& t, std::size_t n, GaussianCloud& cloud) {
  const std::vector<float>&mins = sog.mins, &maxs = sog.maxs, &scaleBook = sog.scaleBook,
        &colorBook = sog.colorBook, &shBook = sog.shBook;
  const Image& centroids = sog.centroids;
  const std::size_t coeffs = sog.coeffs, paletteCount = sog.paletteCount;
  const float range[3] = {maxs[0] - mins[0] != 0.0f ? maxs[0] - mins[0] : 1.0f,
                          maxs[1] - mins[1] != 0.0f ? maxs[1] - mins[1] : 1.0f,
                          maxs[2] - mins[2] != 0.0f ? maxs[2] - mins[2] : 1.0f};
  constexpr int kQuatIndex[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  const float invSqrt2 = 0.70710678118654752f;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t o = i * 4;
    for (int k = 0; k < 3; ++k) {
      const unsigned v = t.lo[o + k] | (static_cast<unsigned>(t.hi[o + k]) << 8);
      cloud.positions[i][k] = invLog(mins[k] + range[k] * (static_cast<float>(v) / 65535.0f));
    }
    const unsigned tag = t.q[o + 3];
    if (tag >= 252) {
      float wxyz[4] = {0, 0, 0, 0};
      float sum = 0.0f;
      for (int k = 0; k < 3; ++k) {
        const float v = (static_cast<float>(t.q[o + k]) / 255.0f * 2.0f - 1.0f) * invSqrt2;
        wxyz[kQuatIndex[tag - 252][k]] = v;
        sum += v * v;
      }
      wxyz[tag - 252] = std::sqrt(std::max(0.0f, 1.0f - sum));
      cloud.rotations[i] = detail::unitQuat(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
    }  // else the identity allocate() left
    cloud.scales[i] =
        glm::exp(glm::vec3(scaleBook[t.s[o]], scaleBook[t.s[o + 1]], scaleBook[t.s[o + 2]]));
    cloud.shDc[i] = glm::vec3(colorBook[t.c0[o]], colorBook[t.c0[o + 1]], colorBook[t.c0[o + 2]]);
    cloud.opacities[i] = static_cast<float>(t.c0[o + 3]) / 255.0f;
    if (coeffs == 0) continue;
    const std::size_t label = t.labels[o] | (static_cast<std::size_t>(t.labels[o + 1]) << 8);
    glm::vec3* rest = cloud.shRest.data() + i * coeffs;
    if (label >= paletteCount) continue;  // zeros, as splat-transform
    const std::size_t cy = label / 64, cxBase = (label % 64) * coeffs;
    for (std::size_t j = 0; j < coeffs; ++j) {
      if (cy >= static_cast<std::size_t>(centroids.height)) break;
      const std::size_t at = (cy * static_cast<std::size_t>(centroids.width) + cxBase + j) * 4;
      rest[j] = glm::vec3(shBook[centroids.rgba[at]], shBook[centroids.rgba[at + 1]],
                          shBook[centroids.rgba[at + 2]]);
    }
  }
}

/// Decodes splats [first, first + n) of `sog` (its textures loaded) into `cloud`.
void decodeRange(const Sog& sog, std::size_t first, std::size_t n, GaussianCloud& cloud) {
  const std::size_t o = first * 4;
  const SogTexels t{
      sog.lo.rgba.data() + o, sog.hi.rgba.data() + o,
      sog.q.rgba.data() + o,  sog.s.rgba.data() + o,
      sog.c0.rgba.data() + o, sog.labels.rgba.empty() ? nullptr : sog.labels.rgba.data() + o};
  decodeSplats(sog, t, n, cloud);
}

/// `bytes` (a .sog bundle, or a meta.json whose textures `sideFiles` reads) loaded.
Sog loadSogBytes(std::string_view bytes, std::string_view name, const SideFileReader& sideFiles) {
  if (detail::ZipArchive::isZip(bytes)) {
    const detail::ZipArchive zip(bytes, name);
    const std::string meta = zip.read("meta.json", kMaxMetaBytes);
    return loadSog(meta, name,
                   [&](const std::string& file) { return zip.read(file, kMaxImageBytes); });
  }
  return loadSog(bytes, name, [&](const std::string& file) {
    std::string data, error;
    if (!sideFiles) fail(name, "cannot read '" + file + "': no side files");
    if (!sideFiles(file, data, error)) fail(name, "cannot read '" + file + "': " + error);
    if (data.size() > kMaxImageBytes) fail(name, "'" + file + "' is larger than 1 GiB");
    return data;
  });
}

/// An SOG scene read a batch at a time: its textures decoded whole (4 bytes a texel, 6 or
/// 7 textures: about 28 bytes a splat, a ninth of the cloud's 244 at SH degree 3), the
/// splats converted a batch at a time.
class SogBatches final : public GaussianBatchReader {
 public:
  explicit SogBatches(Sog sog) : sog_(std::move(sog)) {}
  std::uint64_t size() const override { return sog_.count; }
  int shDegree() const override { return sog_.degree; }
  std::size_t rowBytes() const override { return sog_.labels.rgba.empty() ? 20 : 24; }
  std::size_t read(GaussianCloud& batch, std::size_t max) override {
    const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(max, size() - next_));
    batch = GaussianCloud{};
    detail::allocate(batch, n, sog_.degree);
    decodeRange(sog_, next_, n, batch);
    next_ += n;
    return n;
  }
  void rewind() override { next_ = 0; }

 private:
  Sog sog_;
  std::size_t next_ = 0;
};

/// An SOG meta.json read by columns (GaussianColumnDecoder): each texture a WebP side file
/// decoded a band of rows at a time as it arrives, the SH centroids whole before any splat.
class SogColumns final : public GaussianColumnDecoder {
 public:
  SogColumns(Sog sog, const std::string& name) : sog_(std::move(sog)), name_(name) {
    for (std::size_t k = 0; k < sog_.files.size(); ++k) {
      const std::string& file = sog_.files[k];
      // As the whole reader's side files (session::sideFileUrl) refuse them.
      if (!isFileBesideScene(file))
        fail(name_, "cannot read '" + file + "': " + file + ": not a file beside the scene");
      Column c;
      c.recordBytes = 4;
      c.file = file;
      c.webp = true;
      c.maxTexels = sog_.maxPixels;
      if (k == 5) {  // the centroids
        c.whole = true;
        c.maxTexels = 64 * sog_.coeffs * 1024;
        c.width = static_cast<std::uint32_t>(64 * sog_.coeffs);
      }
      columns_.push_back(std::move(c));
    }
  }
  const std::vector<Column>& columns() const override { return columns_; }
  std::uint64_t size() const override { return sog_.count; }
  int shDegree() const override { return sog_.degree; }
  void decode(const std::vector<const char*>& records, std::uint64_t first, std::size_t n,
              GaussianCloud& batch) const override {
    detail::checkRows(first, n, sog_.count);
    if (records.size() != columns_.size())
      fail(name_, "expected " + std::to_string(columns_.size()) + " columns, got " +
                      std::to_string(records.size()));
    if (sog_.coeffs > 0 && !haveCentroids_) fail(name_, "the SH centroids have not come");
    const auto texel = [&](std::size_t k) {
      return reinterpret_cast<const std::uint8_t*>(records[k]);
    };
    batch = GaussianCloud{};
    detail::allocate(batch, n, sog_.degree);
    decodeSplats(sog_,
                 SogTexels{texel(0), texel(1), texel(2), texel(3), texel(4),
                           sog_.coeffs > 0 ? texel(6) : nullptr},
                 n, batch);
  }
  void takeWhole(std::size_t k, std::string_view texels, int width, int height) override {
    if (k != 5) return;
    sog_.centroids.width = width;
    sog_.centroids.height = height;
    sog_.centroids.rgba.assign(texels.begin(), texels.end());
    haveCentroids_ = true;
  }

 private:
  Sog sog_;
  std::string name_;
  std::vector<Column> columns_;
  bool haveCentroids_ = false;
};

}  // namespace

GaussianColumns openSogColumns(std::string_view head, const std::string& name,
                               std::uint64_t fileBytes) {
  GaussianColumns found;
  if (fileBytes > kMaxColumnsJsonBytes) return found;  // read whole
  if (head.size() < fileBytes) {
    found.needMore = true;
    return found;
  }
  found.decoder = std::make_unique<SogColumns>(
      loadSogMeta(head.substr(0, static_cast<std::size_t>(fileBytes)), name), name);
  return found;
}

GaussianCloud readSogGaussians(std::string_view bytes, std::string_view name,
                               const SideFileReader& sideFiles) {
  const Sog sog = loadSogBytes(bytes, name, sideFiles);
  GaussianCloud cloud;
  detail::allocate(cloud, sog.count, sog.degree);
  decodeRange(sog, 0, sog.count, cloud);
  return cloud;
}

std::unique_ptr<GaussianBatchReader> openSogGaussianBatches(const std::string& path,
                                                            const SideFileReader& sideFiles) {
  std::string bytes;
  {
    const detail::PieceFile file(path);
    if (file.size() > (std::uint64_t{8} << 30)) fail(path, "an SOG scene larger than 8 GiB");
    // A meta.json (no zip) is held to its own limit before it is read.
    if (!detail::ZipArchive::isZip(file.head(4)) && file.size() > kMaxMetaBytes)
      fail(path, "meta.json is larger than 16 MiB");
    bytes.resize(static_cast<std::size_t>(file.size()));
    file.read(0, bytes.data(), bytes.size());
  }
  return std::make_unique<SogBatches>(loadSogBytes(bytes, path, sideFiles));
}

}  // namespace gs::splats
