// writeOutlineWorld: a world flattened, cut into outline groups (outline_encoder.hpp)
// and written back as VRML97 text, outlines first (paper section 1.1).
#include "outline/outline_world.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

#include "qnv/error.hpp"
#include "scene/traversal.hpp"

namespace gs::outline {

namespace {

/// Text output with VRML97 number formatting.
class Writer {
 public:
  std::string text;

  Writer& operator<<(std::string_view s) {
    text.append(s);
    return *this;
  }
  /// Shortest text that reads back to the same float.
  Writer& num(float v) {
    if (!std::isfinite(v)) v = 0.0f;
    if (v == 0.0f) v = 0.0f;  // no "-0"
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    text.append(buf, r.ptr);
    return *this;
  }
  Writer& num(std::int64_t v) {
    text.append(std::to_string(v));
    return *this;
  }
  Writer& vec(const glm::vec3& v) {
    num(v.x) << " ";
    num(v.y) << " ";
    return num(v.z);
  }
  /// A unit vector with `digits` significant digits (enough for shading, smaller files).
  Writer& unit(const glm::vec3& v, int digits = 5) {
    for (int i = 0; i < 3; ++i) {
      float c = std::isfinite(v[i]) ? v[i] : 0.0f;
      if (c == 0.0f) c = 0.0f;
      char buf[32];
      const auto r = std::to_chars(buf, buf + sizeof buf, c, std::chars_format::general, digits);
      if (i) text.push_back(' ');
      text.append(buf, r.ptr);
    }
    return *this;
  }
  Writer& str(const std::string& s) {
    text.push_back('"');
    for (char c : s) {
      if (c == '"' || c == '\\') text.push_back('\\');
      text.push_back(c);
    }
    text.push_back('"');
    return *this;
  }
  /// `name [ v, v, ... ]` over 3-vectors, a few per line.
  void vectors(std::string_view name, const std::vector<glm::vec3>& v, std::string_view indent,
               bool units = false) {
    *this << name << " [";
    for (std::size_t i = 0; i < v.size(); ++i) {
      *this << (i % 6 == 0 ? "\n" : " ");
      if (i % 6 == 0) *this << indent;
      if (units)
        unit(v[i]);
      else
        vec(v[i]);
      if (i + 1 < v.size()) *this << ",";
    }
    *this << " ]";
  }
  void floats(std::string_view name, const std::vector<float>& v) {
    *this << name << " [";
    for (std::size_t i = 0; i < v.size(); ++i) {
      *this << (i ? ", " : " ");
      num(v[i]);
    }
    *this << " ]";
  }
};

/// The Appearance of a Shape as text, without DEF: the key of its appearance class.
/// `color`, when given, is a Color node's colour: it replaces diffuseColor (clause 4.14:
/// lit colour = Color), or is an emissive colour for an unlit Shape.
std::string appearanceText(const vrml::Node* appearance, const glm::vec3* color = nullptr) {
  Writer w;
  w << "Appearance {";
  const vrml::NodePtr m = appearance ? appearance->sfnode("material") : nullptr;
  if (!(m && !m->unresolved && m->typeId() == vrml::NodeTypeId::Material) && color) {
    w << " material Material { diffuseColor 0 0 0 emissiveColor ";
    w.vec(*color) << " }";
  } else if (m && !m->unresolved && m->typeId() == vrml::NodeTypeId::Material) {
    using vrml::FieldType;
    w << " material Material { diffuseColor ";
    w.vec(color ? *color : m->get<FieldType::SFColor>("diffuseColor", glm::vec3(0.8f)))
        << " specularColor ";
    w.vec(m->get<FieldType::SFColor>("specularColor", glm::vec3(0.0f))) << " emissiveColor ";
    w.vec(m->get<FieldType::SFColor>("emissiveColor", glm::vec3(0.0f))) << " ambientIntensity ";
    w.num(m->get<FieldType::SFFloat>("ambientIntensity", 0.2f)) << " shininess ";
    w.num(m->get<FieldType::SFFloat>("shininess", 0.2f)) << " transparency ";
    w.num(m->get<FieldType::SFFloat>("transparency", 0.0f)) << " }";
  }
  w << " }";
  return std::move(w.text);
}

struct Flattened {
  PolygonSoup soup;
  std::vector<std::string> appearances;  // by appearance index
  std::vector<bool> solid;               // per material id
};

/// Material id = appearance index * 2 + solid.
Flattened flatten(scene::SceneTraversal& traversal, const scene::TraversalFrame& frame) {
  Flattened f;
  std::map<std::string, std::uint32_t> appearanceIndex;
  for (const scene::ShapeInstance& shape : frame.shapes) {
    const vrml::Mesh& mesh = traversal.mesh(*shape.geometry);
    if (mesh.primitive != vrml::Primitive::triangles || mesh.indices.empty()) continue;
    auto materialOf = [&](const glm::vec3* color) {
      std::string key = appearanceText(shape.appearance, color);
      const auto [it, inserted] = appearanceIndex.try_emplace(
          std::move(key), static_cast<std::uint32_t>(f.appearances.size()));
      if (inserted) f.appearances.push_back(it->first);
      return it->second * 2 + (mesh.solid ? 1u : 0u);
    };
    const bool colored = mesh.colors.size() == mesh.positions.size();
    const std::uint32_t material = colored ? 0u : materialOf(nullptr);
    const auto base = static_cast<std::uint32_t>(f.soup.positions.size());
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(shape.model)));
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      f.soup.positions.push_back(glm::vec3(shape.model * glm::vec4(mesh.positions[i], 1.0f)));
      glm::vec3 n = i < mesh.normals.size() ? normalMatrix * mesh.normals[i] : glm::vec3(0.0f);
      const float len = glm::length(n);
      f.soup.normals.push_back(len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0.0f));
    }
    // A mirroring transform turns counter-clockwise into clockwise: swap to keep fronts.
    const bool mirrored = glm::determinant(glm::mat3(shape.model)) < 0.0f;
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
      f.soup.indices.push_back(base + mesh.indices[i]);
      f.soup.indices.push_back(base + mesh.indices[mirrored ? i + 2 : i + 1]);
      f.soup.indices.push_back(base + mesh.indices[mirrored ? i + 1 : i + 2]);
      if (colored) {  // the triangle's mean Color (per-vertex shading is lost)
        const glm::vec3 c =
            (glm::vec3(mesh.colors[mesh.indices[i]]) + glm::vec3(mesh.colors[mesh.indices[i + 1]]) +
             glm::vec3(mesh.colors[mesh.indices[i + 2]])) /
            3.0f;
        f.soup.material.push_back(materialOf(&c));
      } else {
        f.soup.material.push_back(material);
      }
    }
  }
  f.solid.resize(2 * f.appearances.size());
  for (std::size_t i = 0; i < f.solid.size(); ++i) f.solid[i] = (i % 2) == 1;
  return f;
}

/// True when the group's vertex normals differ from its flat face normals (the source
/// was smooth-shaded): then they are written, else the browser's flat normals match.
bool needsNormals(const PolygonGroup& g) {
  if (g.normals.size() != g.positions.size()) return false;
  for (std::size_t i = 0; i + 2 < g.indices.size(); i += 3) {
    const glm::vec3 &a = g.positions[g.indices[i]], &b = g.positions[g.indices[i + 1]],
                    &c = g.positions[g.indices[i + 2]];
    const glm::vec3 n = glm::cross(b - a, c - a);
    const float len = glm::length(n);
    if (!(len > 0.0f)) continue;
    for (std::size_t k = 0; k < 3; ++k)
      if (glm::dot(g.normals[g.indices[i + k]], n / len) < 0.9999f) return true;
  }
  return false;
}

void writeBindables(Writer& w, const scene::SceneTraversal& t, const scene::TraversalFrame& frame) {
  if (t.navigation().node) {
    const scene::NavigationSettings& n = t.navigation();
    w << "NavigationInfo { type [";
    for (const std::string& s : n.type) w.str(s) << " ";
    w << "] headlight " << (n.headlight ? "TRUE" : "FALSE") << " speed ";
    w.num(n.speed) << " ";
    w.floats("avatarSize", n.avatarSize);
    w << " visibilityLimit ";
    w.num(n.visibilityLimit) << " }\n";
  }
  if (t.background().node) {
    const scene::BackgroundSettings& b = t.background();
    w << "Background {\n  ";
    w.vectors("skyColor", b.skyColor, "    ");
    w << "\n  ";
    w.floats("skyAngle", b.skyAngle);
    w << "\n  ";
    w.vectors("groundColor", b.groundColor, "    ");
    w << "\n  ";
    w.floats("groundAngle", b.groundAngle);
    w << "\n}\n";
  }
  if (t.fog().node) {
    const scene::FogSettings& fog = t.fog();
    w << "Fog { color ";
    w.vec(fog.color) << " fogType " << (fog.exponential ? "\"EXPONENTIAL\"" : "\"LINEAR\"")
                     << " visibilityRange ";
    w.num(fog.visibilityRange) << " }\n";
  }
  for (const scene::ViewpointInfo& v : t.viewpoints()) {
    const glm::quat q = glm::normalize(v.camera.orientation);
    const float angle = 2.0f * std::acos(std::clamp(q.w, -1.0f, 1.0f));
    const float s = std::sqrt(std::max(0.0f, 1.0f - q.w * q.w));
    const glm::vec3 axis = s > 1e-6f ? glm::vec3(q.x, q.y, q.z) / s : glm::vec3(0, 0, 1);
    w << "Viewpoint { position ";
    w.vec(v.camera.position) << " orientation ";
    w.vec(axis) << " ";
    w.num(s > 1e-6f ? angle : 0.0f) << " fieldOfView ";
    w.num(v.camera.fieldOfView) << " description ";
    w.str(v.description) << " }\n";
  }
  for (const scene::LightInstance& l : frame.lights) {
    const char* type = l.type == scene::LightType::directional ? "DirectionalLight"
                       : l.type == scene::LightType::point     ? "PointLight"
                                                               : "SpotLight";
    w << type << " { color ";
    w.vec(l.color) << " intensity ";
    w.num(l.intensity) << " ambientIntensity ";
    w.num(l.ambientIntensity);
    if (l.type != scene::LightType::point) {
      w << " direction ";
      w.vec(l.direction);
    }
    if (l.type != scene::LightType::directional) {
      w << " location ";
      w.vec(l.location) << " attenuation ";
      w.vec(l.attenuation) << " radius ";
      w.num(l.radius);
    }
    if (l.type == scene::LightType::spot) {
      w << " beamWidth ";
      w.num(l.beamWidth) << " cutOffAngle ";
      w.num(l.cutOffAngle);
    }
    w << " }\n";
  }
}

}  // namespace

std::string writeOutlineWorld(std::shared_ptr<const vrml::Scene> scene,
                              const OutlineOptions& options, OutlineWorldSummary* summary) {
  const std::string url = scene->url;
  scene::SceneTraversal traversal(std::move(scene));
  scene::TraversalFrame frame;
  traversal.collect(traversal.boundViewpointCamera(), frame);
  const Flattened flat = flatten(traversal, frame);
  OutlineSummary os;
  const std::vector<PolygonGroup> groups = encodeOutlineGroups(flat.soup, options, &os);

  OutlineWorldSummary sum;
  sum.groups = groups.size();
  sum.droppedTriangles = os.droppedTriangles;
  sum.triangles = os.triangles - os.droppedTriangles;
  sum.outlineVertices = os.outlineVertices;
  sum.appearances = flat.appearances.size();

  Writer w;
  w << "#VRML V2.0 utf8\n# Outline groups (GhostSpace OutlineGroup extension, "
       "docs/vrml-extensions.md) of ";
  w << (url.empty() ? std::string("a world") : url) << ": " << std::to_string(sum.groups)
    << " groups, " << std::to_string(sum.triangles) << " triangles. All outlines come first,\n"
    << "# then the polygons of each group, largest group first (Nagasawa, Beyond VRML, 1.1).\n";
  writeBindables(w, traversal, frame);

  std::vector<bool> defined(flat.appearances.size(), false);
  auto appearance = [&](std::uint32_t material) {
    const std::uint32_t a = material / 2;
    const std::string name = "A" + std::to_string(a);
    if (defined[a]) return "USE " + name;
    defined[a] = true;
    return "DEF " + name + " " + flat.appearances[a];
  };
  for (std::size_t k = 0; k < groups.size(); ++k) {
    const PolygonGroup& g = groups[k];
    w << "OutlineGroup { groupId " << std::to_string(k) << " appearance " << appearance(g.material)
      << "\n  ";
    w.vectors("outline", g.outline, "    ");
    if (g.outlineLengths.size() > 1) {
      w << "\n  outlineLengths [";
      for (std::uint32_t n : g.outlineLengths) w << " " << std::to_string(n);
      w << " ]";
    }
    w << "\n}\n";
  }
  sum.outlineBytes = w.text.size();
  for (std::size_t k = 0; k < groups.size(); ++k) {
    const PolygonGroup& g = groups[k];
    const bool solid = g.material < flat.solid.size() && flat.solid[g.material];
    w << "OutlineGroup { groupId " << std::to_string(k) << " children [ Shape { appearance "
      << appearance(g.material) << "\n  geometry IndexedFaceSet { solid "
      << (solid ? "TRUE" : "FALSE") << "\n    coord Coordinate { ";
    w.vectors("point", g.positions, "      ");
    w << " }\n";
    if (needsNormals(g)) {
      // The source's shading normals. One normal shared by the whole group (a flat face
      // whose triangles disagree in winding) is written once with an index per face;
      // otherwise one per vertex, to 3 significant digits (shading needs no more).
      const glm::vec3 first = g.normals.front();
      const bool shared = std::all_of(g.normals.begin(), g.normals.end(), [&](const glm::vec3& n) {
        return glm::dot(n, first) >= 0.99999f;
      });
      w << "    normal Normal { vector [ ";
      if (shared) {
        w.unit(first, 3);
        w << " ] }\n    normalPerVertex FALSE normalIndex [";
        for (std::size_t i = 0; i < g.indices.size(); i += 3)
          w << ((i / 3) % 32 == 0 ? "\n      0" : " 0");
        w << " ]\n";
      } else {
        for (std::size_t i = 0; i < g.normals.size(); ++i) {
          w << (i % 8 == 0 ? "\n      " : ", ");
          w.unit(g.normals[i], 3);
        }
        w << " ] }\n";
      }
    }
    w << "    coordIndex [";
    for (std::size_t i = 0; i < g.indices.size(); i += 3) {
      w << ((i / 3) % 8 == 0 ? "\n      " : " ");
      w << std::to_string(g.indices[i]) << " " << std::to_string(g.indices[i + 1]) << " "
        << std::to_string(g.indices[i + 2]) << " -1";
    }
    w << " ]\n  } } ] }\n";
  }
  sum.bytes = w.text.size();
  if (summary) *summary = sum;
  return std::move(w.text);
}

}  // namespace gs::outline
