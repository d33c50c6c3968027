// Bounds-checked reads of glTF 2.0 accessors (glTF 2.0 clause 3.6 "Buffers, buffer views
// and accessors", 3.6.2.3 sparse accessors, 3.11 normalized integers).
#pragma once

#include "gltf/document.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace gs::gltf {

/// One accessor's elements in its buffer view, bounds checked when made; element i,
/// component c is at at(i, c). Sparse substitutions are not applied here (readFloats).
struct AccessorView {
  const unsigned char* data = nullptr;  // null when count is 0 or there is no bufferView
  std::size_t count = 0;                // elements
  std::size_t stride = 0;               // bytes between elements
  int componentType = 0;                // TINYGLTF_COMPONENT_TYPE_*
  int components = 0;                   // 1 (SCALAR) .. 16 (MAT4)
  bool normalized = false;

  /// First byte of component c of element i (i < count, c < components).
  const char* at(std::size_t i, int c) const;
  /// Component c of element i as a float: floats as stored; normalized integers mapped to
  /// [0, 1] or [-1, 1] (clause 3.11); other integers converted.
  float value(std::size_t i, int c) const;
  /// Component 0 of element i as an unsigned index (u8, u16 or u32 accessors).
  std::uint32_t index(std::size_t i) const;
};

/// The view of accessor `index`; `what` names its use in messages ("POSITION accessor 3
/// runs past the end of its buffer view"). A sparse accessor is an Error unless
/// `allowSparse` (its view then holds the base values; data is null without a bufferView).
/// Throws Error "name: ..." for a missing accessor, buffer view or buffer, an invalid
/// type, a stride smaller than an element, or elements past the end of the view.
AccessorView accessorView(const tinygltf::Model& model, int index, const std::string& name,
                          const char* what, bool allowSparse = false);

/// Accessor `index` as floats, `components` per element (it must have exactly that many,
/// else Error), with normalized integers converted and sparse substitutions applied
/// (sparse indices out of range are an Error). At most `maxElements` elements (Error
/// beyond: a small file cannot make a huge allocation through a large count).
std::vector<float> readFloats(const tinygltf::Model& model, int index, int components,
                              const std::string& name, const char* what,
                              std::size_t maxElements = std::size_t{1} << 27);

/// Accessor `index` as indices (u8, u16 or u32 SCALAR, else Error), each below
/// `vertexCount` (else Error naming the index), at most `maxElements`.
std::vector<std::uint32_t> readIndices(const tinygltf::Model& model, int index,
                                       std::size_t vertexCount, const std::string& name,
                                       std::size_t maxElements = std::size_t{1} << 28);

}  // namespace gs::gltf
