// Node maths: Transform, LOD, Billboard and TextureTransform matrices; URL resolution.
#include "node_access.hpp"
#include "render/traversal.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace gs::render {

namespace detail {
const std::vector<float>& mfFloat(const vrml::Node& n, std::string_view name) {
  static const std::vector<float> kEmpty;
  return fieldRef<vrml::FieldType::MFFloat>(n, name, kEmpty);
}
const std::vector<glm::vec3>& mfColor(const vrml::Node& n, std::string_view name) {
  static const std::vector<glm::vec3> kEmpty;
  return fieldRef<vrml::FieldType::MFColor>(n, name, kEmpty);
}
const std::vector<std::string>& mfString(const vrml::Node& n, std::string_view name) {
  static const std::vector<std::string> kEmpty;
  return fieldRef<vrml::FieldType::MFString>(n, name, kEmpty);
}
const std::string& sfString(const vrml::Node& n, std::string_view name) {
  static const std::string kEmpty;
  return fieldRef<vrml::FieldType::SFString>(n, name, kEmpty);
}
glm::mat3 rotationPart(const glm::mat4& m) {
  glm::mat3 r(m);
  for (int c = 0; c < 3; ++c) {
    const float len = glm::length(r[c]);
    r[c] = len > 0.0f ? r[c] / len : glm::vec3(c == 0, c == 1, c == 2);
  }
  return r;
}
float meanScale(const glm::mat4& m) {
  return std::cbrt(std::abs(glm::determinant(glm::mat3(m))));
}
}  // namespace detail

using namespace detail;

int selectLodLevel(const std::vector<float>& range, float distance, std::size_t levelCount) {
  if (levelCount == 0) return -1;
  std::size_t level = 0;
  while (level < range.size() && distance >= range[level]) ++level;
  return static_cast<int>(std::min(level, levelCount - 1));
}

glm::mat4 billboardRotation(const glm::vec3& axisOfRotation, const glm::vec3& viewer,
                            const glm::vec3& viewerUp) {
  const float axisLength = glm::length(axisOfRotation);
  if (axisLength < 1e-9f) {
    // Viewer-aligned: Z towards the viewer, Y along the viewer's up vector.
    if (glm::length(viewer) < 1e-9f) return glm::mat4(1.0f);
    const glm::vec3 z = glm::normalize(viewer);
    glm::vec3 x = glm::cross(viewerUp, z);
    if (glm::length(x) < 1e-9f) return glm::mat4(1.0f);
    x = glm::normalize(x);
    const glm::vec3 y = glm::cross(z, x);
    return glm::mat4(glm::mat3(x, y, z));
  }
  const glm::vec3 axis = axisOfRotation / axisLength;
  // The viewer direction and the local Z axis, both projected on the plane normal to axis.
  const glm::vec3 toViewer = viewer - glm::dot(viewer, axis) * axis;
  const glm::vec3 localZ = glm::vec3(0, 0, 1) - axis.z * axis;
  if (glm::length(toViewer) < 1e-9f || glm::length(localZ) < 1e-9f) return glm::mat4(1.0f);
  const glm::vec3 to = glm::normalize(toViewer), from = glm::normalize(localZ);
  const float angle = std::atan2(glm::dot(glm::cross(from, to), axis), glm::dot(from, to));
  return glm::rotate(glm::mat4(1.0f), angle, axis);
}

glm::mat3 textureTransformMatrix(const vrml::Node& tt) {
  const glm::vec2 c = sfVec2(tt, "center", glm::vec2(0.0f));
  const glm::vec2 s = sfVec2(tt, "scale", glm::vec2(1.0f));
  const glm::vec2 t = sfVec2(tt, "translation", glm::vec2(0.0f));
  const float a = sfFloat(tt, "rotation", 0.0f);
  auto translate = [](glm::vec2 v) {
    glm::mat3 m(1.0f);
    m[2] = glm::vec3(v, 1.0f);
    return m;
  };
  glm::mat3 rot(1.0f);
  rot[0] = glm::vec3(std::cos(a), std::sin(a), 0.0f);
  rot[1] = glm::vec3(-std::sin(a), std::cos(a), 0.0f);
  glm::mat3 scale(1.0f);
  scale[0][0] = s.x;
  scale[1][1] = s.y;
  return translate(-c) * scale * rot * translate(c) * translate(t);
}

namespace {

// Length of the scheme ("http" in "http://...") or 0 when `s` has none. One-letter
// schemes are taken as Windows drive letters, not schemes.
std::size_t schemeLength(const std::string& s) {
  if (s.empty() || !std::isalpha(static_cast<unsigned char>(s[0]))) return 0;
  for (std::size_t i = 1; i < s.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c == ':') return i >= 2 ? i : 0;
    if (!std::isalnum(c) && c != '+' && c != '-' && c != '.') return 0;
  }
  return 0;
}

// Removes "." and ".." segments; `path` may be relative (leading ".." are kept).
std::string removeDotSegments(const std::string& path) {
  const bool absolute = !path.empty() && path[0] == '/';
  std::vector<std::string> out;
  std::size_t start = absolute ? 1 : 0;
  bool trailingSlash = false;
  while (start <= path.size()) {
    std::size_t end = path.find('/', start);
    if (end == std::string::npos) end = path.size();
    const std::string segment = path.substr(start, end - start);
    trailingSlash = false;
    if (segment == "." || segment.empty()) {
      trailingSlash = end < path.size() || segment == ".";
    } else if (segment == "..") {
      if (!out.empty() && out.back() != "..")
        out.pop_back();
      else if (!absolute)
        out.push_back("..");
      trailingSlash = true;
    } else {
      out.push_back(segment);
    }
    start = end + 1;
  }
  std::string result = absolute ? "/" : "";
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (i > 0) result += '/';
    result += out[i];
  }
  if (trailingSlash && !out.empty()) result += '/';
  return result;
}

}  // namespace

std::string resolveUrl(const std::string& base, const std::string& reference) {
  if (reference.empty()) return base;
  if (schemeLength(reference) > 0) return reference;
  const std::size_t scheme = schemeLength(base);
  // Split base into "scheme://authority" and its path.
  std::string prefix, basePath = base;
  if (scheme > 0 && base.compare(scheme, 3, "://") == 0) {
    const std::size_t pathStart = base.find('/', scheme + 3);
    prefix = base.substr(0, pathStart == std::string::npos ? base.size() : pathStart);
    basePath = pathStart == std::string::npos ? "/" : base.substr(pathStart);
  } else if (scheme > 0) {
    prefix = base.substr(0, scheme + 1);
    basePath = base.substr(scheme + 1);
  }
  if (reference.size() >= 2 && reference[0] == '/' && reference[1] == '/')
    return scheme > 0 ? base.substr(0, scheme + 1) + reference : reference;
  if (reference[0] == '/') return prefix + removeDotSegments(reference);
  const std::size_t slash = basePath.rfind('/');
  const std::string directory = slash == std::string::npos ? "" : basePath.substr(0, slash + 1);
  return prefix + removeDotSegments(directory + reference);
}

std::string localPathOfUrl(const std::string& url) {
  const std::size_t scheme = schemeLength(url);
  if (scheme == 0) return url;
  std::string lower = url.substr(0, scheme);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (lower != "file") return {};
  std::string path = url.substr(scheme + 1);
  if (path.rfind("//", 0) == 0) {
    path = path.substr(2);
    const std::size_t slash = path.find('/');
    path = slash == std::string::npos ? std::string() : path.substr(slash);  // drop host
  }
  std::string decoded;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (path[i] == '%' && i + 2 < path.size() &&
        std::isxdigit(static_cast<unsigned char>(path[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(path[i + 2]))) {
      decoded += static_cast<char>(std::stoi(path.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      decoded += path[i];
    }
  }
  return decoded;
}

}  // namespace gs::render
