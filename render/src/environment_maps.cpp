// EnvironmentLight's image-based light (environment_maps.hpp): cube faces resampled on the
// CPU, their irradiance as spherical harmonics, the specular cube map mipmapped by GL.
#include "environment_maps.hpp"

#include "base/fetch.hpp"
#include "base/url.hpp"
#include "dds_images.hpp"

#include "gpu_resources.hpp"
#include "scene/node_access.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace gs::render::detail {
namespace {

constexpr float kPi = 3.14159265358979f;

/// An X3D cube face as a viewer inside the cube sees it (Background's convention, clause
/// 6.5; background.cpp): the face's centre and the directions of the image's right and up.
struct X3dFace {
  glm::vec3 center, right, up;
};
// back, bottom, front, left, right, top (the order of resampleCubeFaces' argument).
constexpr std::array<X3dFace, 6> kX3dFaces = {{
    {{0, 0, 1}, {-1, 0, 0}, {0, 1, 0}},
    {{0, -1, 0}, {1, 0, 0}, {0, 0, -1}},
    {{0, 0, -1}, {1, 0, 0}, {0, 1, 0}},
    {{-1, 0, 0}, {0, 0, -1}, {0, 1, 0}},
    {{1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
    {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}},
}};

/// The direction through GL face `face`'s point (sc, tc), each in [-1, 1] (OpenGL 4.5 core
/// table 8.19, inverted).
glm::vec3 glFaceDirection(int face, float sc, float tc) {
  switch (face) {
    case 0:
      return {1.0f, -tc, -sc};
    case 1:
      return {-1.0f, -tc, sc};
    case 2:
      return {sc, 1.0f, tc};
    case 3:
      return {sc, -1.0f, -tc};
    case 4:
      return {sc, -tc, 1.0f};
    default:
      return {-sc, -tc, -1.0f};
  }
}

/// The X3D face a direction meets (the index into kX3dFaces).
int x3dFaceOf(const glm::vec3& d) {
  const glm::vec3 a = glm::abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x > 0 ? 4 : 3;
  if (a.y >= a.z) return d.y > 0 ? 5 : 1;
  return d.z > 0 ? 0 : 2;
}

float srgbToLinear(std::uint8_t v) {
  const float c = static_cast<float>(v) / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

/// `image` averaged down (or repeated up) to size x size linear texels, rows top to bottom.
std::vector<glm::vec3> resizeLinear(const Image& image, int size) {
  std::vector<glm::vec3> out(static_cast<std::size_t>(size) * static_cast<std::size_t>(size));
  if (image.width <= 0 || image.height <= 0) return out;
  std::array<float, 256> lut{};
  for (int i = 0; i < 256; ++i)
    lut[static_cast<std::size_t>(i)] = srgbToLinear(static_cast<std::uint8_t>(i));
  for (int y = 0; y < size; ++y) {
    const int y0 = y * image.height / size;
    const int y1 = std::max(y0 + 1, (y + 1) * image.height / size);
    for (int x = 0; x < size; ++x) {
      const int x0 = x * image.width / size;
      const int x1 = std::max(x0 + 1, (x + 1) * image.width / size);
      glm::vec3 sum(0.0f);
      for (int sy = y0; sy < y1; ++sy)
        for (int sx = x0; sx < x1; ++sx) {
          const std::uint8_t* p = image.pixel(sx, sy);
          sum += glm::vec3(lut[p[0]], lut[p[1]], lut[p[2]]);
        }
      out[static_cast<std::size_t>(y) * static_cast<std::size_t>(size) +
          static_cast<std::size_t>(x)] = sum / static_cast<float>((y1 - y0) * (x1 - x0));
    }
  }
  return out;
}

/// The real SH basis at unit direction d (bands 0..2).
std::array<float, 9> shBasis(const glm::vec3& d) {
  return {0.282095f,
          0.488603f * d.y,
          0.488603f * d.z,
          0.488603f * d.x,
          1.092548f * d.x * d.y,
          1.092548f * d.y * d.z,
          0.315392f * (3.0f * d.z * d.z - 1.0f),
          1.092548f * d.x * d.z,
          0.546274f * (d.x * d.x - d.y * d.y)};
}

/// The solid angle of the part [x0, x1] x [y0, y1] of a cube face at distance 1 (the
/// integral of (1 + x^2 + y^2)^(-3/2)).
float faceSolidAngle(float x0, float y0, float x1, float y1) {
  const auto a = [](float x, float y) {
    return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0f));
  };
  return a(x0, y0) - a(x0, y1) - a(x1, y0) + a(x1, y1);
}

/// Radiance coefficients to E / pi (the clamped-cosine convolution per band, over pi).
IrradianceSh convolve(const std::array<glm::vec3, 9>& radiance) {
  IrradianceSh out{};
  constexpr std::array<float, 9> kBand = {1.0f,  2.0f / 3.0f, 2.0f / 3.0f, 2.0f / 3.0f, 0.25f,
                                          0.25f, 0.25f,       0.25f,       0.25f};
  for (std::size_t i = 0; i < 9; ++i) out[i] = radiance[i] * kBand[i];
  return out;
}

}  // namespace

CubeFaces resampleCubeFaces(const std::array<const Image*, 6>& x3dFaces, int size) {
  CubeFaces out;
  out.size = std::max(size, 1);
  std::array<std::vector<glm::vec3>, 6> resized;
  static const Image kEmpty;
  for (std::size_t f = 0; f < 6; ++f)
    resized[f] = resizeLinear(x3dFaces[f] != nullptr ? *x3dFaces[f] : kEmpty, out.size);
  const auto n = static_cast<std::size_t>(out.size);
  for (int face = 0; face < 6; ++face) {
    std::vector<glm::vec3>& texels = out.texels[static_cast<std::size_t>(face)];
    texels.resize(n * n);
    for (std::size_t t = 0; t < n; ++t)
      for (std::size_t s = 0; s < n; ++s) {
        const float sc = (2.0f * (static_cast<float>(s) + 0.5f)) / static_cast<float>(n) - 1.0f;
        const float tc = (2.0f * (static_cast<float>(t) + 0.5f)) / static_cast<float>(n) - 1.0f;
        const glm::vec3 d = glFaceDirection(face, sc, tc);
        const int x3d = x3dFaceOf(d);
        const X3dFace& xf = kX3dFaces[static_cast<std::size_t>(x3d)];
        const float major = std::abs(glm::dot(d, xf.center));
        const float u = glm::dot(d, xf.right) / major * 0.5f + 0.5f;  // image right
        const float v = glm::dot(d, xf.up) / major * 0.5f + 0.5f;     // image up
        const auto px = std::min(static_cast<std::size_t>(u * static_cast<float>(n)), n - 1);
        const auto py =
            std::min(static_cast<std::size_t>((1.0f - v) * static_cast<float>(n)), n - 1);
        texels[t * n + s] = resized[static_cast<std::size_t>(x3d)][py * n + px];
      }
  }
  return out;
}

std::vector<Image> cubeFacesOfImage(const Image& image) {
  if (image.empty()) return {};
  const double aspect = static_cast<double>(image.width) / image.height;
  std::vector<Image> faces;
  if (std::abs(aspect - 4.0 / 3.0) < 0.01 * 4.0 / 3.0) {
    // The cross: (column, row) of back, bottom, front, left, right, top.
    static constexpr std::array<std::array<int, 2>, 6> kCell = {
        {{3, 1}, {1, 2}, {1, 1}, {0, 1}, {2, 1}, {1, 0}}};
    const int side = std::min(image.width / 4, image.height / 3);
    if (side < 1) return {};
    for (const auto& [column, row] : kCell) {
      Image& face = faces.emplace_back(side, side);
      for (int y = 0; y < side; ++y)
        std::copy_n(image.pixel(column * side, row * side + y), 4 * side, face.pixel(0, y));
    }
    return faces;
  }
  if (std::abs(aspect - 2.0) >= 0.02) return {};
  // The panorama: direction d is at column (1/2 + atan2(d.x, d.z) / 2 pi) x width and row
  // acos(d.y) / pi x height, as X_ITE's Panorama2.fs and cube map lookups place it (its
  // centre where a TextureCoordinate3D of +Z samples the map, measured).
  const int side = std::clamp(image.height / 2, 1, 2048);
  // Bilinear, wrapping around horizontally, into `out` (RGBA).
  const auto sample = [&](float u, float v, std::uint8_t* out) {
    const float x = u * static_cast<float>(image.width) - 0.5f;
    const float y = std::clamp(v * static_cast<float>(image.height) - 0.5f, 0.0f,
                               static_cast<float>(image.height - 1));
    const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(y);
    const int y1 = std::min(y0 + 1, image.height - 1);
    const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
    const auto wrap = [&](int i) { return ((i % image.width) + image.width) % image.width; };
    const std::uint8_t *a = image.pixel(wrap(x0), y0), *b = image.pixel(wrap(x0 + 1), y0),
                       *c = image.pixel(wrap(x0), y1), *d = image.pixel(wrap(x0 + 1), y1);
    for (int k = 0; k < 4; ++k) {
      const float top = static_cast<float>(a[k]) * (1.0f - fx) + static_cast<float>(b[k]) * fx;
      const float bottom = static_cast<float>(c[k]) * (1.0f - fx) + static_cast<float>(d[k]) * fx;
      out[k] = static_cast<std::uint8_t>(
          std::clamp(std::lround(top * (1.0f - fy) + bottom * fy), 0L, 255L));
    }
  };
  for (const X3dFace& xf : kX3dFaces) {
    Image& face = faces.emplace_back(side, side);
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        const float a = 2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(side) - 1.0f;
        const float b = 1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(side);
        const glm::vec3 d = glm::normalize(xf.center + a * xf.right + b * xf.up);
        sample(0.5f + std::atan2(d.x, d.z) / (2.0f * kPi),
               std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi, face.pixel(x, y));
      }
  }
  return faces;
}

IrradianceSh irradianceOf(const CubeFaces& faces) {
  std::array<glm::vec3, 9> radiance{};
  const auto n = static_cast<std::size_t>(faces.size);
  if (n == 0) return {};
  const float texel = 2.0f / static_cast<float>(n);
  for (int face = 0; face < 6; ++face) {
    const std::vector<glm::vec3>& texels = faces.texels[static_cast<std::size_t>(face)];
    if (texels.size() != n * n) continue;
    for (std::size_t t = 0; t < n; ++t)
      for (std::size_t s = 0; s < n; ++s) {
        const float s0 = static_cast<float>(s) * texel - 1.0f;
        const float t0 = static_cast<float>(t) * texel - 1.0f;
        const float sc = s0 + 0.5f * texel, tc = t0 + 0.5f * texel;
        const float solidAngle = faceSolidAngle(s0, t0, s0 + texel, t0 + texel);
        const glm::vec3 d = glm::normalize(glFaceDirection(face, sc, tc));
        const std::array<float, 9> y = shBasis(d);
        const glm::vec3 l = texels[t * n + s] * solidAngle;
        for (std::size_t i = 0; i < 9; ++i) radiance[i] += l * y[i];
      }
  }
  return convolve(radiance);
}

bool irradianceFromCoefficients(const std::vector<float>& coefficients, IrradianceSh& out) {
  if (coefficients.size() < 27) return false;
  std::array<glm::vec3, 9> radiance{};
  for (std::size_t i = 0; i < 9; ++i) {
    radiance[i] = {coefficients[3 * i], coefficients[3 * i + 1], coefficients[3 * i + 2]};
    if (!std::isfinite(radiance[i].x) || !std::isfinite(radiance[i].y) ||
        !std::isfinite(radiance[i].z))
      return false;
  }
  out = convolve(radiance);
  return true;
}

namespace {

/// The six face images of an X3D cube map texture node, or why not.
struct FaceImages {
  std::array<Image, 6> images;
  int size = 0;          // the largest face side
  bool pending = false;  // a face is still on its way
  std::string problem;   // why the node gives no cube map
};

/// Where each X3D face of an ImageCubeMapTexture (the order of kX3dFaces: back, bottom,
/// front, left, right, top) is in a DDS cube map (faces +X, -X, +Y, -Y, +Z, -Z), and
/// whether its image is mirrored left to right or top to bottom: as castle-model-viewer
/// reads DDS cube maps (measured with a file whose faces have distinct colours and
/// corner marks).
struct DdsFace {
  int face;
  bool mirrorX, mirrorY;
};
constexpr std::array<DdsFace, 6> kFromDds = {{{4, true, true},      // back: +Z, turned half round
                                              {2, false, false},    // bottom: +Y
                                              {5, true, true},      // front: -Z
                                              {1, true, true},      // left: -X
                                              {0, true, true},      // right: +X
                                              {3, false, false}}};  // top: -Y

/// An ImageCubeMapTexture (X3D 4.0 clause 34.4.2): its first url that gives a DDS cube
/// map, or an image that cubeFacesOfImage reads as one (a panorama or a cross), as six X3D
/// faces.
FaceImages loadImageCube(const vrml::Node& texture, const std::string& baseUrl,
                         base::Fetcher* fetcher) {
  FaceImages out;
  std::string failures;
  for (const std::string& reference : scene::mfString(texture, "url")) {
    if (reference.empty()) continue;
    const std::string url = base::resolveUrl(baseUrl, reference);
    const base::Fetched got =
        base::fetcherOr(fetcher).fetch(url, baseUrl, base::FetchMode::background);
    if (got.pending()) {
      out.pending = true;
      return out;
    }
    std::string error = got.error;
    if (got.ready()) {
      try {
        if (!got.bytes.starts_with("DDS ")) {
          const Image image = decodeImage(got.bytes, url);
          std::vector<Image> faces = cubeFacesOfImage(image);
          if (faces.size() != 6)
            throw std::runtime_error(
                url + ": a " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                " image is no cube map (ImageCubeMapTexture reads DDS cube maps, 2:1 "
                "panoramas and 4:3 crosses)");
          for (std::size_t f = 0; f < 6; ++f) out.images[f] = std::move(faces[f]);
          out.size = out.images[0].width;
          return out;
        }
        const DdsImages dds = decodeDdsImages(got.bytes, url);
        if (!dds.cube()) throw std::runtime_error(url + ": a DDS file but no cube map");
        const auto w = static_cast<std::size_t>(dds.width),
                   h = static_cast<std::size_t>(dds.height);
        for (std::size_t f = 0; f < 6; ++f) {
          const DdsFace from = kFromDds[f];
          Image& dst = out.images[f];
          dst = Image(dds.width, dds.height);
          const std::uint8_t* src =
              dds.rgba.data() + static_cast<std::size_t>(from.face) * w * h * 4;
          for (std::size_t y = 0; y < h; ++y)
            for (std::size_t x = 0; x < w; ++x) {
              const std::size_t sx = from.mirrorX ? w - 1 - x : x;
              const std::size_t sy = from.mirrorY ? h - 1 - y : y;
              std::copy_n(src + 4 * (sy * w + sx), 4, dst.rgba.data() + 4 * (y * w + x));
            }
        }
        out.size = std::max(dds.width, dds.height);
        return out;
      } catch (const std::exception& e) {
        error = e.what();
      }
    }
    failures += (failures.empty() ? "" : "; ") + error;
  }
  out.problem = failures.empty() ? std::string("no url") : failures;
  return out;
}

FaceImages loadFaces(const vrml::Node& texture, const std::string& baseUrl,
                     base::Fetcher* fetcher) {
  if (texture.typeId() == vrml::NodeTypeId::ImageCubeMapTexture)
    return loadImageCube(texture, baseUrl, fetcher);
  FaceImages out;
  if (texture.typeId() != vrml::NodeTypeId::ComposedCubeMapTexture) {
    out.problem = texture.typeName() +
                  " is not supported as an EnvironmentLight texture "
                  "(ComposedCubeMapTexture and ImageCubeMapTexture are)";
    return out;
  }
  // X3D 4.0 clause 34.4.1; the order of kX3dFaces.
  static constexpr std::array<const char*, 6> kFields = {
      "backTexture", "bottomTexture", "frontTexture", "leftTexture", "rightTexture", "topTexture"};
  for (std::size_t f = 0; f < 6; ++f) {
    const vrml::NodePtr face = texture.sfnode(std::string_view(kFields[f]));
    if (!face || face->unresolved) continue;  // a missing face is black
    if (face->typeId() == vrml::NodeTypeId::ImageTexture) {
      LoadedImage loaded = loadFirstImage(scene::mfString(*face, "url"), baseUrl, fetcher);
      if (loaded.pending) {
        out.pending = true;
        continue;
      }
      if (loaded.components == 0) {
        out.problem += (out.problem.empty() ? "" : "; ") + std::string(kFields[f]) + ": " +
                       (loaded.failures.empty() ? "no url" : loaded.failures);
        continue;
      }
      out.images[f] = std::move(loaded.image);
    } else if (face->typeId() == vrml::NodeTypeId::PixelTexture) {
      static const vrml::SFImage kNone;
      const vrml::SFImage& image = scene::fieldRef<vrml::FieldType::SFImage>(*face, "image", kNone);
      std::vector<std::uint8_t> rgba;
      bool alpha = false;
      if (!decodeSFImage(image, rgba, alpha)) continue;  // empty: black
      Image& dst = out.images[f];
      dst = Image(image.width, image.height);
      const std::size_t row = static_cast<std::size_t>(image.width) * 4;
      for (int y = 0; y < image.height; ++y)  // SFImage rows are bottom to top
        std::copy_n(rgba.data() + static_cast<std::size_t>(image.height - 1 - y) * row, row,
                    dst.rgba.data() + static_cast<std::size_t>(y) * row);
    } else {
      out.problem += (out.problem.empty() ? "" : "; ") + std::string(kFields[f]) + ": " +
                     face->typeName() + " is not supported as a cube face";
      continue;
    }
    out.size = std::max({out.size, out.images[f].width, out.images[f].height});
  }
  return out;
}

float linearToSrgb(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

/// Uploads `faces` as a mipmapped cube map of half floats.
GLuint uploadCubeMap(const CubeFaces& faces) {
  GLuint id = 0;
  glGenTextures(1, &id);
  glBindTexture(GL_TEXTURE_CUBE_MAP, id);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  for (int f = 0; f < 6; ++f)
    glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + static_cast<GLenum>(f), 0, GL_RGB16F, faces.size,
                 faces.size, 0, GL_RGB, GL_FLOAT, faces.texels[static_cast<std::size_t>(f)].data());
  glGenerateMipmap(GL_TEXTURE_CUBE_MAP);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTexParameteri(GL_TEXTURE_CUBE_MAP, wrap, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
  return id;
}

/// Side of the specular cube map: the largest face's side, at most 256 texels, at least 16
/// (smaller faces are repeated up, so that the SH projection samples every band well).
constexpr int kMaxCubeSize = 256;
constexpr int kMinCubeSize = 16;

}  // namespace

CubeTexture loadCubeTexture(const vrml::Node& composed, const std::string& baseUrl,
                            base::Fetcher* fetcher) {
  CubeTexture out;
  FaceImages faces = loadFaces(composed, baseUrl, fetcher);
  out.pending = faces.pending;
  out.problem = std::move(faces.problem);
  if (faces.pending || faces.size == 0) return out;
  std::array<const Image*, 6> images{};
  for (std::size_t i = 0; i < 6; ++i) images[i] = &faces.images[i];
  CubeFaces cube = resampleCubeFaces(images, std::min(faces.size, 512));
  for (std::vector<glm::vec3>& texels : cube.texels)
    for (glm::vec3& t : texels) t = {linearToSrgb(t.x), linearToSrgb(t.y), linearToSrgb(t.z)};
  out.id = uploadCubeMap(cube);
  return out;
}

const GpuEnvironment* EnvironmentMaps::get(const scene::EnvironmentLightInstance& light,
                                           scene::SceneTraversal& traversal,
                                           base::Fetcher* fetcher) {
  const vrml::Node& node = *light.node;
  auto [it, added] = entries_.try_emplace(&node);
  Entry& e = it->second;
  const std::uint64_t revision = vrml::revisionWithFields(node);
  if (!added && e.done && e.revision == revision) return e.gpu.usable ? &e.gpu : nullptr;
  if (e.gpu.cubeMap != 0) glDeleteTextures(1, &e.gpu.cubeMap);
  e.gpu = {};
  e.revision = revision;

  const vrml::NodePtr specular = node.sfnode("specularTexture");
  const vrml::NodePtr diffuse = node.sfnode("diffuseTexture");
  FaceImages specularFaces, diffuseFaces;
  // A problem names the texture (an ImageCubeMapTexture's says only what its url gave).
  const auto load = [&](const vrml::NodePtr& texture, const char* field) {
    FaceImages faces = loadFaces(*texture, texture->urlBaseOr(*light.baseUrl), fetcher);
    if (!faces.problem.empty() && !faces.problem.starts_with(texture->typeName()))
      faces.problem = std::string(field) + " " + texture->typeName() + ": " + faces.problem;
    return faces;
  };
  if (specular && !specular->unresolved) specularFaces = load(specular, "specularTexture");
  if (diffuse && !diffuse->unresolved) diffuseFaces = load(diffuse, "diffuseTexture");
  if (specularFaces.pending || diffuseFaces.pending) return nullptr;  // ask again next draw
  e.done = true;
  for (const std::string* problem : {&specularFaces.problem, &diffuseFaces.problem})
    if (!problem->empty())
      traversal.report(vrml::Severity::warning, node.location,
                       "EnvironmentLight: " + *problem + ": that image-based light is not drawn");

  const auto cubeOf = [](const FaceImages& f) {
    std::array<const Image*, 6> faces{};
    for (std::size_t i = 0; i < 6; ++i) faces[i] = &f.images[i];
    return resampleCubeFaces(faces, std::clamp(f.size, kMinCubeSize, kMaxCubeSize));
  };
  bool haveIrradiance =
      irradianceFromCoefficients(scene::mfFloat(node, "diffuseCoefficients"), e.gpu.irradiance);
  if (!haveIrradiance && diffuseFaces.size > 0) {
    e.gpu.irradiance = irradianceOf(cubeOf(diffuseFaces));
    haveIrradiance = true;
  }
  if (specularFaces.size > 0) {
    const CubeFaces cube = cubeOf(specularFaces);
    if (!haveIrradiance) {
      e.gpu.irradiance = irradianceOf(cube);
      haveIrradiance = true;
    }
    e.gpu.cubeMap = uploadCubeMap(cube);
    e.gpu.maxLod = std::floor(std::log2(static_cast<float>(cube.size)));
  }
  e.gpu.usable = haveIrradiance || e.gpu.cubeMap != 0;
  if (!e.gpu.usable && specularFaces.problem.empty() && diffuseFaces.problem.empty())
    traversal.report(vrml::Severity::warning, node.location,
                     "EnvironmentLight has no specularTexture, diffuseTexture or "
                     "diffuseCoefficients: it lights nothing");
  return e.gpu.usable ? &e.gpu : nullptr;
}

void EnvironmentMaps::release() {
  for (auto& [node, e] : entries_)
    if (e.gpu.cubeMap != 0) glDeleteTextures(1, &e.gpu.cubeMap);
  entries_.clear();
}

}  // namespace gs::render::detail
