// X3D vertex attributes (X3D 4.0 clause 31.4): the FloatVertexAttribute,
// Matrix3VertexAttribute and Matrix4VertexAttribute nodes of a geometry's `attrib` field,
// expanded onto the mesh's vertices through Mesh::pointIndices (value i belongs to
// coordinate point i, as clause 31.2.2 and the composed geometry nodes index them).
#include "geometry_internal.hpp"

#include <algorithm>
#include <cstring>
#include <string>

namespace gs::vrml::geometry_detail {

bool hasVertexAttributes(const Node& geometry) {
  const FieldValue* f = geometry.field("attrib");
  if (f == nullptr || f->type() != FieldType::MFNode) return false;
  const std::vector<NodePtr>& nodes = f->get<FieldType::MFNode>();
  return std::any_of(nodes.begin(), nodes.end(),
                     [](const NodePtr& n) { return n && !n->unresolved; });
}

namespace {

/// Copies `per` floats of point `p` from `src` (floats, `per` a point) into `out`, or
/// zeros when the array has no such point; returns false then.
bool copyPoint(const float* src, std::size_t count, std::size_t per, std::size_t p, float* out) {
  if ((p + 1) * per > count) {
    std::fill(out, out + per, 0.0f);
    return false;
  }
  std::memcpy(out, src + p * per, per * sizeof(float));
  return true;
}

/// The floats of `matrices` row by row (the order the file wrote them), into `out`.
template <typename Matrix>
void rowsInFileOrder(const std::vector<Matrix>& matrices, std::vector<float>& out) {
  out.clear();
  for (const Matrix& m : matrices) {
    const Matrix rows = glm::transpose(m);
    out.insert(out.end(), &rows[0][0], &rows[0][0] + Matrix::length() * Matrix::length());
  }
}

}  // namespace

void assignVertexAttributes(const Node& geometry, Mesh& m, ProblemLog& log) {
  if (m.pointIndices.empty() || m.pointIndices.size() != m.positions.size()) return;
  const std::size_t n = m.positions.size();
  std::vector<float> fileOrder;  // a matrix attribute's values, row by row
  for (const NodePtr& node : fieldOr<FieldType::MFNode>(geometry, "attrib")) {
    if (!node || node->unresolved) continue;
    VertexAttribute a;
    a.name = fieldOr<FieldType::SFString>(*node, "name");
    const float* src = nullptr;
    std::size_t count = 0;
    switch (node->typeId()) {
      case NodeTypeId::FloatVertexAttribute: {
        const std::int32_t c = node->get<FieldType::SFInt32>("numComponents", 4);
        if (c < 1 || c > 4) {
          log.add("FloatVertexAttribute \"" + a.name + "\": numComponents " + std::to_string(c) +
                  " is not 1 to 4; the attribute is not passed");
          continue;
        }
        a.components = c;
        const std::vector<float>& v = fieldOr<FieldType::MFFloat>(*node, "value");
        src = v.data();
        count = v.size();
        break;
      }
      // A matrix's floats in file order (its rows one after another), which a shader's
      // matN reads as its columns, as X_ITE passes them (create3000's
      // Shaders/Matrix3VertexAttribute.x3d).
      case NodeTypeId::Matrix3VertexAttribute:
        a.components = 9;
        rowsInFileOrder(fieldOr<FieldType::MFMatrix3f>(*node, "value"), fileOrder);
        src = fileOrder.data();
        count = fileOrder.size();
        break;
      case NodeTypeId::Matrix4VertexAttribute:
        a.components = 16;
        rowsInFileOrder(fieldOr<FieldType::MFMatrix4f>(*node, "value"), fileOrder);
        src = fileOrder.data();
        count = fileOrder.size();
        break;
      default:
        continue;  // not a vertex attribute node (the parser reported it)
    }
    if (a.name.empty()) {
      log.add(node->typeName() + " has no name; the attribute is not passed");
      continue;
    }
    const auto per = static_cast<std::size_t>(a.components);
    a.values.resize(n * per);
    std::size_t missing = 0;
    std::uint32_t firstMissing = 0;
    for (std::size_t v = 0; v < n; ++v) {
      const std::uint32_t p = m.pointIndices[v];
      if (!copyPoint(src, count, per, p, a.values.data() + v * per) && missing++ == 0)
        firstMissing = p;
    }
    if (missing > 0)
      log.add(node->typeName() + " \"" + a.name + "\" has no value for point " +
              std::to_string(firstMissing) + " (" + std::to_string(count / per) +
              " values); 0 is used");
    m.attributes.push_back(std::move(a));
  }
}

}  // namespace gs::vrml::geometry_detail
