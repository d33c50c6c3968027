// glTF 2.0 as a world: entry point, node hierarchy, cameras and lights (gltf/import.hpp).
#include "importer.hpp"

#include "base/url.hpp"

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#define GLM_ENABLE_EXPERIMENTAL
#include <glm/gtx/matrix_decompose.hpp>

#include <cmath>
#include <set>

namespace gs::gltf::x3d {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Extensions whose content is read (docs/gltf.md); any other is reported by name.
const std::set<std::string> kReadExtensions = {
    "KHR_lights_punctual",     "KHR_materials_unlit",    "KHR_materials_emissive_strength",
    "KHR_texture_transform",   "KHR_mesh_quantization",  "KHR_draco_mesh_compression",
    "EXT_meshopt_compression", "KHR_gaussian_splatting",
};

Rotation axisAngle(glm::dquat q) {
  const double len = glm::length(q);
  if (!(len > 0.0)) return Rotation(0, 0, 1, 0);
  q /= len;
  if (q.w < 0.0) q = -q;
  const double s = std::sqrt(std::max(0.0, 1.0 - q.w * q.w));
  const double angle = 2.0 * std::acos(std::clamp(q.w, -1.0, 1.0));
  if (s < 1e-9) return Rotation(0, 0, 1, 0);
  return Rotation(static_cast<float>(q.x / s), static_cast<float>(q.y / s),
                  static_cast<float>(q.z / s), static_cast<float>(angle));
}

}  // namespace

Rotation gltfRotation(const glm::dquat& q) {
  return axisAngle(q);
}

int gltfAttribute(const tinygltf::Primitive& p, const std::string& name) {
  const auto it = p.attributes.find(name);
  return it == p.attributes.end() ? -1 : it->second;
}

const std::vector<glm::vec3>& mfvec3Field(const Node& node, std::string_view field) {
  static const std::vector<glm::vec3> none;
  const int i = node.type().findExact(field);
  if (i < 0 || node.fieldAt(static_cast<std::size_t>(i)).type() != FieldType::MFVec3f) return none;
  return node.fieldAt(static_cast<std::size_t>(i)).get<FieldType::MFVec3f>();
}

NodePtr GltfImporter::make(std::string_view type) const {
  auto t = options_.nodeType(type);
  if (!t) throw gltf::Error("internal: no node type " + std::string(type));
  return std::make_shared<Node>(std::move(t));
}

void GltfImporter::set(Node& node, std::string_view field, FieldValue value) {
  const int i = node.type().findExact(field);
  if (i < 0 || node.type().fields[static_cast<std::size_t>(i)].type != value.type())
    throw gltf::Error("internal: " + node.typeName() + " has no field " + std::string(field) +
                      " of that type");
  node.fieldAt(static_cast<std::size_t>(i)) = std::move(value);
}

void GltfImporter::warn(const std::string& message) {
  scene_.diagnostics.warning({url_, 0, 0}, message);
}

void GltfImporter::checkExtensions() {
  for (const std::string& e : m_.extensionsRequired)
    if (!kReadExtensions.count(e))
      gltf::fail(url_, "the asset requires extension " + e + ", which is not supported");
  for (const std::string& e : m_.extensionsUsed)
    if (!kReadExtensions.count(e))
      warn("glTF extension " + e + " is not supported; the asset is drawn without it");
}

void GltfImporter::run() {
  checkExtensions();
  const std::vector<int> roots = gltf::sceneRoots(m_);
  transforms_.assign(m_.nodes.size(), nullptr);
  parents_.assign(m_.nodes.size(), -1);
  for (std::size_t i = 0; i < m_.nodes.size(); ++i)
    for (int c : m_.nodes[i].children)
      if (c >= 0 && static_cast<std::size_t>(c) < m_.nodes.size() &&
          parents_[static_cast<std::size_t>(c)] < 0)
        parents_[static_cast<std::size_t>(c)] = static_cast<int>(i);
  ownGeometry_ = morphAnimatedNodes();
  for (std::size_t i = 0; i < m_.nodes.size(); ++i)
    if (m_.nodes[i].skin >= 0 || !m_.nodes[i].weights.empty())
      ownGeometry_.insert(static_cast<int>(i));
  std::vector<NodePtr> built;
  for (int r : roots) built.push_back(buildNode(r, 0, glm::dmat4(1.0)));
  // Lights light the whole scene (glTF's lights are not scoped): at the root, placed by
  // their node's world transform when the asset was read.
  for (NodePtr& l : lights_) built.insert(built.begin(), l);
  // KHR_gaussian_splatting primitives: one GaussianSplats node naming the asset itself,
  // whose reader (splats::readGltfGaussians) places every splat primitive of the default
  // scene by its node's world transform and turns it to a capture's axes; turned back
  // here (docs/gltf.md, "Gaussian splats").
  if (gaussianSplats_) {
    NodePtr splats = make("GaussianSplats");
    // The asset's own name (its last path segment, with any query), which resolves to
    // itself against its URL; the whole URL would not for a relative path with folders.
    const std::size_t slash = url_.find_last_of('/', url_.find_first_of("?#"));
    const std::string self = slash == std::string::npos ? url_ : url_.substr(slash + 1);
    set(*splats, "url", FieldValue::make<FieldType::MFString>(std::vector<std::string>{self}));
    NodePtr turn = make("Transform");
    set(*turn, "rotation",
        FieldValue::make<FieldType::SFRotation>(
            Rotation(0.0f, 0.0f, 1.0f, static_cast<float>(kPi))));
    set(*turn, "children", FieldValue::make<FieldType::MFNode>(std::vector<NodePtr>{splats}));
    built.push_back(turn);
  }
  for (NodePtr& n : built) {
    scene_.rootNodes.push_back(n);
    if (options_.onRootNode) options_.onRootNode(n);
  }
  skins();
  animations();
}

NodePtr GltfImporter::buildNode(int index, int depth, const glm::dmat4& parentWorld) {
  if (index < 0 || static_cast<std::size_t>(index) >= m_.nodes.size())
    gltf::fail(url_, "node " + std::to_string(index) + " does not exist");
  if (depth > options_.maxNesting)
    gltf::fail(url_, "nodes nested deeper than " + std::to_string(options_.maxNesting) +
                         " (ParseLimits::maxNesting)");
  if (transforms_[static_cast<std::size_t>(index)])
    gltf::fail(url_, "node " + std::to_string(index) + " is reached twice (not a tree)");
  if (++nodesMade_ > options_.maxNodes)
    gltf::fail(url_, "more than " + std::to_string(options_.maxNodes) + " nodes");
  const tinygltf::Node& n = m_.nodes[static_cast<std::size_t>(index)];
  const std::string where = "node " + std::to_string(index) + ": ";
  NodePtr t = make("Transform");
  transforms_[static_cast<std::size_t>(index)] = t;
  glm::dvec3 translation(0.0), scale(1.0);
  glm::dquat rotation(1.0, 0.0, 0.0, 0.0);
  if (!n.matrix.empty()) {
    if (n.matrix.size() != 16) gltf::fail(url_, where + "a matrix needs 16 numbers");
    const glm::dmat4 m = glm::make_mat4(n.matrix.data());  // both column-major
    glm::dvec3 skew;
    glm::dvec4 perspective;
    if (!glm::decompose(m, scale, rotation, translation, skew, perspective)) {
      warn(where + "its matrix cannot be decomposed into translation, rotation and scale");
      scale = glm::dvec3(1.0);
      rotation = glm::dquat(1.0, 0.0, 0.0, 0.0);
    }
  } else {
    if (!n.translation.empty()) {
      if (n.translation.size() != 3) gltf::fail(url_, where + "a translation needs 3 numbers");
      translation = glm::dvec3(n.translation[0], n.translation[1], n.translation[2]);
    }
    if (!n.rotation.empty()) {
      if (n.rotation.size() != 4) gltf::fail(url_, where + "a rotation needs 4 numbers");
      rotation = glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
    }
    if (!n.scale.empty()) {
      if (n.scale.size() != 3) gltf::fail(url_, where + "a scale needs 3 numbers");
      scale = glm::dvec3(n.scale[0], n.scale[1], n.scale[2]);
    }
  }
  set(*t, "translation", FieldValue::make<FieldType::SFVec3f>(glm::vec3(translation)));
  set(*t, "rotation", FieldValue::make<FieldType::SFRotation>(axisAngle(rotation)));
  set(*t, "scale", FieldValue::make<FieldType::SFVec3f>(glm::vec3(scale)));
  if (!n.name.empty()) {
    t->defName = n.name;
    scene_.x3d.exports.push_back(X3dExport{n.name, n.name, t, {url_, 0, 0}});
  }
  const double qlen = glm::length(rotation);
  const glm::dquat unit = qlen > 0.0 ? rotation / qlen : glm::dquat(1.0, 0.0, 0.0, 0.0);
  const glm::dmat4 world = parentWorld * glm::translate(glm::dmat4(1.0), translation) *
                           glm::mat4_cast(unit) * glm::scale(glm::dmat4(1.0), scale);

  std::vector<NodePtr> children;
  if (n.mesh >= 0) {
    const std::vector<NodePtr> shapes =
        ownGeometry_.count(index) ? ownShapes(index, n.mesh) : meshShapes(n.mesh);
    children.insert(children.end(), shapes.begin(), shapes.end());
  }
  if (n.camera >= 0)
    if (NodePtr c = camera(n.camera)) children.push_back(c);
  if (const auto it = n.extensions.find("KHR_lights_punctual"); it != n.extensions.end())
    if (it->second.Has("light") && it->second.Get("light").IsInt())
      light(it->second.Get("light").GetNumberAsInt(), world);
  for (int c : n.children) children.push_back(buildNode(c, depth + 1, world));
  set(*t, "children", FieldValue::make<FieldType::MFNode>(std::move(children)));
  return t;
}

NodePtr GltfImporter::camera(int index) {
  if (index < 0 || static_cast<std::size_t>(index) >= m_.cameras.size()) {
    warn("camera " + std::to_string(index) + " does not exist");
    return nullptr;
  }
  const tinygltf::Camera& c = m_.cameras[static_cast<std::size_t>(index)];
  NodePtr v;
  if (c.type == "orthographic") {
    v = make("OrthoViewpoint");
    const auto x = static_cast<float>(c.orthographic.xmag);
    const auto y = static_cast<float>(c.orthographic.ymag);
    set(*v, "fieldOfView", FieldValue::make<FieldType::MFFloat>(std::vector<float>{-x, -y, x, y}));
  } else {
    v = make("Viewpoint");
    const double yfov =
        c.perspective.yfov > 0.0 && c.perspective.yfov < kPi ? c.perspective.yfov : kPi / 4.0;
    set(*v, "fieldOfView", FieldValue::make<FieldType::SFFloat>(static_cast<float>(yfov)));
  }
  set(*v, "position", FieldValue::make<FieldType::SFVec3f>(glm::vec3(0.0f)));
  set(*v, "description",
      FieldValue::make<FieldType::SFString>(c.name.empty() ? "camera " + std::to_string(index)
                                                           : c.name));
  return v;
}

void GltfImporter::light(int index, const glm::dmat4& world) {
  const auto it = m_.extensions.find("KHR_lights_punctual");
  if (it == m_.extensions.end() || !it->second.Has("lights")) return;
  const tinygltf::Value& all = it->second.Get("lights");
  if (index < 0 || !all.IsArray() || static_cast<std::size_t>(index) >= all.ArrayLen()) {
    warn("KHR_lights_punctual light " + std::to_string(index) + " does not exist");
    return;
  }
  const tinygltf::Value& l = all.Get(index);
  auto number = [&](const tinygltf::Value& o, const char* key, double fallback) {
    return o.Has(key) && o.Get(key).IsNumber() ? o.Get(key).GetNumberAsDouble() : fallback;
  };
  const std::string type =
      l.Has("type") && l.Get("type").IsString() ? l.Get("type").Get<std::string>() : "";
  glm::vec3 color(1.0f);
  if (l.Has("color") && l.Get("color").IsArray() && l.Get("color").ArrayLen() == 3)
    for (int k = 0; k < 3; ++k)
      color[k] = static_cast<float>(
          l.Get("color").Get(k).IsNumber() ? l.Get("color").Get(k).GetNumberAsDouble() : 1.0);
  NodePtr light;
  if (type == "directional") {
    light = make("DirectionalLight");
  } else if (type == "point") {
    light = make("PointLight");
  } else if (type == "spot") {
    light = make("SpotLight");
    double outer = kPi / 4.0, inner = 0.0;
    if (l.Has("spot")) {
      outer = number(l.Get("spot"), "outerConeAngle", outer);
      inner = number(l.Get("spot"), "innerConeAngle", inner);
    }
    set(*light, "cutOffAngle", FieldValue::make<FieldType::SFFloat>(static_cast<float>(outer)));
    set(*light, "beamWidth", FieldValue::make<FieldType::SFFloat>(static_cast<float>(inner)));
  } else {
    warn("KHR_lights_punctual light " + std::to_string(index) + " has unknown type '" + type + "'");
    return;
  }
  set(*light, "color", FieldValue::make<FieldType::SFColor>(glm::clamp(color, 0.0f, 1.0f)));
  set(*light, "intensity",
      FieldValue::make<FieldType::SFFloat>(
          static_cast<float>(std::max(0.0, number(l, "intensity", 1.0)))));
  // glTF lights shine along -Z of their node, from its origin, falling off with the square
  // of the distance within `range` (infinite when absent).
  const glm::vec3 origin(world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
  glm::vec3 direction(world * glm::dvec4(0.0, 0.0, -1.0, 0.0));
  direction = glm::length(direction) > 0.0f ? glm::normalize(direction) : glm::vec3(0, 0, -1);
  if (type != "point") set(*light, "direction", FieldValue::make<FieldType::SFVec3f>(direction));
  if (type != "directional") {
    set(*light, "location", FieldValue::make<FieldType::SFVec3f>(origin));
    set(*light, "attenuation", FieldValue::make<FieldType::SFVec3f>(glm::vec3(0.0f, 0.0f, 1.0f)));
    const double range = number(l, "range", 0.0);
    set(*light, "radius",
        FieldValue::make<FieldType::SFFloat>(range > 0.0 ? static_cast<float>(range) : 1e30f));
  }
  if (const int g = light->type().findExact("global"); g >= 0)
    light->fieldAt(static_cast<std::size_t>(g)) = FieldValue::make<FieldType::SFBool>(true);
  lights_.push_back(std::move(light));
}

}  // namespace gs::gltf::x3d

namespace gs::gltf {

bool isGltf(std::string_view bytes) {
  return gltf::isGlb(bytes) || gltf::looksLikeGltfJson(bytes);
}

void importGltf(std::string_view bytes, const std::string& url, const ImportOptions& options,
                vrml::Scene& scene) {
  scene.x3d.encoding = "glTF";
  const gltf::BufferLoader loader = [&](const std::string& uri) -> std::optional<std::string> {
    // tinygltf gives the uri decoded: a URL names it encoded again (a space as %20).
    const std::string reference =
        base::hasScheme(url) && !base::hasScheme(uri) ? base::percentEncodePath(uri) : uri;
    base::Fetched got = base::fetcherOr(options.fetcher)
                            .fetch(base::resolveUrl(url, reference), url, base::FetchMode::whole);
    if (got.state == base::FetchState::refused) throw gltf::Error(url + ": " + got.error);
    if (!got.ready()) return std::nullopt;
    return std::move(got.bytes);
  };
  try {
    std::vector<std::string> warnings;
    const tinygltf::Model model =
        gltf::load(bytes, url, loader, gltf::Images::keepEncoded, &warnings);
    for (const std::string& w : warnings) scene.diagnostics.warning({url, 0, 0}, "tinygltf: " + w);
    x3d::GltfImporter(model, url, options, scene).run();
  } catch (const gltf::Error& e) {
    scene.diagnostics.error({url, 0, 0}, e.what());
  }
}

}  // namespace gs::gltf
