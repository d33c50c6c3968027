// Bounds-checked accessor reads: see accessors.hpp.
#include "gltf/accessors.hpp"

#include "base/byte_order.hpp"

#include <algorithm>

namespace gs::gltf {
namespace {

using base::loadFloatLe;
using base::loadLe;

std::string accessorName(const char* what, int index) {
  return std::string(what) + " accessor " + std::to_string(index);
}

// A view of `count` elements of `elem` bytes at `offset` in buffer view `viewIndex`.
const unsigned char* checkedRange(const tinygltf::Model& m, int viewIndex, std::size_t offset,
                                  std::size_t count, std::size_t elem, std::size_t& stride,
                                  bool useViewStride, const std::string& name,
                                  const std::string& where) {
  if (viewIndex < 0 || static_cast<std::size_t>(viewIndex) >= m.bufferViews.size())
    fail(name, where + " has no valid bufferView");
  const tinygltf::BufferView& bv = m.bufferViews[static_cast<std::size_t>(viewIndex)];
  if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= m.buffers.size())
    fail(name, where + ": its buffer view has no valid buffer");
  const std::vector<unsigned char>& buf = m.buffers[static_cast<std::size_t>(bv.buffer)].data;
  stride = useViewStride && bv.byteStride ? bv.byteStride : elem;
  if (stride < elem) fail(name, where + ": byteStride is smaller than an element");
  if (bv.byteOffset > buf.size() || bv.byteLength > buf.size() - bv.byteOffset)
    fail(name, where + ": its buffer view runs past the end of its buffer");
  if (count == 0) return nullptr;
  if (offset > bv.byteLength || elem > bv.byteLength - offset ||
      count - 1 > (bv.byteLength - offset - elem) / stride)
    fail(name, where + " runs past the end of its buffer view");
  return buf.data() + bv.byteOffset + offset;
}

}  // namespace

const char* AccessorView::at(std::size_t i, int c) const {
  return reinterpret_cast<const char*>(data + i * stride) +
         c * tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(componentType));
}

float AccessorView::value(std::size_t i, int c) const {
  const char* p = at(i, c);
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const auto v = static_cast<std::int8_t>(*p);
      return normalized ? std::max(static_cast<float>(v) / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const auto v = static_cast<std::uint8_t>(*p);
      return normalized ? static_cast<float>(v) / 255.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const auto v = static_cast<std::int16_t>(loadLe<std::uint16_t>(p));
      return normalized ? std::max(static_cast<float>(v) / 32767.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const auto v = loadLe<std::uint16_t>(p);
      return normalized ? static_cast<float>(v) / 65535.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return static_cast<float>(loadLe<std::uint32_t>(p));
    default:
      return loadFloatLe(p);
  }
}

std::uint32_t AccessorView::index(std::size_t i) const {
  const char* p = at(i, 0);
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return static_cast<std::uint8_t>(*p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return loadLe<std::uint16_t>(p);
    default:
      return loadLe<std::uint32_t>(p);
  }
}

AccessorView accessorView(const tinygltf::Model& m, int index, const std::string& name,
                          const char* what, bool allowSparse) {
  const std::string where = accessorName(what, index);
  if (index < 0 || static_cast<std::size_t>(index) >= m.accessors.size())
    fail(name, where + " does not exist");
  const tinygltf::Accessor& a = m.accessors[static_cast<std::size_t>(index)];
  if (a.sparse.isSparse && !allowSparse) fail(name, where + " is sparse, which is not supported");
  const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
  const int comps = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
  if (size <= 0 || comps <= 0) fail(name, where + " has an invalid type");
  const std::size_t elem = static_cast<std::size_t>(size) * static_cast<std::size_t>(comps);
  AccessorView v{nullptr, a.count, elem, a.componentType, comps, a.normalized};
  if (a.bufferView < 0 && a.sparse.isSparse) return v;  // all zeros before substitution
  v.data = checkedRange(m, a.bufferView, a.byteOffset, a.count, elem, v.stride, true, name, where);
  return v;
}

std::vector<float> readFloats(const tinygltf::Model& m, int index, int components,
                              const std::string& name, const char* what, std::size_t maxElements) {
  const AccessorView v = accessorView(m, index, name, what, true);
  const std::string where = accessorName(what, index);
  if (v.components != components)
    fail(name, where + " has " + std::to_string(v.components) + " components, expected " +
                   std::to_string(components));
  if (v.count > maxElements)
    fail(name, where + " has " + std::to_string(v.count) + " elements, more than " +
                   std::to_string(maxElements));
  const auto n = static_cast<std::size_t>(components);
  std::vector<float> out(v.count * n, 0.0f);
  if (v.data != nullptr)
    for (std::size_t i = 0; i < v.count; ++i)
      for (int c = 0; c < components; ++c) out[i * n + static_cast<std::size_t>(c)] = v.value(i, c);
  const tinygltf::Accessor& a = m.accessors[static_cast<std::size_t>(index)];
  if (!a.sparse.isSparse) return out;
  // Sparse substitutions (clause 3.6.2.3): `count` indices and as many values.
  const auto count = static_cast<std::size_t>(std::max(a.sparse.count, 0));
  if (count > v.count) fail(name, where + ": more sparse values than elements");
  const int it = a.sparse.indices.componentType;
  if (it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    fail(name, where + ": sparse indices are not u8/u16/u32");
  AccessorView indices{nullptr, count, 0, it, 1, false};
  indices.data = checkedRange(
      m, a.sparse.indices.bufferView, a.sparse.indices.byteOffset, count,
      static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(it))),
      indices.stride, false, name, where + " sparse indices");
  // Sparse values are tightly packed elements of the accessor's type.
  const std::size_t elemBytes = n * static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(
                                        static_cast<std::uint32_t>(a.componentType)));
  AccessorView values{nullptr, count, 0, a.componentType, components, a.normalized};
  values.data = checkedRange(m, a.sparse.values.bufferView, a.sparse.values.byteOffset, count,
                             elemBytes, values.stride, false, name, where + " sparse values");
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t target = indices.index(k);
    if (target >= v.count)
      fail(name, where + ": sparse index " + std::to_string(target) + " is out of range");
    for (int c = 0; c < components; ++c)
      out[target * n + static_cast<std::size_t>(c)] = values.value(k, c);
  }
  return out;
}

std::vector<std::uint32_t> readIndices(const tinygltf::Model& m, int index, std::size_t vertexCount,
                                       const std::string& name, std::size_t maxElements) {
  const AccessorView idx = accessorView(m, index, name, "indices");
  const int t = idx.componentType;
  if (idx.components != 1 ||
      (t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
       t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    fail(name, "indices accessor " + std::to_string(index) + " is not u8/u16/u32 SCALAR");
  if (idx.count > maxElements)
    fail(name, "indices accessor " + std::to_string(index) + " has more than " +
                   std::to_string(maxElements) + " elements");
  std::vector<std::uint32_t> list;
  list.reserve(idx.count);
  for (std::size_t i = 0; i < idx.count; ++i) {
    const std::uint32_t v = idx.index(i);
    if (v >= vertexCount)
      fail(name, "index " + std::to_string(v) + " in accessor " + std::to_string(index) +
                     " is out of range (" + std::to_string(vertexCount) + " vertices)");
    list.push_back(v);
  }
  return list;
}

}  // namespace gs::gltf
