// X3D NURBS swept and swung surfaces (ISO/IEC 19775-1 X3D 4.0 clauses 27.4.11, 27.4.12) as
// X_ITE 15 draws them: an Extrusion (clause 6.19) without caps, smooth (creaseAngle pi),
// whose crossSection is the 2D curve (crossSectionCurve, profileCurve) and whose spine is
// the trajectory: NurbsSweptSurface's 3D NurbsCurve, NurbsSwungSurface's 2D curve laid in
// the XZ plane ((x, y) -> (x, 0, y)). The 2D curves are NurbsCurve2D (tessellated as
// NurbsCurve is) or ContourPolyline2D (its points); ccw and solid are the surface's.
#include "geometry/nurbs.hpp"
#include "geometry_internal.hpp"

#include <numbers>

namespace gs::vrml::geometry_detail {

std::vector<glm::dvec2> nurbsCurve2DPoints(const NodePtr& node, ProblemLog& log) {
  if (!node) return {};
  const FieldValue* f = node->field("controlPoint");
  if (f == nullptr || f->type() != FieldType::MFVec2d) return {};
  const auto& given = f->get<FieldType::MFVec2d>();
  if (node->typeId() == NodeTypeId::ContourPolyline2D)
    return std::vector<glm::dvec2>(given.begin(), given.end());
  if (node->typeId() != NodeTypeId::NurbsCurve2D) return {};
  std::vector<glm::dvec3> points;
  points.reserve(given.size());
  for (const glm::dvec2& p : given) points.emplace_back(p.x, p.y, 0.0);
  std::vector<glm::dvec2> out;
  for (const glm::dvec3& p : nurbsCurvePoints(*node, points, log)) out.emplace_back(p.x, p.y);
  return out;
}

namespace {

Mesh sweep(const Node& node, const std::vector<glm::dvec2>& section,
           const std::vector<glm::dvec3>& trajectory, ProblemLog& log) {
  if (section.size() < 2 || trajectory.size() < 2) return {};
  std::vector<glm::vec2> crossSection(section.begin(), section.end());
  std::vector<glm::vec3> spine(trajectory.begin(), trajectory.end());
  static const std::vector<glm::vec2> kScale = {{1, 1}};
  static const std::vector<Rotation> kOrientation = {{0, 0, 1, 0}};
  ExtrusionInput in;
  in.spine = spine;
  in.crossSection = crossSection;
  in.scale = kScale;
  in.orientation = kOrientation;
  in.beginCap = in.endCap = false;
  return extrude(
      in,
      [&](std::span<const glm::vec3> points) {
        PolygonSoup soup;
        soup.points = points;
        soup.ccw = node.get<FieldType::SFBool>("ccw", true);
        soup.solid = node.get<FieldType::SFBool>("solid", true);
        soup.convex = true;
        soup.creaseAngle = std::numbers::pi_v<float>;
        return soup;
      },
      log);
}

}  // namespace

Mesh tessellateNurbsSweptSurface(const Node& node, ProblemLog& log) {
  const NodePtr& trajectory = node.sfnode("trajectoryCurve");
  if (!trajectory || trajectory->typeId() != NodeTypeId::NurbsCurve) return {};
  return sweep(node, nurbsCurve2DPoints(node.sfnode("crossSectionCurve"), log),
               nurbsCurvePoints(*trajectory, nurbs::controlPoints(*trajectory), log), log);
}

Mesh tessellateNurbsSwungSurface(const Node& node, ProblemLog& log) {
  std::vector<glm::dvec3> trajectory;
  for (const glm::dvec2& p : nurbsCurve2DPoints(node.sfnode("trajectoryCurve"), log))
    trajectory.emplace_back(p.x, 0.0, p.y);
  return sweep(node, nurbsCurve2DPoints(node.sfnode("profileCurve"), log), trajectory, log);
}

}  // namespace gs::vrml::geometry_detail
