// glTF 2.0 KHR_gaussian_splatting (readers.hpp; Khronos extension README, release
// candidate): POINTS primitives whose attributes are POSITION,
// KHR_gaussian_splatting:ROTATION (x y z w), :SCALE (linear), :OPACITY (0..1) and
// :SH_DEGREE_l_COEF_n (RGB), with `kernel` and `colorSpace` on the extension object. Every
// such primitive of every mesh instance of the default scene is placed by its node's world
// transform M (covariance M C C^T M^T, SH rotated by M's rotation) and then turned from
// glTF's axes to the .ply axes: 180 degrees about Z, the inverse of what splat-transform
// 3.7's writeGlb applies (Transform.PLY to IDENTITY).
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gltf/accessors.hpp"
#include "gltf/document.hpp"
#include "gltf_gaussians.hpp"
#include "reader_support.hpp"
#include "splats/lod_tree.hpp"

namespace gs::splats {

namespace {

using detail::fail;

/// Real SH of band `band` (1..3) at unit `d`, in the project's basis (evaluateSh).
std::vector<double> basis(int band, const glm::vec3& d) {
  std::vector<double> y;
  const int first = shCoefficients(band - 1), last = shCoefficients(band);
  for (int k = first; k < last; ++k) {
    std::array<glm::vec3, 16> c{};
    c[static_cast<std::size_t>(k)] = glm::vec3(1.0f, 0.0f, 0.0f);
    y.push_back(evaluateSh(3, c.data(), d).x);
  }
  return y;
}

/// The matrix D of band `band` with c' = D c for coefficients c of a function f and c' of
/// g(d) = f(R^T d) (the function turned by R): least squares over 64 directions spread
/// over the sphere (a Fibonacci lattice), which determine each band exactly.
std::vector<double> shRotation(int band, const glm::mat3& r) {
  const int n = 2 * band + 1;
  constexpr int kSamples = 64;
  std::vector<double> ata(static_cast<std::size_t>(n * n), 0.0),
      atb(static_cast<std::size_t>(n * n), 0.0);
  for (int s = 0; s < kSamples; ++s) {
    const double z = 1.0 - (2.0 * s + 1.0) / kSamples, rad = std::sqrt(1.0 - z * z);
    const double phi = s * 2.399963229728653;  // golden angle
    const glm::vec3 d(static_cast<float>(rad * std::cos(phi)),
                      static_cast<float>(rad * std::sin(phi)), static_cast<float>(z));
    const std::vector<double> a = basis(band, d), b = basis(band, glm::transpose(r) * d);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        ata[static_cast<std::size_t>(i * n + j)] +=
            a[static_cast<std::size_t>(i)] * a[static_cast<std::size_t>(j)];
        atb[static_cast<std::size_t>(i * n + j)] +=
            a[static_cast<std::size_t>(i)] * b[static_cast<std::size_t>(j)];
      }
  }
  // Solve ata * D = atb by Gauss-Jordan elimination with partial pivoting (ata is SPD).
  for (int col = 0; col < n; ++col) {
    int pivot = col;
    for (int row = col + 1; row < n; ++row)
      if (std::fabs(ata[static_cast<std::size_t>(row * n + col)]) >
          std::fabs(ata[static_cast<std::size_t>(pivot * n + col)]))
        pivot = row;
    for (int j = 0; j < n; ++j) {
      std::swap(ata[static_cast<std::size_t>(col * n + j)],
                ata[static_cast<std::size_t>(pivot * n + j)]);
      std::swap(atb[static_cast<std::size_t>(col * n + j)],
                atb[static_cast<std::size_t>(pivot * n + j)]);
    }
    const double p = ata[static_cast<std::size_t>(col * n + col)];
    for (int j = 0; j < n; ++j) {
      ata[static_cast<std::size_t>(col * n + j)] /= p;
      atb[static_cast<std::size_t>(col * n + j)] /= p;
    }
    for (int row = 0; row < n; ++row) {
      if (row == col) continue;
      const double f = ata[static_cast<std::size_t>(row * n + col)];
      for (int j = 0; j < n; ++j) {
        ata[static_cast<std::size_t>(row * n + j)] -=
            f * ata[static_cast<std::size_t>(col * n + j)];
        atb[static_cast<std::size_t>(row * n + j)] -=
            f * atb[static_cast<std::size_t>(col * n + j)];
      }
    }
  }
  return atb;  // D, row-major
}

}  // namespace

namespace detail {

GltfSplatAttributes gltfSplatAttributes(const tinygltf::Primitive& prim, const tinygltf::Value& ext,
                                        const std::string& name) {
  if (prim.mode != TINYGLTF_MODE_POINTS)
    fail(name, "a KHR_gaussian_splatting primitive must be POINTS");
  GltfSplatAttributes a;
  // colorSpace (required) and kernel (unknown kernels fall back to the ellipse).
  if (ext.IsObject() && ext.Has("colorSpace") && ext.Get("colorSpace").IsString()) {
    const std::string cs = ext.Get("colorSpace").Get<std::string>();
    if (cs == "lin_rec709_display")
      a.colorSpace = ColorSpace::linear;
    else if (cs != "srgb_rec709_display")
      fail(name, "unsupported KHR_gaussian_splatting colorSpace '" + cs + "'");
  }
  const auto attribute = [&](const std::string& semantic) {
    const auto it = prim.attributes.find(semantic);
    return it == prim.attributes.end() ? -1 : it->second;
  };
  a.position = attribute("POSITION");
  if (a.position < 0) fail(name, "a KHR_gaussian_splatting primitive lacks POSITION");
  const std::string pre = std::string(kGltfSplatExtension) + ":";
  const auto required = [&](const std::string& semantic) {
    const int i = attribute(pre + semantic);
    if (i < 0) fail(name, "attribute " + pre + semantic + " missing");
    return i;
  };
  a.rotation = required("ROTATION");
  a.scale = required("SCALE");
  a.opacity = required("OPACITY");
  a.dc = attribute(pre + "SH_DEGREE_0_COEF_0");
  if (a.dc < 0) a.color = attribute("COLOR_0");  // the fallback colour
  if (a.dc < 0 && a.color < 0) fail(name, "attribute " + pre + "SH_DEGREE_0_COEF_0 missing");
  // Degrees 1..3, each complete or absent (lower degrees first).
  for (int l = 1; l <= kMaxShDegree; ++l) {
    std::vector<int> band;
    for (int m = 0; m < 2 * l + 1; ++m) {
      const int i =
          attribute(pre + "SH_DEGREE_" + std::to_string(l) + "_COEF_" + std::to_string(m));
      if (i < 0) break;
      band.push_back(i);
    }
    if (band.empty()) break;
    if (band.size() != static_cast<std::size_t>(2 * l + 1))
      fail(name, "SH degree " + std::to_string(l) + " is only partly defined");
    a.rest.insert(a.rest.end(), band.begin(), band.end());
    a.degree = l;
  }
  return a;
}

void forEachGltfSplatPrimitive(
    const tinygltf::Model& model, const std::string& name,
    const std::function<void(const tinygltf::Primitive&, const tinygltf::Value&,
                             const glm::dmat4&)>& visit) {
  std::vector<char> visited(model.nodes.size(), 0);
  std::vector<std::pair<int, glm::dmat4>> stack;
  const std::vector<int> roots = gltf::sceneRoots(model);
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, glm::dmat4(1.0));
  while (!stack.empty()) {
    const auto [index, parent] = stack.back();
    stack.pop_back();
    if (index < 0 || static_cast<std::size_t>(index) >= model.nodes.size())
      fail(name, "node " + std::to_string(index) + " does not exist");
    if (visited[static_cast<std::size_t>(index)]++)
      fail(name, "node " + std::to_string(index) + " is reached twice (not a tree)");
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(index)];
    glm::dmat4 local(1.0);
    if (node.matrix.size() == 16) {
      local = glm::make_mat4(node.matrix.data());
    } else {
      if (node.translation.size() == 3)
        local = glm::translate(
            local, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
      if (node.rotation.size() == 4)
        local =
            local * glm::mat4_cast(glm::normalize(glm::dquat(node.rotation[3], node.rotation[0],
                                                             node.rotation[1], node.rotation[2])));
      if (node.scale.size() == 3)
        local = glm::scale(local, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
    }
    const glm::dmat4 world = parent * local;
    if (node.mesh >= 0 && static_cast<std::size_t>(node.mesh) < model.meshes.size())
      for (const auto& prim : model.meshes[static_cast<std::size_t>(node.mesh)].primitives)
        if (const auto e = prim.extensions.find(kGltfSplatExtension); e != prim.extensions.end())
          visit(prim, e->second, world);
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it)
      stack.emplace_back(*it, world);
  }
}

GltfPlacement::GltfPlacement(const glm::dmat4& world, int degree, const std::string& name)
    : degree_(degree) {
  // Cloud axes = F * world, F = 180 degrees about Z (glTF -> .ply axes).
  const glm::dmat4 f = glm::rotate(glm::dmat4(1.0), glm::pi<double>(), glm::dvec3(0, 0, 1));
  toCloud_ = f * world;
  m_ = glm::dmat3(toCloud_);
  // A similarity (orthogonal columns of one length, det > 0) keeps a scale + rotation;
  // anything else goes through the covariance.
  const double s0 = glm::length(m_[0]), s1 = glm::length(m_[1]), s2 = glm::length(m_[2]);
  const double det = glm::determinant(m_);
  if (!(s0 > 0.0) || !(s1 > 0.0) || !(s2 > 0.0) || !std::isfinite(det) || !(det > 0.0))
    fail(name, "a node's transform is not decomposable (zero, negative or infinite scale)");
  const double tol = 1e-6 * s0;
  s0_ = s0;
  similar_ = std::fabs(s0 - s1) < tol && std::fabs(s0 - s2) < tol &&
             std::fabs(glm::dot(m_[0], m_[1])) < tol * s0 &&
             std::fabs(glm::dot(m_[0], m_[2])) < tol * s0 &&
             std::fabs(glm::dot(m_[1], m_[2])) < tol * s0;
  glm::dmat3 rotation = similar_ ? m_ / s0 : glm::dmat3(1.0);
  if (!similar_) {  // the rotation part of M for the SH: Gram-Schmidt of its columns
    rotation[0] = glm::normalize(m_[0]);
    rotation[1] = glm::normalize(m_[1] - glm::dot(m_[1], rotation[0]) * rotation[0]);
    rotation[2] = glm::cross(rotation[0], rotation[1]);
  }
  turn_ = glm::quat_cast(glm::mat3(rotation));
  for (int l = 1; l <= degree; ++l) d_.push_back(shRotation(l, glm::mat3(rotation)));
}

void GltfPlacement::place(const float* pos, const float* rot, const float* scale, float opacity,
                          const float* dc, const float* const* rest, GaussianCloud& part,
                          std::size_t j) const {
  part.positions[j] = glm::vec3(toCloud_ * glm::dvec4(pos[0], pos[1], pos[2], 1.0));
  const glm::quat q = unitQuat(rot[3], rot[0], rot[1], rot[2]);
  const glm::vec3 sc = glm::abs(glm::vec3(scale[0], scale[1], scale[2]));
  if (similar_) {
    part.rotations[j] = glm::normalize(turn_ * q);
    part.scales[j] = sc * static_cast<float>(s0_);
  } else {
    const glm::dmat3 sigma = m_ * glm::dmat3(covariance(sc, q)) * glm::transpose(m_);
    covarianceToScaleRotation(sigma, part.scales[j], part.rotations[j]);
  }
  part.opacities[j] = std::clamp(opacity, 0.0f, 1.0f);
  part.shDc[j] = glm::vec3(dc[0], dc[1], dc[2]);
  glm::vec3* out = part.shRest.data() + j * static_cast<std::size_t>(part.shRestPerSplat());
  for (int l = 1, k0 = 0; l <= degree_; ++l) {
    const int n = 2 * l + 1;
    const std::vector<double>& dl = d_[static_cast<std::size_t>(l - 1)];
    for (int a = 0; a < n; ++a) {
      glm::dvec3 sum(0.0);
      for (int b = 0; b < n; ++b) {
        const float* src = rest[k0 + b];
        sum += dl[static_cast<std::size_t>(a * n + b)] * glm::dvec3(src[0], src[1], src[2]);
      }
      out[k0 + a] = glm::vec3(sum);
    }
    k0 += n;
  }
}

}  // namespace detail

namespace {

struct Reader {
  const tinygltf::Model& model;
  std::string name;
  std::size_t budget;  // splats still allowed (instancing must not multiply memory)
  GaussianCloud cloud;
  bool haveColorSpace = false;

  std::vector<float> floats(int accessor, int components, const char* what, std::size_t count) {
    std::vector<float> v = gltf::readFloats(model, accessor, components, name, what, kMaxSplats);
    if (v.size() != count * static_cast<std::size_t>(components))
      fail(name, std::string(what) + ": expected " + std::to_string(count) + " elements, got " +
                     std::to_string(v.size() / static_cast<std::size_t>(components)));
    return v;
  }

  void primitive(const tinygltf::Primitive& prim, const tinygltf::Value& ext,
                 const glm::dmat4& world) {
    const detail::GltfSplatAttributes a = detail::gltfSplatAttributes(prim, ext, name);
    if (haveColorSpace && a.colorSpace != cloud.colorSpace)
      fail(name, "primitives differ in colorSpace");
    cloud.colorSpace = a.colorSpace;
    cloud.kernel = Kernel::ellipse;
    haveColorSpace = true;

    const std::vector<float> pos =
        gltf::readFloats(model, a.position, 3, name, "POSITION", kMaxSplats);
    const std::size_t count = pos.size() / 3;
    if (count == 0) return;
    if (count > budget)
      fail(name, "more splats than the file's bytes can hold (instanced " + std::to_string(count) +
                     " more)");
    budget -= count;
    const std::vector<float> rot = floats(a.rotation, 4, "ROTATION", count),
                             scale = floats(a.scale, 3, "SCALE", count),
                             opacity = floats(a.opacity, 1, "OPACITY", count);
    std::vector<float> dc;
    if (a.dc >= 0) {
      dc = floats(a.dc, 3, "SH_DEGREE_0_COEF_0", count);
    } else {
      const gltf::AccessorView v = gltf::accessorView(model, a.color, name, "COLOR_0", true);
      // glTF 2.0 section 3.7.2.1: COLOR_0 is VEC3 or VEC4 (the red, green and blue read).
      if (v.components != 3 && v.components != 4)
        fail(name,
             "COLOR_0: expected VEC3 or VEC4, got " + std::to_string(v.components) + " components");
      std::vector<float> rgba = floats(a.color, v.components, "COLOR_0", count);
      for (std::size_t i = 0; i < count; ++i)
        for (int k = 0; k < 3; ++k)
          dc.push_back(detail::dcOfColor(
              rgba[i * static_cast<std::size_t>(v.components) + static_cast<std::size_t>(k)]));
    }
    std::vector<std::vector<float>> rest;  // coefficient k (1..15) -> RGB per splat
    for (int accessor : a.rest) rest.push_back(floats(accessor, 3, "SH coefficient", count));

    const detail::GltfPlacement placement(world, a.degree, name);
    const std::size_t base = cloud.size();
    GaussianCloud part;
    detail::allocate(part, count, a.degree);
    std::vector<const float*> restAt(rest.size());
    for (std::size_t i = 0; i < count; ++i) {
      for (std::size_t k = 0; k < rest.size(); ++k) restAt[k] = rest[k].data() + i * 3;
      placement.place(&pos[i * 3], &rot[i * 4], &scale[i * 3], opacity[i], &dc[i * 3],
                      restAt.data(), part, i);
    }
    // Primitives of different degrees: the cloud keeps the highest, others padded.
    if (base == 0) {
      const ColorSpace keep = cloud.colorSpace;
      cloud = std::move(part);
      cloud.colorSpace = keep;
      return;
    }
    if (part.shDegree > cloud.shDegree) cloud.setShDegree(part.shDegree);
    cloud.reserve(base + count);
    for (std::size_t i = 0; i < count; ++i) cloud.append(part, i);
  }
};

}  // namespace

GaussianCloud readGltfGaussians(std::string_view bytes, std::string_view name,
                                const SideFileReader& sideFiles) {
  const std::string n(name);
  const gltf::BufferLoader loader = [&](const std::string& uri) -> std::optional<std::string> {
    std::string data, error;
    if (!sideFiles || !sideFiles(uri, data, error)) return std::nullopt;
    return data;
  };
  tinygltf::Model model;
  try {
    model = gltf::load(bytes, n, loader);
  } catch (const gltf::Error& e) {
    throw FormatError(e.what());
  }
  std::size_t budget = bytes.size();
  for (const auto& b : model.buffers) budget += b.data.size();
  Reader r{model, n, std::min(budget, kMaxSplats), {}, false};
  try {
    detail::forEachGltfSplatPrimitive(
        model, n,
        [&](const tinygltf::Primitive& prim, const tinygltf::Value& ext, const glm::dmat4& world) {
          r.primitive(prim, ext, world);
        });
  } catch (const gltf::Error& e) {
    throw FormatError(e.what());
  }
  if (r.cloud.empty())
    fail(n, "no KHR_gaussian_splatting primitive with splats in the default scene");
  return std::move(r.cloud);
}

}  // namespace gs::splats
