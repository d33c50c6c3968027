// X3D Texturing3D textures decoded to RGBA texels (gpu_resources.hpp, decodeTexture3D).
#include "base/fetch.hpp"
#include "base/url.hpp"
#include "dds_images.hpp"
#include "formats/volume_readers.hpp"
#include "gpu_resources.hpp"
#include "scene/node_access.hpp"

#include <algorithm>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string_view>

namespace gs::render::detail {

namespace {

/// Texels a 3D texture may have (2^24: 64 MiB of RGBA).
constexpr std::size_t kMaxTexels3D = std::size_t{1} << 24;

/// A DirectDraw Surface volume (or 2D image) as a 3D texture (dds_images.hpp).
Texels3D decodeDds(std::string_view b, const std::string& url) {
  const DdsImages dds = decodeDdsImages(b, url);
  if (dds.cube()) throw std::runtime_error(url + ": a DDS cube map is no 3D texture");
  Texels3D t;
  t.width = dds.width;
  t.height = dds.height;
  t.depth = dds.depth;
  t.components = dds.components;
  if (static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height) *
          static_cast<std::size_t>(t.depth) >
      kMaxTexels3D)
    throw std::runtime_error(url + ": DDS size out of range");
  // DDS rows run top to bottom; texture t grows upwards.
  const std::size_t row = static_cast<std::size_t>(t.width) * 4;
  t.rgba.resize(dds.rgba.size());
  for (int z = 0; z < t.depth; ++z)
    for (int y = 0; y < t.height; ++y)
      std::memcpy(
          t.rgba.data() + (static_cast<std::size_t>(z) * t.height + (t.height - 1 - y)) * row,
          dds.rgba.data() + (static_cast<std::size_t>(z) * t.height + y) * row, row);
  return t;
}

/// A NRRD volume with attached data, its values stretched over 0..255: grey, or with a
/// first axis of 2..4 components grey-alpha, RGB or RGBA (as X_ITE reads NRRD textures).
Texels3D decodeNrrdTexture(std::string_view b, const std::string& url) {
  formats::NrrdParseOptions options;
  options.componentAxis = true;
  const formats::NrrdHeader h = formats::parseNrrdHeader(b, url, options);
  if (!h.dataFile.empty() || h.encoding == formats::NrrdHeader::Encoding::gzip)
    throw std::runtime_error(url + ": only raw or ascii NRRD with attached data is a 3D texture");
  if (h.voxelCount() > kMaxTexels3D) throw std::runtime_error(url + ": NRRD too large");
  const qnv::Volume v = formats::decodeNrrdData(h, b.substr(std::min(h.dataOffset, b.size())), url);
  const std::size_t components = h.components;
  Texels3D t;
  t.width = static_cast<int>(v.dims.x / components);
  t.height = static_cast<int>(v.dims.y);
  t.depth = static_cast<int>(v.dims.z);
  t.components = static_cast<int>(components);
  const auto [lowest, highest] = std::minmax_element(v.samples.begin(), v.samples.end());
  // (A plain copy: clang 14 cannot capture a structured binding in a lambda.)
  const float lo = *lowest;
  const float range = *highest > lo ? *highest - lo : 1.0f;
  const auto level = [&](std::size_t i) {
    return static_cast<std::uint8_t>(std::clamp((v.samples[i] - lo) / range, 0.0f, 1.0f) * 255.0f +
                                     0.5f);
  };
  const std::size_t texels = v.samples.size() / components;
  t.rgba.resize(texels * 4);
  for (std::size_t i = 0; i < texels; ++i) {
    std::uint8_t* p = &t.rgba[4 * i];
    const std::size_t s = i * components;
    if (components <= 2) {
      p[0] = p[1] = p[2] = level(s);
      p[3] = components == 2 ? level(s + 1) : 255;
    } else {
      p[0] = level(s);
      p[1] = level(s + 1);
      p[2] = level(s + 2);
      p[3] = components == 4 ? level(s + 3) : 255;
    }
  }
  return t;
}

Texels3D decodePixelTexture3D(const vrml::Node& node) {
  Texels3D t;
  static const std::vector<std::int32_t> kNone;
  const std::vector<std::int32_t>& image =
      scene::fieldRef<vrml::FieldType::MFInt32>(node, "image", kNone);
  if (image.size() < 4) return t;  // an empty image: no texture
  vrml::SFImage slice;
  slice.components = image[0];
  if (slice.components < 1 || slice.components > 4 || image[1] < 1 || image[2] < 1 || image[3] < 1)
    throw std::runtime_error("PixelTexture3D image header is not components 1..4 and sizes >= 1");
  const auto n = static_cast<std::uint64_t>(image[1]) * static_cast<std::uint64_t>(image[2]) *
                 static_cast<std::uint64_t>(image[3]);
  if (n > kMaxTexels3D || image.size() - 4 != n)
    throw std::runtime_error("PixelTexture3D has " + std::to_string(image.size() - 4) +
                             " pixels, expected " + std::to_string(n));
  // Pixels run s fastest, then t, then r (clause 33.4.4): GL's order. Decoded as one tall
  // SFImage (clause 5.3.6).
  slice.width = image[1];
  slice.height = image[2] * image[3];
  slice.pixels.reserve(static_cast<std::size_t>(n));
  for (std::size_t i = 4; i < image.size(); ++i)
    slice.pixels.push_back(static_cast<std::uint32_t>(image[i]));
  bool alpha = false;
  if (!decodeSFImage(slice, t.rgba, alpha))
    throw std::runtime_error("PixelTexture3D is inconsistent");
  t.width = image[1];
  t.height = image[2];
  t.depth = image[3];
  t.components = slice.components;
  return t;
}

Texels3D decodeComposedTexture3D(const vrml::Node& node, const std::string& baseUrl,
                                 base::Fetcher* fetcher) {
  Texels3D t;
  for (const vrml::NodePtr& slice : node.mfnode("texture")) {
    if (!slice || slice->unresolved) continue;
    std::vector<std::uint8_t> rgba;  // rows bottom to top
    int w = 0, h = 0, components = 0;
    if (slice->typeId() == vrml::NodeTypeId::PixelTexture) {
      static const vrml::SFImage kEmpty;
      const vrml::SFImage& image =
          scene::fieldRef<vrml::FieldType::SFImage>(*slice, "image", kEmpty);
      bool alpha = false;
      if (image.width == 0 || image.height == 0 || !decodeSFImage(image, rgba, alpha)) continue;
      w = image.width;
      h = image.height;
      components = image.components;
    } else if (slice->typeId() == vrml::NodeTypeId::ImageTexture) {
      LoadedImage loaded = loadFirstImage(scene::mfString(*slice, "url"), baseUrl, fetcher);
      if (loaded.pending) {
        t.pending = true;
        return t;
      }
      if (loaded.components == 0)
        throw std::runtime_error("ComposedTexture3D slice: " + loaded.failures);
      w = loaded.image.width;
      h = loaded.image.height;
      components = loaded.components;
      const std::size_t row = static_cast<std::size_t>(w) * 4;
      rgba.resize(row * static_cast<std::size_t>(h));
      for (int y = 0; y < h; ++y)
        std::memcpy(rgba.data() + static_cast<std::size_t>(h - 1 - y) * row,
                    loaded.image.rgba.data() + static_cast<std::size_t>(y) * row, row);
    } else {
      throw std::runtime_error("ComposedTexture3D: a " + slice->typeName() + " slice is not read");
    }
    if (t.depth == 0) {
      t.width = w;
      t.height = h;
    } else if (w != t.width || h != t.height) {
      throw std::runtime_error("ComposedTexture3D: slices of different sizes");
    }
    t.components = std::max(t.components, components);
    t.rgba.insert(t.rgba.end(), rgba.begin(), rgba.end());
    ++t.depth;
    if (t.rgba.size() > 4 * kMaxTexels3D)
      throw std::runtime_error("ComposedTexture3D: too many texels");
  }
  return t;
}

Texels3D decodeImageTexture3D(const vrml::Node& node, const std::string& baseUrl,
                              base::Fetcher* fetcher) {
  std::string failures;
  for (const std::string& reference : scene::mfString(node, "url")) {
    if (reference.empty()) continue;
    const std::string url = base::resolveUrl(baseUrl, reference);
    const base::Fetched got =
        base::fetcherOr(fetcher).fetch(url, baseUrl, base::FetchMode::background);
    if (got.pending()) {
      Texels3D t;
      t.pending = true;
      return t;
    }
    std::string error = got.error;
    if (got.ready()) {
      try {
        if (got.bytes.starts_with("DDS ")) return decodeDds(got.bytes, url);
        if (got.bytes.starts_with("NRRD")) return decodeNrrdTexture(got.bytes, url);
        error = url + ": neither a DDS nor a NRRD file";
      } catch (const std::exception& e) {
        error = e.what();
      }
    }
    failures += (failures.empty() ? "" : "; ") + error;
  }
  throw std::runtime_error(failures.empty() ? std::string("no url") : failures);
}

}  // namespace

Texels3D decodeTexture3D(const vrml::Node& node, const std::string& baseUrl,
                         base::Fetcher* fetcher) {
  try {
    switch (node.typeId()) {
      case vrml::NodeTypeId::PixelTexture3D:
        return decodePixelTexture3D(node);
      case vrml::NodeTypeId::ComposedTexture3D:
        return decodeComposedTexture3D(node, baseUrl, fetcher);
      case vrml::NodeTypeId::ImageTexture3D:
        return decodeImageTexture3D(node, baseUrl, fetcher);
      default:
        break;
    }
  } catch (const std::exception& e) {
    Texels3D t;
    t.problem = e.what();
    return t;
  }
  return {};
}

}  // namespace gs::render::detail
