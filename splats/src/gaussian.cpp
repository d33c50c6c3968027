// The Gaussian model: covariance, spherical harmonics and the EWA projection
// (splats/gaussian.hpp).
#include "splats/gaussian.hpp"

#include <utility>

#include <glm/gtc/type_ptr.hpp>

namespace gs::splats {

void GaussianCloud::reserve(std::size_t n) {
  positions.reserve(n);
  scales.reserve(n);
  rotations.reserve(n);
  opacities.reserve(n);
  shDc.reserve(n);
  shRest.reserve(n * static_cast<std::size_t>(shRestPerSplat()));
}

void GaussianCloud::resize(std::size_t n) {
  positions.resize(n, glm::vec3(0.0f));
  scales.resize(n, glm::vec3(1.0f));
  rotations.resize(n, glm::quat(1.0f, 0.0f, 0.0f, 0.0f));
  opacities.resize(n, 1.0f);
  shDc.resize(n, glm::vec3(0.0f));
  shRest.resize(n * static_cast<std::size_t>(shRestPerSplat()), glm::vec3(0.0f));
}

void GaussianCloud::append(const GaussianCloud& other, std::size_t i) {
  positions.push_back(other.positions[i]);
  scales.push_back(other.scales[i]);
  rotations.push_back(other.rotations[i]);
  opacities.push_back(other.opacities[i]);
  shDc.push_back(other.shDc[i]);
  const int mine = shRestPerSplat(), theirs = other.shRestPerSplat();
  for (int k = 0; k < mine; ++k) {
    shRest.push_back(
        k < theirs
            ? other.shRest[i * static_cast<std::size_t>(theirs) + static_cast<std::size_t>(k)]
            : glm::vec3(0.0f));
  }
}

void GaussianCloud::appendRange(const GaussianCloud& other, std::size_t first, std::size_t last) {
  if (other.shDegree != shDegree) {
    for (std::size_t i = first; i < last; ++i) append(other, i);
    return;
  }
  const auto range = [&](auto& to, const auto& from, std::size_t per) {
    to.insert(to.end(), from.begin() + static_cast<std::ptrdiff_t>(first * per),
              from.begin() + static_cast<std::ptrdiff_t>(last * per));
  };
  range(positions, other.positions, 1);
  range(scales, other.scales, 1);
  range(rotations, other.rotations, 1);
  range(opacities, other.opacities, 1);
  range(shDc, other.shDc, 1);
  range(shRest, other.shRest, static_cast<std::size_t>(shRestPerSplat()));
}

void GaussianCloud::setShDegree(int degree) {
  degree = std::clamp(degree, 0, kMaxShDegree);
  if (degree == shDegree) return;
  const std::size_t theirs = static_cast<std::size_t>(shRestPerSplat());
  const std::size_t mine = static_cast<std::size_t>(shCoefficients(degree) - 1);
  std::vector<glm::vec3> rest(size() * mine, glm::vec3(0.0f));
  for (std::size_t i = 0; i < size(); ++i)
    for (std::size_t k = 0; k < std::min(mine, theirs); ++k)
      rest[i * mine + k] = shRest[i * theirs + k];
  shRest = std::move(rest);
  shDegree = degree;
}

float importance(const GaussianCloud& cloud, std::size_t i) {
  glm::vec3 s = glm::abs(cloud.scales[i]);
  if (s.x < s.y) std::swap(s.x, s.y);
  if (s.y < s.z) std::swap(s.y, s.z);
  if (s.x < s.y) std::swap(s.x, s.y);
  const float value = cloud.opacities[i] * 3.14159265f * s.x * s.y;
  return std::isfinite(value) ? value : 0.0f;
}

GaussianCloud sortByImportance(const GaussianCloud& cloud) {
  std::vector<std::pair<float, std::uint32_t>> keys(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i)
    keys[i] = {importance(cloud, i), static_cast<std::uint32_t>(i)};
  std::stable_sort(keys.begin(), keys.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  GaussianCloud out;
  out.shDegree = cloud.shDegree;
  out.colorSpace = cloud.colorSpace;
  out.kernel = cloud.kernel;
  out.reserve(cloud.size());
  for (const auto& key : keys) out.append(cloud, key.second);
  return out;
}

glm::mat3 covariance(const glm::vec3& scale, const glm::quat& rotation) {
  const glm::mat3 r = glm::mat3_cast(rotation);
  glm::mat3 m;
  for (int c = 0; c < 3; ++c) m[c] = r[c] * scale[c];
  return m * glm::transpose(m);
}

namespace {

constexpr float kShC1 = 0.4886025119029199f;
constexpr float kShC2[] = {1.0925484305920792f, -1.0925484305920792f, 0.31539156525252005f,
                           -1.0925484305920792f, 0.5462742152960396f};
constexpr float kShC3[] = {-0.5900435899266435f, 2.890611442640554f,   -0.4570457994644658f,
                           0.3731763325901154f,  -0.4570457994644658f, 1.445305721320277f,
                           -0.5900435899266435f};

float linearToSrgb(float c) {
  if (!(c > 0.0f)) return 0.0f;
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

int shBasis(int degree, const glm::vec3& d, float* out) {
  out[0] = kShC0;
  if (degree < 1) return 1;
  const float x = d.x, y = d.y, z = d.z;
  out[1] = -kShC1 * y;
  out[2] = kShC1 * z;
  out[3] = -kShC1 * x;
  if (degree < 2) return 4;
  const float xx = x * x, yy = y * y, zz = z * z, xy = x * y, yz = y * z, xz = x * z;
  out[4] = kShC2[0] * xy;
  out[5] = kShC2[1] * yz;
  out[6] = kShC2[2] * (2.0f * zz - xx - yy);
  out[7] = kShC2[3] * xz;
  out[8] = kShC2[4] * (xx - yy);
  if (degree < 3) return 9;
  out[9] = kShC3[0] * y * (3.0f * xx - yy);
  out[10] = kShC3[1] * xy * z;
  out[11] = kShC3[2] * y * (4.0f * zz - xx - yy);
  out[12] = kShC3[3] * z * (2.0f * zz - 3.0f * xx - 3.0f * yy);
  out[13] = kShC3[4] * x * (4.0f * zz - xx - yy);
  out[14] = kShC3[5] * z * (xx - yy);
  out[15] = kShC3[6] * x * (xx - 3.0f * yy);
  return 16;
}

glm::vec3 evaluateSh(int degree, const glm::vec3* sh, const glm::vec3& d) {
  float basis[16];
  const int n = shBasis(degree, d, basis);
  glm::vec3 result = basis[0] * sh[0];
  for (int k = 1; k < n; ++k) result += basis[k] * sh[k];
  return result;
}

glm::vec3 shColor(const GaussianCloud& cloud, std::size_t i, const glm::vec3& direction) {
  std::array<glm::vec3, 16> coefficients;
  coefficients[0] = cloud.shDc[i];
  const int rest = cloud.shRestPerSplat();
  for (int k = 0; k < rest; ++k)
    coefficients[static_cast<std::size_t>(k + 1)] =
        cloud.shRest[i * static_cast<std::size_t>(rest) + static_cast<std::size_t>(k)];
  glm::vec3 c = evaluateSh(cloud.shDegree, coefficients.data(), direction) + 0.5f;
  c = glm::max(c, glm::vec3(0.0f));
  if (cloud.colorSpace == ColorSpace::linear)
    c = glm::vec3(linearToSrgb(c.r), linearToSrgb(c.g), linearToSrgb(c.b));
  return c;
}

bool projectGaussian(const glm::vec3& position, const glm::mat3& sigma, const ProjectionView& view,
                     ProjectedGaussian& out) {
  const glm::vec4 eye = view.modelView * glm::vec4(position, 1.0f);
  const float depth = -eye.z;
  if (!(depth >= view.nearClip) || !(depth <= view.farClip)) return false;
  // Camera looking down +z with y down, as Kerbl et al.: t = (x, -y, depth) in pixels' sense.
  const float tx = eye.x, ty = eye.y, tz = depth;
  // The Jacobian of (fx x / z, fy y / z) at the centre; Kerbl et al. clamp x/z, y/z to 1.3
  // times the half field of view so that splats far off-screen do not explode.
  const float limX = 1.3f * 0.5f * static_cast<float>(view.width) / view.fx;
  const float limY = 1.3f * 0.5f * static_cast<float>(view.height) / view.fy;
  const float txz = std::clamp(tx / tz, -limX, limX) * tz;
  const float tyz = std::clamp(ty / tz, -limY, limY) * tz;
  // Eye space with z pointing forward: (x, y, -z_gl); the y sign does not change the
  // 2D covariance's form in a y-up pixel frame. W is the model-view's rotation with its z
  // row negated (that flip).
  const glm::mat4& w = view.modelView;
  // J (2x3) rows: (fx / z, 0, -fx x / z^2), (0, fy / z, -fy y / z^2) for a y-up frame.
  const glm::vec3 j0(view.fx / tz, 0.0f, -view.fx * txz / (tz * tz));
  const glm::vec3 j1(0.0f, view.fy / tz, -view.fy * tyz / (tz * tz));
  // Sigma' = J W Sigma W^T J^T, entry by entry: with u = W^T j (a row of J W), Sigma'_kl =
  // u_k^T Sigma u_l (two matrix-vector products, not two matrix products).
  const auto rowOfJW = [&w](const glm::vec3& j) {
    return glm::vec3(w[0][0] * j.x + w[0][1] * j.y - w[0][2] * j.z,
                     w[1][0] * j.x + w[1][1] * j.y - w[1][2] * j.z,
                     w[2][0] * j.x + w[2][1] * j.y - w[2][2] * j.z);
  };
  const glm::vec3 u0 = rowOfJW(j0), u1 = rowOfJW(j1);
  const glm::vec3 su0 = sigma * u0, su1 = sigma * u1;
  const float a = glm::dot(u0, su0) + 0.3f;
  const float b = glm::dot(u0, su1);
  const float c = glm::dot(u1, su1) + 0.3f;
  const float det = a * c - b * b;
  if (!(det > 0.0f) || !std::isfinite(det)) return false;
  const float sharp = (a - 0.3f) * (c - 0.3f) - b * b;
  out.lowPassKeep = std::sqrt(std::clamp(sharp / det, 0.0f, 1.0f));
  out.conic = glm::vec3(c / det, -b / det, a / det);
  const float mid = 0.5f * (a + c);
  const float lambda = mid + std::sqrt(std::max(0.1f, mid * mid - det));
  const float radius = std::ceil(3.0f * std::sqrt(lambda));
  out.extent = glm::vec2(radius);
  out.center = glm::vec2(view.cx + view.fx * tx / tz, view.cy + view.fy * ty / tz);
  out.depth = depth;
  if (!std::isfinite(out.center.x) || !std::isfinite(out.center.y)) return false;
  return out.center.x + radius > 0.0f && out.center.x - radius < static_cast<float>(view.width) &&
         out.center.y + radius > 0.0f && out.center.y - radius < static_cast<float>(view.height);
}

}  // namespace gs::splats
