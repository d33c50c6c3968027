// ImageTexture and PixelTexture to GL textures (clauses 6.22, 6.33), with mipmaps, the
// repeatS / repeatT wrap modes or X3D's TextureProperties (filters, boundary modes);
// MovieTexture goes to movie_textures.cpp.
#include "base/data_url.hpp"
#include "base/url.hpp"
#include "environment_maps.hpp"
#include "gpu_resources.hpp"
#include "render/image.hpp"
#include "render/scene_renderer.hpp"
#include "scene/node_access.hpp"

#include <algorithm>

namespace gs::render::detail {
namespace {

/// How a texture is sampled: VRML97's repeatS / repeatT (6.22), or X3D 4.0's
/// TextureProperties (clause 18.4.9) when the texture has one (which then overrides them).
struct Sampling {
  GLint minFilter = GL_LINEAR_MIPMAP_LINEAR, magFilter = GL_LINEAR;
  GLint wrapS = GL_REPEAT, wrapT = GL_REPEAT, wrapR = GL_REPEAT;
};

GLint boundaryMode(const std::string& mode) {
  if (mode == "MIRRORED_REPEAT") return GL_MIRRORED_REPEAT;
  if (mode == "CLAMP" || mode == "CLAMP_TO_EDGE") return GL_CLAMP_TO_EDGE;
  if (mode == "CLAMP_TO_BOUNDARY") return GL_CLAMP_TO_BORDER;
  return GL_REPEAT;  // REPEAT and anything unknown
}

// X3D 4.0 tables 18.7 and 18.8. FASTEST is nearest (as castle-engine reads it); NICEST
// and DEFAULT are the trilinear / bilinear filtering GhostSpace draws without one.
GLint minificationFilter(const std::string& mode) {
  if (mode == "AVG_PIXEL") return GL_LINEAR;
  if (mode == "AVG_PIXEL_NEAREST_MIPMAP") return GL_LINEAR_MIPMAP_NEAREST;
  if (mode == "NEAREST_PIXEL" || mode == "FASTEST") return GL_NEAREST;
  if (mode == "NEAREST_PIXEL_AVG_MIPMAP") return GL_NEAREST_MIPMAP_LINEAR;
  if (mode == "NEAREST_PIXEL_NEAREST_MIPMAP") return GL_NEAREST_MIPMAP_NEAREST;
  return GL_LINEAR_MIPMAP_LINEAR;  // AVG_PIXEL_AVG_MIPMAP, NICEST, DEFAULT
}

const vrml::NodePtr kNoNode;

GLint magnificationFilter(const std::string& mode) {
  return mode == "NEAREST_PIXEL" || mode == "FASTEST" ? GL_NEAREST : GL_LINEAR;
}

/// `quality` picks the minification filter of a texture without TextureProperties.
Sampling samplingOf(const vrml::Node& texture, TextureQuality quality) {
  Sampling s;
  s.minFilter = quality == TextureQuality::low      ? GL_LINEAR
                : quality == TextureQuality::medium ? GL_NEAREST_MIPMAP_LINEAR
                                                    : GL_LINEAR_MIPMAP_LINEAR;
  s.wrapS = scene::sfBool(texture, "repeatS", true) ? GL_REPEAT : GL_CLAMP_TO_EDGE;
  s.wrapT = scene::sfBool(texture, "repeatT", true) ? GL_REPEAT : GL_CLAMP_TO_EDGE;
  s.wrapR = scene::sfBool(texture, "repeatR", true) ? GL_REPEAT : GL_CLAMP_TO_EDGE;
  static const vrml::NodePtr kNone;
  const vrml::NodePtr& p =
      scene::fieldRef<vrml::FieldType::SFNode>(texture, "textureProperties", kNone);
  if (!p || p->typeId() != vrml::NodeTypeId::TextureProperties) return s;
  s.wrapS = boundaryMode(scene::sfString(*p, "boundaryModeS"));
  s.wrapT = boundaryMode(scene::sfString(*p, "boundaryModeT"));
  s.wrapR = boundaryMode(scene::sfString(*p, "boundaryModeR"));
  s.minFilter = minificationFilter(scene::sfString(*p, "minificationFilter"));
  s.magFilter = magnificationFilter(scene::sfString(*p, "magnificationFilter"));
  return s;
}

/// Mipmaps, filters and S/T wrapping of the texture bound to `target`.
void applySampling(GLenum target, const Sampling& sampling) {
  glGenerateMipmap(target);
  glTexParameteri(target, GL_TEXTURE_MIN_FILTER, sampling.minFilter);
  glTexParameteri(target, GL_TEXTURE_MAG_FILTER, sampling.magFilter);
  glTexParameteri(target, GL_TEXTURE_WRAP_S, sampling.wrapS);
  glTexParameteri(target, GL_TEXTURE_WRAP_T, sampling.wrapT);
}

GLuint uploadRgba(const std::uint8_t* rowsBottomUp, int width, int height,
                  const Sampling& sampling) {
  GLuint id = 0;
  glGenTextures(1, &id);
  glBindTexture(GL_TEXTURE_2D, id);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               rowsBottomUp);
  applySampling(GL_TEXTURE_2D, sampling);
  glBindTexture(GL_TEXTURE_2D, 0);
  return id;
}

GLuint uploadRgba3D(const Texels3D& t, const Sampling& sampling) {
  GLuint id = 0;
  glGenTextures(1, &id);
  glBindTexture(GL_TEXTURE_3D, id);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage3D(GL_TEXTURE_3D, 0, GL_RGBA8, t.width, t.height, t.depth, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               t.rgba.data());
  applySampling(GL_TEXTURE_3D, sampling);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_R, sampling.wrapR);
  glBindTexture(GL_TEXTURE_3D, 0);
  return id;
}

bool anyTranslucent(const std::vector<std::uint8_t>& rgba) {
  for (std::size_t i = 3; i < rgba.size(); i += 4)
    if (rgba[i] != 255) return true;
  return false;
}

}  // namespace

LoadedImage loadFirstImage(const std::vector<std::string>& urls, const std::string& baseUrl,
                           base::Fetcher* fetcher) {
  LoadedImage out;
  for (const std::string& reference : urls) {
    if (reference.empty()) continue;
    const std::string url = base::resolveUrl(baseUrl, reference);
    // Local files, data: URLs (glTF, X3D 4) and the network, under the one set of rules
    // (a world from the network never reads local files).
    const base::Fetched got =
        base::fetcherOr(fetcher).fetch(url, baseUrl, base::FetchMode::background);
    if (got.pending()) {
      out.pending = true;  // on its way: the next url only if this one fails
      return out;
    }
    std::string error = got.error;
    if (got.ready()) {
      try {
        int components = 0;
        out.image = decodeImage(got.bytes, url, &components);
        out.components = std::clamp(components, 1, 4);
        // A palette or tRNS transparency makes an RGB or grey file RGBA or grey+alpha.
        if (anyTranslucent(out.image.rgba)) {
          out.hasAlpha = true;
          if (out.components == 3) out.components = 4;
          if (out.components == 1) out.components = 2;
        }
        out.url = url;
        return out;
      } catch (const std::exception& e) {
        error = e.what();
      }
    }
    const std::string shown =
        base::isDataUrl(url) && url.size() > 48 ? url.substr(0, 48) + "..." : url;
    if (!got.ready()) {
      out.failures += (out.failures.empty() ? "" : "; ") + error;  // names the URL
    } else {
      out.failures += (out.failures.empty() ? "" : "; ") + shown + ": " + error;
    }
  }
  return out;
}

namespace {

GpuTexture uploadSampled(const LoadedImage& loaded, const Sampling& sampling) {
  GpuTexture texture;
  const Image& image = loaded.image;
  // GL wants the bottom row first; VRML's (0, 0) is the image's lower-left corner.
  const std::size_t row = static_cast<std::size_t>(image.width) * 4;
  std::vector<std::uint8_t> flipped(image.rgba.size());
  for (int y = 0; y < image.height; ++y)
    std::copy_n(image.rgba.data() + static_cast<std::size_t>(y) * row, row,
                flipped.data() + static_cast<std::size_t>(image.height - 1 - y) * row);
  texture.id = uploadRgba(flipped.data(), image.width, image.height, sampling);
  texture.components = loaded.components;
  texture.hasAlpha = loaded.hasAlpha;
  texture.width = image.width;
  texture.height = image.height;
  return texture;
}

}  // namespace

GpuTexture uploadImage(const LoadedImage& loaded, bool repeatS, bool repeatT) {
  Sampling sampling;
  sampling.wrapS = repeatS ? GL_REPEAT : GL_CLAMP_TO_EDGE;
  sampling.wrapT = repeatT ? GL_REPEAT : GL_CLAMP_TO_EDGE;
  return uploadSampled(loaded, sampling);
}

bool decodeSFImage(const vrml::SFImage& image, std::vector<std::uint8_t>& rgba, bool& hasAlpha) {
  hasAlpha = false;
  if (image.width <= 0 || image.height <= 0 || image.components < 1 || image.components > 4 ||
      image.width > 16384 || image.height > 16384 ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height)
    return false;
  rgba.resize(image.pixels.size() * 4);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const std::uint32_t p = image.pixels[i];
    std::uint8_t r, g, b, a = 255;
    switch (image.components) {
      case 1:
        r = g = b = static_cast<std::uint8_t>(p & 0xFF);
        break;
      case 2:
        r = g = b = static_cast<std::uint8_t>((p >> 8) & 0xFF);
        a = static_cast<std::uint8_t>(p & 0xFF);
        break;
      case 3:
        r = static_cast<std::uint8_t>((p >> 16) & 0xFF);
        g = static_cast<std::uint8_t>((p >> 8) & 0xFF);
        b = static_cast<std::uint8_t>(p & 0xFF);
        break;
      default:
        r = static_cast<std::uint8_t>((p >> 24) & 0xFF);
        g = static_cast<std::uint8_t>((p >> 16) & 0xFF);
        b = static_cast<std::uint8_t>((p >> 8) & 0xFF);
        a = static_cast<std::uint8_t>(p & 0xFF);
        break;
    }
    rgba[i * 4] = r;
    rgba[i * 4 + 1] = g;
    rgba[i * 4 + 2] = b;
    rgba[i * 4 + 3] = a;
    if (a != 255) hasAlpha = true;
  }
  return true;
}

const GpuTexture& TextureCache::get(const vrml::Node& node, const std::string& inheritedBase,
                                    scene::SceneTraversal& traversal, base::Fetcher* fetcher) {
  // A texture written in an EXTERNPROTO's file resolves against that file (Node::urlBase).
  const std::string& baseUrl = node.urlBaseOr(inheritedBase);
  if (node.typeId() == vrml::NodeTypeId::MovieTexture)
    return movies.get(node, baseUrl, traversal, fetcher);
  if (auto it = textures_.find(&node); it != textures_.end()) return it->second;
  GpuTexture texture;
  Sampling sampling = samplingOf(node, quality_);
  // X_ITE 15 draws an X3D texture without TextureProperties whose sides are both under 16
  // texels with nearest texels and no mipmaps (its Browser's getMinTextureSize), so a
  // PixelTexture checkerboard stays crisp; VRML97's stay filtered, as castle draws them.
  const bool x3dSmallDefaults =
      !traversal.scene().x3d.version.empty() &&
      !scene::fieldRef<vrml::FieldType::SFNode>(node, "textureProperties", kNoNode);
  const auto smallTexture = [&](int width, int height) {
    if (x3dSmallDefaults && std::max(width, height) < 16)
      sampling.minFilter = sampling.magFilter = GL_NEAREST;
  };
  if (node.typeId() == vrml::NodeTypeId::PixelTexture) {
    std::vector<std::uint8_t> rgba;
    static const vrml::SFImage kEmpty;
    const vrml::SFImage& image = scene::fieldRef<vrml::FieldType::SFImage>(node, "image", kEmpty);
    bool hasAlpha = false;
    if (image.width == 0 || image.height == 0) {
      // An empty PixelTexture means no texture (clause 6.33).
    } else if (decodeSFImage(image, rgba, hasAlpha)) {
      smallTexture(image.width, image.height);
      texture.id = uploadRgba(rgba.data(), image.width, image.height, sampling);
      texture.components = image.components;
      texture.hasAlpha = hasAlpha;
      texture.width = image.width;
      texture.height = image.height;
    } else {
      traversal.report(vrml::Severity::warning, node.location,
                       "PixelTexture image is inconsistent: drawn untextured");
    }
  } else if (node.typeId() == vrml::NodeTypeId::ImageTexture) {
    LoadedImage loaded = loadFirstImage(scene::mfString(node, "url"), baseUrl, fetcher);
    if (loaded.pending) {
      static const GpuTexture kNone;  // untextured until the bytes arrive
      return kNone;
    }
    if (loaded.components > 0) {
      smallTexture(loaded.image.width, loaded.image.height);
      texture = uploadSampled(loaded, sampling);
    } else {
      traversal.report(
          vrml::Severity::warning, node.location,
          loaded.failures.empty()
              ? std::string("ImageTexture has no url: drawn untextured")
              : "cannot load ImageTexture (" + loaded.failures + "): drawn untextured");
    }
  } else if (node.typeId() == vrml::NodeTypeId::PixelTexture3D ||
             node.typeId() == vrml::NodeTypeId::ComposedTexture3D ||
             node.typeId() == vrml::NodeTypeId::ImageTexture3D) {
    const Texels3D texels = decodeTexture3D(node, baseUrl, fetcher);
    if (texels.pending) {
      static const GpuTexture kNone;  // untextured until the bytes arrive
      return kNone;
    }
    if (!texels.problem.empty())
      traversal.report(vrml::Severity::warning, node.location,
                       node.typeName() + ": " + texels.problem + ": drawn untextured");
    if (texels.depth > 0 && !texels.rgba.empty()) {
      smallTexture(texels.width, texels.height);  // X_ITE: width and height, not depth
      texture.id = uploadRgba3D(texels, sampling);
      texture.components = texels.components;
      texture.hasAlpha = anyTranslucent(texels.rgba);
      texture.volume = true;
    }
  } else if (node.typeId() == vrml::NodeTypeId::ComposedCubeMapTexture ||
             node.typeId() == vrml::NodeTypeId::ImageCubeMapTexture) {
    CubeTexture cube = loadCubeTexture(node, baseUrl, fetcher);
    if (cube.pending) {
      static const GpuTexture kNone;  // untextured until the faces arrive
      return kNone;
    }
    if (!cube.problem.empty())
      traversal.report(
          vrml::Severity::warning, node.location,
          node.typeName() + ": " + cube.problem +
              (node.typeId() == vrml::NodeTypeId::ComposedCubeMapTexture ? ": that face is black"
                                                                         : ": drawn untextured"));
    texture.id = cube.id;
    texture.components = cube.id != 0 ? 3 : 0;
    texture.cube = true;
  } else {
    traversal.report(vrml::Severity::warning, node.location,
                     node.typeName() + " is not supported yet: drawn untextured");
  }
  if (node.is(vrml::AbstractType::X3DUrlObject)) loads_.emplace_back(&node, texture.id != 0);
  return textures_.emplace(&node, texture).first->second;
}

void TextureCache::release() {
  for (auto& [node, texture] : textures_)
    if (texture.id != 0) glDeleteTextures(1, &texture.id);
  textures_.clear();
  movies.release();
}

}  // namespace gs::render::detail
