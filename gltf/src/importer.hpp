// The glTF importer's classes, shared by import.cpp, import_geometry.cpp,
// import_materials.cpp and import_animation.cpp (tinygltf underneath; see gltf/import.hpp).
#pragma once

#include "gltf/import.hpp"

#include "gltf/document.hpp"

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include <array>
#include <map>
#include <set>
#include <string>
#include <vector>

// The importer builds the node model's values throughout: its names are used unqualified.
namespace gs::gltf::x3d {
using namespace gs::vrml;

/// The rotation of unit quaternion `q` (any length but 0; 0 gives no rotation) as VRML's
/// axis and angle, the angle in [0, pi].
Rotation gltfRotation(const glm::dquat& q);

/// The accessor of attribute `name` (POSITION, JOINTS_0, ...) of `p`, -1 without one.
int gltfAttribute(const tinygltf::Primitive& p, const std::string& name);

/// Field `field` of `node` when it is an MFVec3f, else an empty list.
const std::vector<glm::vec3>& mfvec3Field(const Node& node, std::string_view field);

/// Adds ROUTE from.fromField TO to.toField to `scene` (located at `url`).
void addRoute(Scene& scene, const NodePtr& from, const char* fromField, const NodePtr& to,
              const char* toField, const std::string& url);

/// One import: the built nodes, shared where the asset shares (a mesh used by two nodes is
/// one Shape list, USEd twice).
class GltfImporter {
 public:
  GltfImporter(const tinygltf::Model& model, const std::string& url, const ImportOptions& options,
               Scene& scene)
      : m_(model), url_(url), options_(options), scene_(scene) {}
  void run();

  // Node construction (import.cpp).
  NodePtr make(std::string_view type) const;
  static void set(Node& node, std::string_view field, FieldValue value);
  void warn(const std::string& message);

 private:
  // import.cpp: the node hierarchy, cameras, lights.
  NodePtr buildNode(int index, int depth, const glm::dmat4& parentWorld);
  NodePtr camera(int index);
  void light(int index, const glm::dmat4& world);
  void checkExtensions();

  // import_geometry.cpp: meshes and primitives.
  const std::vector<NodePtr>& meshShapes(int mesh);
  /// The Shapes of mesh `mesh` made for node `node` alone (a skinned or morph-animated
  /// node deforms its own copy), remembered in nodePrimitives_.
  std::vector<NodePtr> ownShapes(int node, int mesh);
  /// `weights`: the morph target weights (the node's when it has them, else the mesh's).
  NodePtr primitiveShape(const tinygltf::Primitive& p, const std::vector<double>& weights);

  // import_materials.cpp: materials, textures, samplers.
  NodePtr appearance(int material);
  NodePtr texture(int index);
  /// A sampler's filters and wrap modes as a TextureProperties node.
  NodePtr sampler(const tinygltf::Sampler& s);
  /// The TEXCOORD_n sets the material's textures read: the base colour texture's first (0
  /// without one), then the others' sets in ascending order, each once; at most 2 (a third
  /// is reported as a warning when `report`, and read from the first). `used` gets, per
  /// texture (base colour, metallic-roughness, normal, emissive, occlusion), the set it
  /// reads or -1.
  std::vector<int> texCoordSets(int material, std::array<int, 5>* used = nullptr,
                                bool report = false);
  /// The base colour texture's KHR_texture_transform as a 3x3 UV matrix (identity
  /// without one).
  glm::mat3 uvTransform(int material) const;

  // import_skins.cpp: skins as Skin nodes.
  void skins();

  // import_animation.cpp: animations as TimeSensors, interpolators and ROUTEs.
  void animations();
  /// Nodes whose morph target weights some animation channel drives.
  std::set<int> morphAnimatedNodes() const;
  /// A `weights` channel: per primitive of the node's own Shapes, a CoordinateInterpolator
  /// (and NormalInterpolator) of the morphed vertices at each key, ROUTEd from `sensor`.
  void morphChannel(const NodePtr& sensor, int node, const std::vector<float>& fractions,
                    const std::vector<std::size_t>& sourceKeys, const std::vector<float>& output,
                    std::size_t keyCount, bool cubic, std::vector<NodePtr>& made);

  const tinygltf::Model& m_;
  const std::string& url_;
  const ImportOptions& options_;
  Scene& scene_;
  std::vector<NodePtr> transforms_;  // per glTF node, once built
  std::map<int, std::vector<NodePtr>> meshes_;
  std::map<int, NodePtr> appearances_;
  std::map<int, NodePtr> textures_;
  std::vector<NodePtr> lights_;  // placed at the root, in world coordinates
  std::vector<int> parents_;     // per glTF node: its parent, -1 for none
  std::set<int> ownGeometry_;    // nodes that get their own Shapes (skinned, morph-animated)
  /// Per node in ownGeometry_: (primitive index, Shape) for each primitive drawn.
  std::map<int, std::vector<std::pair<int, NodePtr>>> nodePrimitives_;
  /// The Skin made for a Shape (morph animation of a skinned mesh ROUTEs to it).
  std::map<const Node*, NodePtr> skinOfShape_;
  std::size_t nodesMade_ = 0;
  bool firstCamera_ = true;
  /// A primitive of KHR_gaussian_splatting was met: drawn by one GaussianSplats node.
  bool gaussianSplats_ = false;
};

}  // namespace gs::gltf::x3d
