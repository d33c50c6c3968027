// EXT_meshopt_compression (Khronos extension registry, vendor extension EXT): buffer views
// whose bytes are stored compressed by meshoptimizer's vertex and index codecs, decoded
// with Debian's libmeshoptimizer into the view's "fallback" buffer after tinygltf parsed
// the document.
#include "compression.hpp"

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <string>
#include <vector>

namespace gs::gltf::detail {

namespace {

constexpr std::string_view kExtension = "EXT_meshopt_compression";
constexpr std::string_view kFallbackUri = "gs-meshopt-fallback:";
/// Decompressed bytes of all fallback buffers of one asset at most (512 MiB).
constexpr std::uint64_t kMaxFallbackBytes = std::uint64_t{512} << 20;

/// The integer member `key` of `v`, or `fallback` when absent; -1 when not an integer.
long long intMember(const tinygltf::Value& v, const char* key, long long fallback) {
  if (!v.Has(key)) return fallback;
  const tinygltf::Value& m = v.Get(key);
  if (m.IsInt()) return m.GetNumberAsInt();
  if (m.IsNumber()) {
    const double d = m.GetNumberAsDouble();
    return d >= 0 && d < 9e15 && d == static_cast<double>(static_cast<long long>(d))
               ? static_cast<long long>(d)
               : -1;
  }
  return -1;
}

std::string stringMember(const tinygltf::Value& v, const char* key, const char* fallback) {
  if (!v.Has(key) || !v.Get(key).IsString()) return fallback;
  return v.Get(key).Get<std::string>();
}

void decodeView(tinygltf::Model& m, std::size_t index, const tinygltf::Value& ext,
                const std::string& name) {
  const std::string prefix =
      std::string(kExtension) + " of bufferView " + std::to_string(index) + ": ";
  const tinygltf::BufferView& view = m.bufferViews[index];
  const long long source = intMember(ext, "buffer", -1);
  const long long offset = intMember(ext, "byteOffset", 0);
  const long long length = intMember(ext, "byteLength", -1);
  const long long stride = intMember(ext, "byteStride", -1);
  const long long count = intMember(ext, "count", -1);
  const std::string mode = stringMember(ext, "mode", "");
  const std::string filter = stringMember(ext, "filter", "NONE");
  if (source < 0 || static_cast<std::size_t>(source) >= m.buffers.size())
    fail(name, prefix + "no buffer " + std::to_string(source));
  const std::vector<unsigned char>& in = m.buffers[static_cast<std::size_t>(source)].data;
  if (offset < 0 || length < 0 || static_cast<std::uint64_t>(offset) > in.size() ||
      static_cast<std::uint64_t>(length) > in.size() - static_cast<std::uint64_t>(offset))
    fail(name, prefix + "compressed bytes outside buffer " + std::to_string(source));
  if (stride <= 0 || stride > 256 || count < 0 || count > (1ll << 28))
    fail(name, prefix + "byteStride " + std::to_string(stride) + " or count " +
                   std::to_string(count) + " out of range");
  const std::uint64_t bytes =
      static_cast<std::uint64_t>(count) * static_cast<std::uint64_t>(stride);
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= m.buffers.size())
    fail(name, prefix + "no fallback buffer");
  std::vector<unsigned char>& out = m.buffers[static_cast<std::size_t>(view.buffer)].data;
  if (bytes > view.byteLength || view.byteOffset > out.size() ||
      view.byteLength > out.size() - view.byteOffset)
    fail(name, prefix + std::to_string(bytes) + " decoded bytes do not fit the view");
  const auto* src = in.data() + offset;
  const auto n = static_cast<std::size_t>(count), s = static_cast<std::size_t>(stride);
  std::vector<unsigned char> decoded(static_cast<std::size_t>(bytes));
  int rc = -1;
  if (mode == "ATTRIBUTES") {
    if (s % 4 != 0) fail(name, prefix + "ATTRIBUTES need a byteStride divisible by 4");
    rc = meshopt_decodeVertexBuffer(decoded.data(), n, s, src, static_cast<std::size_t>(length));
  } else if (mode == "TRIANGLES" || mode == "INDICES") {
    if (s != 2 && s != 4) fail(name, prefix + mode + " need a byteStride of 2 or 4");
    if (mode == "TRIANGLES" && n % 3 != 0)
      fail(name, prefix + "TRIANGLES need a count divisible by 3");
    rc = mode == "TRIANGLES" ? meshopt_decodeIndexBuffer(decoded.data(), n, s, src,
                                                         static_cast<std::size_t>(length))
                             : meshopt_decodeIndexSequence(decoded.data(), n, s, src,
                                                           static_cast<std::size_t>(length));
  } else {
    fail(name, prefix + "unknown mode '" + mode + "'");
  }
  if (rc != 0)
    fail(name,
         prefix + "the " + mode + " stream is damaged (meshopt error " + std::to_string(rc) + ")");
  if (filter == "OCTAHEDRAL") {
    if (mode != "ATTRIBUTES" || (s != 4 && s != 8))
      fail(name, prefix + "OCTAHEDRAL needs byteStride 4 or 8");
    meshopt_decodeFilterOct(decoded.data(), n, s);
  } else if (filter == "QUATERNION") {
    if (mode != "ATTRIBUTES" || s != 8) fail(name, prefix + "QUATERNION needs byteStride 8");
    meshopt_decodeFilterQuat(decoded.data(), n, s);
  } else if (filter == "EXPONENTIAL") {
    if (mode != "ATTRIBUTES") fail(name, prefix + "EXPONENTIAL needs ATTRIBUTES");
    meshopt_decodeFilterExp(decoded.data(), n, s);
  } else if (filter != "NONE") {
    fail(name, prefix + "unknown filter '" + filter + "'");
  }
  if (!decoded.empty()) std::memcpy(out.data() + view.byteOffset, decoded.data(), decoded.size());
}

}  // namespace

std::string placeMeshoptFallbacks(std::string_view json) {
  if (json.find(kExtension) == std::string_view::npos) return {};
  nlohmann::json doc = nlohmann::json::parse(json, nullptr, /*allow_exceptions=*/false);
  if (!doc.is_object() || !doc.contains("buffers") || !doc["buffers"].is_array()) return {};
  bool changed = false;
  std::uint64_t total = 0;
  for (nlohmann::json& b : doc["buffers"]) {
    if (!b.is_object() || b.contains("uri") || !b.contains("extensions") ||
        !b["extensions"].is_object())
      continue;
    const auto ext = b["extensions"].find(std::string(kExtension));
    if (ext == b["extensions"].end() || !ext->is_object() || !ext->contains("fallback") ||
        !(*ext)["fallback"].is_boolean() || !(*ext)["fallback"].get<bool>() ||
        !b.contains("byteLength") || !b["byteLength"].is_number_unsigned())
      continue;
    const std::uint64_t length = b["byteLength"].get<std::uint64_t>();
    total += length;
    if (total > kMaxFallbackBytes) return {};  // tinygltf then reports the buffer missing
    b["uri"] = std::string(kFallbackUri) + std::to_string(length);
    changed = true;
  }
  return changed ? doc.dump() : std::string();
}

std::size_t maxMeshoptFallbackBytes() {
  return static_cast<std::size_t>(kMaxFallbackBytes);
}

std::optional<std::size_t> meshoptFallbackBytes(std::string_view uri) {
  if (!uri.starts_with(kFallbackUri)) return std::nullopt;
  const std::string_view digits = uri.substr(kFallbackUri.size());
  if (digits.empty() || digits.size() > 10) return std::nullopt;
  std::uint64_t n = 0;
  for (char c : digits) {
    if (c < '0' || c > '9') return std::nullopt;
    n = n * 10 + static_cast<std::uint64_t>(c - '0');
  }
  if (n > kMaxFallbackBytes) return std::nullopt;
  return static_cast<std::size_t>(n);
}

void decodeMeshopt(tinygltf::Model& m, const std::string& name) {
  for (std::size_t i = 0; i < m.bufferViews.size(); ++i) {
    const auto it = m.bufferViews[i].extensions.find(std::string(kExtension));
    if (it == m.bufferViews[i].extensions.end()) continue;
    decodeView(m, i, it->second, name);
    m.bufferViews[i].extensions.erase(it);  // decoded: the view's bytes are plain now
  }
}

}  // namespace gs::gltf::detail
