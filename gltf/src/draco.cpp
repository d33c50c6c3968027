// KHR_draco_mesh_compression (Khronos glTF extension registry): a primitive's indices and
// attributes held as one Draco-compressed buffer view, decoded with Debian's libdraco into
// new buffers that the primitive's accessors then point at, so every reader downstream sees
// plain accessors. Every index and range the extension names is checked first (tinygltf's
// own TINYGLTF_ENABLE_DRACO path indexes the model unchecked, so it is not used).
#include "compression.hpp"

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <nlohmann/json.hpp>

#include <cstring>

namespace gs::gltf::detail {
namespace {

/// Most points or faces one decoded primitive may have (each point then costs at most 16
/// bytes per attribute): a bound on what a small compressed stream can make us allocate.
constexpr std::size_t kMaxDracoElements = std::size_t{1} << 26;

template <class T>
T& at(std::vector<T>& v, int index, const std::string& name, const char* what) {
  if (index < 0 || static_cast<std::size_t>(index) >= v.size())
    fail(name, std::string("KHR_draco_mesh_compression: ") + what + " " + std::to_string(index) +
                   " does not exist");
  return v[static_cast<std::size_t>(index)];
}

void decodePrimitive(tinygltf::Model& m, tinygltf::Primitive& p, const tinygltf::Value& ext,
                     const std::string& name) {
  if (!ext.IsObject() || !ext.Has("bufferView") || !ext.Get("bufferView").IsInt() ||
      !ext.Has("attributes") || !ext.Get("attributes").IsObject())
    fail(name, "KHR_draco_mesh_compression needs a bufferView and an attributes object");
  const tinygltf::BufferView& view =
      at(m.bufferViews, ext.Get("bufferView").GetNumberAsInt(), name, "bufferView");
  const tinygltf::Buffer& buffer = at(m.buffers, view.buffer, name, "buffer");
  if (view.byteOffset > buffer.data.size() ||
      view.byteLength > buffer.data.size() - view.byteOffset)
    fail(name, "KHR_draco_mesh_compression: its bufferView runs past the end of its buffer");
  draco::DecoderBuffer in;
  in.Init(reinterpret_cast<const char*>(buffer.data.data() + view.byteOffset), view.byteLength);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&in);
  if (!decoded.ok())
    fail(name, "KHR_draco_mesh_compression: Draco cannot decode the mesh (" +
                   decoded.status().error_msg_string() + ")");
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  const std::size_t points = mesh->num_points();
  const std::size_t faces = mesh->num_faces();
  if (points > kMaxDracoElements || faces > kMaxDracoElements)
    fail(name, "KHR_draco_mesh_compression: more than 2^26 points or faces");

  if (p.indices >= 0) {
    tinygltf::Accessor& a = at(m.accessors, p.indices, name, "indices accessor");
    std::vector<std::uint32_t> indices(3 * faces);
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = mesh->face(f)[k].value();
        if (v >= points) fail(name, "KHR_draco_mesh_compression: a face names a missing point");
        indices[3 * f.value() + static_cast<std::size_t>(k)] = v;
      }
    replaceAccessorData(m, a, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, indices.size(), indices.data(),
                        indices.size() * sizeof(std::uint32_t));
  }
  const tinygltf::Value& attributes = ext.Get("attributes");
  for (const std::string& key : attributes.Keys()) {
    const tinygltf::Value& id = attributes.Get(key);
    const auto own = p.attributes.find(key);
    if (!id.IsInt() || own == p.attributes.end()) continue;  // nothing reads it
    tinygltf::Accessor& a = at(m.accessors, own->second, name, "attribute accessor");
    const draco::PointAttribute* source =
        id.GetNumberAsInt() < 0
            ? nullptr
            : mesh->GetAttributeByUniqueId(static_cast<std::uint32_t>(id.GetNumberAsInt()));
    if (source == nullptr)
      fail(name, "KHR_draco_mesh_compression: the Draco mesh has no attribute " +
                     std::to_string(id.GetNumberAsInt()) + " (" + key + ")");
    const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
    if (components < 1 || components > 4)
      fail(name, "KHR_draco_mesh_compression: attribute " + key + " is not SCALAR or VEC2-4");
    // As floats (normalized integers become [0, 1] or [-1, 1], as glTF reads them).
    std::vector<float> values(points * static_cast<std::size_t>(components));
    for (draco::PointIndex i(0); i < mesh->num_points(); ++i)
      if (!source->ConvertValue<float>(
              source->mapped_index(i), static_cast<std::int8_t>(components),
              values.data() + i.value() * static_cast<std::size_t>(components)))
        fail(name, "KHR_draco_mesh_compression: attribute " + key + " cannot be converted");
    replaceAccessorData(m, a, TINYGLTF_COMPONENT_TYPE_FLOAT, points, values.data(),
                        values.size() * sizeof(float));
  }
}

}  // namespace

std::string placeDracoAccessors(std::string_view json) {
  if (json.find("KHR_draco_mesh_compression") == std::string_view::npos) return {};
  nlohmann::json doc = nlohmann::json::parse(json, nullptr, /*allow_exceptions=*/false);
  if (!doc.is_object() || !doc.contains("meshes") || !doc["meshes"].is_array() ||
      !doc.contains("accessors") || !doc["accessors"].is_array())
    return {};  // tinygltf reports what is wrong
  nlohmann::json& accessors = doc["accessors"];
  bool changed = false;
  auto place = [&](const nlohmann::json& index, const nlohmann::json& view) {
    if (!index.is_number_integer() || index.get<long long>() < 0 ||
        index.get<std::size_t>() >= accessors.size())
      return;
    nlohmann::json& a = accessors[index.get<std::size_t>()];
    if (a.is_object() && !a.contains("bufferView")) {
      a["bufferView"] = view;
      changed = true;
    }
  };
  for (const nlohmann::json& mesh : doc["meshes"]) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
      continue;
    for (const nlohmann::json& p : mesh["primitives"]) {
      if (!p.is_object() || !p.contains("extensions") || !p["extensions"].is_object()) continue;
      const auto ext = p["extensions"].find("KHR_draco_mesh_compression");
      if (ext == p["extensions"].end() || !ext->is_object() || !ext->contains("bufferView"))
        continue;
      const nlohmann::json& view = (*ext)["bufferView"];
      if (p.contains("indices")) place(p["indices"], view);
      if (p.contains("attributes") && p["attributes"].is_object())
        for (const auto& [name, index] : p["attributes"].items()) place(index, view);
    }
  }
  return changed ? doc.dump() : std::string();
}

void decodeDraco(tinygltf::Model& m, const std::string& name) {
  for (tinygltf::Mesh& mesh : m.meshes)
    for (tinygltf::Primitive& p : mesh.primitives)
      if (const auto it = p.extensions.find("KHR_draco_mesh_compression");
          it != p.extensions.end()) {
        decodePrimitive(m, p, it->second, name);
        p.extensions.erase(it);  // decoded: the accessors hold the data now
      }
}

}  // namespace gs::gltf::detail
