// X3D volume data nodes as QNV gradient vectors (volume_data.hpp).
#include "volume_data.hpp"

#include "base/fetch.hpp"
#include "base/gzip.hpp"
#include "base/url.hpp"
#include "formats/volume_readers.hpp"
#include "gpu_resources.hpp"
#include "qnv/encoder.hpp"
#include "qnv/error.hpp"
#include "render/splat_source.hpp"
#include "scene/node_access.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <optional>
#include <utility>
#include <vector>

namespace gs::render::detail {

namespace {

/// Voxels an X3D world may give inline or by url (2^27: 512 MiB of floats).
constexpr std::size_t kMaxVolumeDataVoxels = std::size_t{1} << 27;

float volumeLuminance(std::uint32_t r, std::uint32_t g, std::uint32_t b) {
  return 0.299f * static_cast<float>(r) + 0.587f * static_cast<float>(g) +
         0.114f * static_cast<float>(b);
}

/// A PixelTexture3D's image: components, width, height, depth, then the pixels packed as
/// SFImage pixels are (clause 5.3.6).
bool volumeFromPixelTexture3D(const vrml::Node& t, qnv::Volume& out, std::string& problem) {
  static const std::vector<std::int32_t> kNoImage;
  const std::vector<std::int32_t>& image =
      scene::fieldRef<vrml::FieldType::MFInt32>(t, "image", kNoImage);
  if (image.size() < 4) {
    problem = "PixelTexture3D has no image";
    return false;
  }
  const std::int32_t c = image[0];
  if (c < 1 || c > 4 || image[1] < 1 || image[2] < 1 || image[3] < 1) {
    problem = "PixelTexture3D image header " + std::to_string(c) + " " + std::to_string(image[1]) +
              " " + std::to_string(image[2]) + " " + std::to_string(image[3]) +
              " is not components 1..4 and sizes >= 1";
    return false;
  }
  const auto w = static_cast<std::uint64_t>(image[1]), h = static_cast<std::uint64_t>(image[2]),
             d = static_cast<std::uint64_t>(image[3]);
  const std::uint64_t n = w * h * d;
  if (n > kMaxVolumeDataVoxels || image.size() - 4 != n) {
    problem = "PixelTexture3D has " + std::to_string(image.size() - 4) + " pixels, expected " +
              std::to_string(n) + " (at most " + std::to_string(kMaxVolumeDataVoxels) + ")";
    return false;
  }
  out.dims = {static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h),
              static_cast<std::uint32_t>(d)};
  out.samples.resize(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < out.samples.size(); ++i) {
    const auto p = static_cast<std::uint32_t>(image[4 + i]);
    switch (c) {
      case 1:
        out.samples[i] = static_cast<float>(p & 0xFF);
        break;
      case 2:
        out.samples[i] = static_cast<float>((p >> 8) & 0xFF);
        break;
      case 3:
        out.samples[i] = volumeLuminance((p >> 16) & 0xFF, (p >> 8) & 0xFF, p & 0xFF);
        break;
      default:
        out.samples[i] = volumeLuminance((p >> 24) & 0xFF, (p >> 16) & 0xFF, (p >> 8) & 0xFF);
        break;
    }
  }
  return true;
}

/// The samples of a NRRD file: `bytes` of `url`, with its data attached or in `data` (the
/// detached data file's bytes).
qnv::Volume volumeFromNrrd(const formats::NrrdHeader& h, const std::string& bytes,
                           const std::string* detached, const std::string& url) {
  if (h.voxelCount() > kMaxVolumeDataVoxels)
    throw qnv::InputError(url + ": " + std::to_string(h.voxelCount()) +
                          " voxels, more than an X3D volume may have here (" +
                          std::to_string(kMaxVolumeDataVoxels) + ")");
  std::string_view data =
      detached != nullptr ? std::string_view(*detached)
                          : std::string_view(bytes).substr(std::min(h.dataOffset, bytes.size()));
  if (h.encoding != formats::NrrdHeader::Encoding::gzip)
    return formats::decodeNrrdData(h, data, url);
  data = formats::skipNrrdLines(data, h.lineSkip, url);
  const std::size_t skip = h.byteSkip > 0 ? static_cast<std::size_t>(h.byteSkip) : 0;
  try {
    return formats::decodeNrrdData(
        h, base::gunzipIfCompressed(data, h.dataBytes() + skip + (std::size_t{1} << 20)), url);
  } catch (const base::GzipError& e) {
    throw qnv::InputError(url + ": " + e.what());
  }
}

/// The url of a NRRD header's detached data file: beside the header or below it, never
/// an absolute path or one that climbs out ('..'), as session/volume_input.cpp reads them.
std::string detachedDataUrl(const std::string& headerUrl, const std::string& dataFile) {
  if (dataFile.empty() || dataFile.front() == '/' || dataFile.find(':') != std::string::npos)
    throw qnv::InputError(headerUrl + ": data file '" + dataFile +
                          "' is an absolute path; only files beside the header are read");
  for (std::size_t i = 0; i + 1 < dataFile.size(); ++i)
    if (dataFile.compare(i, 2, "..") == 0 && (i == 0 || dataFile[i - 1] == '/'))
      throw qnv::InputError(headerUrl + ": data file '" + dataFile +
                            "' leaves the header's folder ('..')");
  return base::resolveUrl(headerUrl, dataFile);
}

/// An ImageTexture3D: the first url that loads (a NRRD file, its data attached or in a
/// file beside it).
bool volumeFromImageTexture3D(const vrml::Node& t, const std::string& baseUrl,
                              base::Fetcher* fetcher, qnv::Volume& out, bool& pending,
                              std::string& problem) {
  std::string failures;
  for (const std::string& reference : scene::mfString(t, "url")) {
    if (reference.empty()) continue;
    const std::string url = base::resolveUrl(baseUrl, reference);
    base::Fetcher& f = base::fetcherOr(fetcher);
    const base::Fetched got = f.fetch(url, baseUrl, base::FetchMode::background);
    if (got.pending()) {
      pending = true;
      return false;
    }
    std::string error = got.error;
    if (got.ready()) {
      try {
        const formats::NrrdHeader h = formats::parseNrrdHeader(got.bytes, url);
        if (h.dataFile.empty()) {
          out = volumeFromNrrd(h, got.bytes, nullptr, url);
          return true;
        }
        const std::string dataUrl = detachedDataUrl(url, h.dataFile);
        const base::Fetched data = f.fetch(dataUrl, url, base::FetchMode::background);
        if (data.pending()) {
          pending = true;
          return false;
        }
        if (!data.ready()) throw qnv::InputError(data.error);
        out = volumeFromNrrd(h, got.bytes, &data.bytes, dataUrl);
        return true;
      } catch (const std::exception& e) {
        error = e.what();
      }
    }
    failures += (failures.empty() ? "" : "; ") + error;
  }
  problem = "ImageTexture3D: " + (failures.empty() ? std::string("no url") : failures);
  return false;
}

/// A ComposedTexture3D: one grey slice per 2D texture, all of the first one's size.
bool volumeFromComposedTexture3D(const vrml::Node& t, const std::string& baseUrl,
                                 base::Fetcher* fetcher, qnv::Volume& out, bool& pending,
                                 std::string& problem) {
  std::vector<std::vector<float>> slices;
  int width = 0, height = 0;
  for (const vrml::NodePtr& slice : t.mfnode("texture")) {
    if (!slice || slice->unresolved) continue;
    std::vector<float> grey;
    int w = 0, h = 0;
    if (slice->typeId() == vrml::NodeTypeId::PixelTexture) {
      static const vrml::SFImage kNone;
      const vrml::SFImage& image =
          scene::fieldRef<vrml::FieldType::SFImage>(*slice, "image", kNone);
      std::vector<std::uint8_t> rgba;
      bool alpha = false;
      if (!decodeSFImage(image, rgba, alpha) || image.width == 0 || image.height == 0) continue;
      w = image.width;
      h = image.height;
      for (std::size_t i = 0; i + 3 < rgba.size(); i += 4)
        grey.push_back(volumeLuminance(rgba[i], rgba[i + 1], rgba[i + 2]));
    } else if (slice->typeId() == vrml::NodeTypeId::ImageTexture) {
      LoadedImage loaded = loadFirstImage(scene::mfString(*slice, "url"), baseUrl, fetcher);
      if (loaded.pending) {
        pending = true;
        return false;
      }
      if (loaded.components == 0) {
        problem = "ComposedTexture3D slice: " + loaded.failures;
        return false;
      }
      w = loaded.image.width;
      h = loaded.image.height;
      for (int y = h - 1; y >= 0; --y)  // rows bottom to top, as texture t grows
        for (int x = 0; x < w; ++x) {
          const std::uint8_t* p = loaded.image.pixel(x, y);
          grey.push_back(volumeLuminance(p[0], p[1], p[2]));
        }
    } else {
      problem = "ComposedTexture3D: a " + slice->typeName() + " slice is not read";
      return false;
    }
    if (slices.empty()) {
      width = w;
      height = h;
    } else if (w != width || h != height) {
      problem = "ComposedTexture3D: slices of " + std::to_string(width) + "x" +
                std::to_string(height) + " and " + std::to_string(w) + "x" + std::to_string(h);
      return false;
    }
    slices.push_back(std::move(grey));
  }
  if (slices.empty()) {
    problem = "ComposedTexture3D has no slices";
    return false;
  }
  out.dims = {static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height),
              static_cast<std::uint32_t>(slices.size())};
  if (out.voxelCount() > kMaxVolumeDataVoxels) {
    problem = "ComposedTexture3D: too many voxels";
    return false;
  }
  for (const std::vector<float>& s : slices)
    out.samples.insert(out.samples.end(), s.begin(), s.end());
  return true;
}

/// An OpacityMapVolumeStyle's PixelTexture transfer function as the 256-entry palette.
std::optional<std::array<qnv::Rgba8, qnv::kPaletteSize>> transferPalette(const vrml::Node* style) {
  if (style == nullptr || style->typeId() != vrml::NodeTypeId::OpacityMapVolumeStyle)
    return std::nullopt;
  const vrml::NodePtr& tf = style->sfnode("transferFunction");
  if (!tf || tf->unresolved || tf->typeId() != vrml::NodeTypeId::PixelTexture) return std::nullopt;
  static const vrml::SFImage kNone;
  const vrml::SFImage& image = scene::fieldRef<vrml::FieldType::SFImage>(*tf, "image", kNone);
  std::vector<std::uint8_t> rgba;
  bool alpha = false;
  if (!decodeSFImage(image, rgba, alpha) || image.width == 0) return std::nullopt;
  std::array<qnv::Rgba8, qnv::kPaletteSize> palette{};
  const auto w = static_cast<std::size_t>(image.width);  // the first row
  for (std::size_t c = 0; c < palette.size(); ++c) {
    const std::size_t x = std::min(w - 1, c * w / palette.size());
    palette[c] = {rgba[4 * x], rgba[4 * x + 1], rgba[4 * x + 2], rgba[4 * x + 3]};
  }
  return palette;
}

}  // namespace

bool isVolumeDataNode(const vrml::Node& node) {
  const vrml::NodeTypeId id = node.typeId();
  return id == vrml::NodeTypeId::VolumeData || id == vrml::NodeTypeId::IsoSurfaceVolumeData ||
         id == vrml::NodeTypeId::SegmentedVolumeData;
}

VolumeDataSet volumeDataSet(const vrml::Node& node, const std::string& baseUrl,
                            base::Fetcher* fetcher) {
  VolumeDataSet out;
  const vrml::NodePtr& voxels = node.sfnode("voxels");
  if (!voxels || voxels->unresolved) {
    out.problem = node.typeName() + " has no voxels";
    return out;
  }
  qnv::Volume volume;
  bool ok = false;
  switch (voxels->typeId()) {
    case vrml::NodeTypeId::PixelTexture3D:
      ok = volumeFromPixelTexture3D(*voxels, volume, out.problem);
      break;
    case vrml::NodeTypeId::ImageTexture3D:
      ok = volumeFromImageTexture3D(*voxels, voxels->urlBaseOr(baseUrl), fetcher, volume,
                                    out.pending, out.problem);
      break;
    case vrml::NodeTypeId::ComposedTexture3D:
      ok = volumeFromComposedTexture3D(*voxels, voxels->urlBaseOr(baseUrl), fetcher, volume,
                                       out.pending, out.problem);
      break;
    default:
      out.problem = voxels->typeName() +
                    " is not read as voxels (PixelTexture3D, "
                    "ImageTexture3D of a NRRD file, ComposedTexture3D are)";
      break;
  }
  if (!ok) return out;
  const glm::vec3 size = glm::max(scene::sfVec3(node, "dimensions", glm::vec3(1.0f)), 1e-6f);
  volume.spacing = size / glm::vec3(volume.dims);
  volume.origin = -0.5f * size + 0.5f * volume.spacing;

  qnv::VolumeEncodeOptions options;
  if (node.typeId() == vrml::NodeTypeId::IsoSurfaceVolumeData) {
    const std::vector<float>& values = scene::mfFloat(node, "surfaceValues");
    if (!values.empty()) {
      const auto [lo, hi] = std::minmax_element(volume.samples.begin(), volume.samples.end());
      float tolerance = scene::sfFloat(node, "surfaceTolerance", 0.0f);
      if (!(tolerance > 0.0f)) tolerance = 0.05f * (*hi - *lo);
      const auto [vlo, vhi] = std::minmax_element(values.begin(), values.end());
      options.valueWindow = std::pair(*vlo - tolerance, *vhi + tolerance);
    }
  } else {
    const vrml::NodePtr& style = node.sfnode("renderStyle");
    options.palette = transferPalette(style && !style->unresolved ? style.get() : nullptr);
  }
  try {
    out.set = splatSetFromEncoded(qnv::encodeVolume(volume, options));
  } catch (const std::exception& e) {
    out.problem = e.what();
  }
  if (out.set && out.set->vectors.empty()) {
    out.set.reset();
    out.problem = node.typeName() + ": no voxel has a gradient" +
                  (options.valueWindow ? " within surfaceTolerance of surfaceValues"
                                       : " (a constant volume)");
  }
  return out;
}

}  // namespace gs::render::detail
