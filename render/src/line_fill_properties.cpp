// LineProperties and FillProperties of an Appearance (line_fill_properties.hpp).
#include "line_fill_properties.hpp"

#include "scene/node_access.hpp"
#include "surface_programs.hpp"

#include <algorithm>

namespace gs::render::detail {

namespace {

const vrml::Node* propertiesNode(const vrml::Node& appearance, vrml::FieldName field,
                                 vrml::NodeTypeId type) {
  const vrml::FieldValue* f = appearance.field(field);
  if (f == nullptr || f->type() != vrml::FieldType::SFNode) return nullptr;
  const vrml::NodePtr& n = f->get<vrml::FieldType::SFNode>();
  return n && !n->unresolved && n->typeId() == type ? n.get() : nullptr;
}

}  // namespace

LineFillStyle readLineFillStyle(const vrml::Node& appearance) {
  LineFillStyle s;
  if (const vrml::Node* l =
          propertiesNode(appearance, "lineProperties", vrml::NodeTypeId::LineProperties);
      l != nullptr && scene::sfBool(*l, "applied", true)) {
    const int type = scene::sfInt(*l, "linetype", 1);
    s.lineType = type >= 1 && type <= 5 ? type : 1;
    if (type != s.lineType) {
      s.problem = "LineProperties.linetype " + std::to_string(type) +
                  " is not supported: drawn solid (types 1 to 5 are)";
      s.problemNode = l;
    }
    const float scale = scene::sfFloat(*l, "linewidthScaleFactor", 0.0f);
    s.lineWidth = scale > 0.0f ? std::clamp(scale, 1.0f, 64.0f) : 1.0f;
  }
  if (const vrml::Node* p =
          propertiesNode(appearance, "pointProperties", vrml::NodeTypeId::PointProperties)) {
    s.pointScale = std::max(scene::sfFloat(*p, "pointSizeScaleFactor", 1.0f), 0.0f);
    s.pointMin = std::max(scene::sfFloat(*p, "pointSizeMinValue", 1.0f), 0.0f);
    s.pointMax = std::max(scene::sfFloat(*p, "pointSizeMaxValue", 1.0f), s.pointMin);
    s.pointAttenuation = glm::max(scene::sfVec3(*p, "attenuation", glm::vec3(1, 0, 0)), 0.0f);
    if (s.pointAttenuation == glm::vec3(0.0f)) s.pointAttenuation.x = 1.0f;
  }
  if (const vrml::Node* f =
          propertiesNode(appearance, "fillProperties", vrml::NodeTypeId::FillProperties)) {
    s.filled = scene::sfBool(*f, "filled", true);
    if (scene::sfBool(*f, "hatched", true)) {
      const int style = scene::sfInt(*f, "hatchStyle", 1);
      s.hatchStyle = std::clamp(style, 1, 6);
      if (style != s.hatchStyle && s.problem.empty()) {
        s.problem = "FillProperties.hatchStyle " + std::to_string(style) + " is drawn as style " +
                    std::to_string(s.hatchStyle) + " (styles 1 to 6 are supported)";
        s.problemNode = f;
      }
    }
    s.hatchColor = glm::clamp(scene::sfColor(*f, "hatchColor", glm::vec3(1.0f)), 0.0f, 1.0f);
  }
  return s;
}

void LineFillStyle::specialize(SurfaceVariant& v, vrml::Primitive primitive) const {
  v.lineType = primitive == vrml::Primitive::lines ? lineType : 1;
  v.hatchStyle = primitive == vrml::Primitive::triangles ? hatchStyle : 0;
  v.unfilled = primitive == vrml::Primitive::triangles && !filled;
}

void LineFillStyle::setUniforms(const SurfaceUniforms& u, vrml::Primitive primitive) const {
  const bool lines = primitive == vrml::Primitive::lines;
  const bool polygons = primitive == vrml::Primitive::triangles;
  glUniform1i(u.lineType, lines ? lineType : 1);
  glUniform1i(u.hatchStyle, polygons ? hatchStyle : 0);
  glUniform1i(u.filled, polygons && !filled ? 0 : 1);
  if (polygons && hatchStyle != 0)
    glUniform3f(u.hatchColor, hatchColor.r, hatchColor.g, hatchColor.b);
  if (lines) glLineWidth(lineWidth);
  const bool points = primitive == vrml::Primitive::points;
  glUniform1f(u.pointScale, points ? pointScale : 1.0f);
  glUniform2f(u.pointSizeRange, points ? pointMin : 1.0f, points ? pointMax : 1.0f);
  const glm::vec3 a = points ? pointAttenuation : glm::vec3(1.0f, 0.0f, 0.0f);
  glUniform3f(u.pointAttenuation, a.x, a.y, a.z);
}

}  // namespace gs::render::detail
