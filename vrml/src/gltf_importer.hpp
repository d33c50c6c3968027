// The glTF importer's classes, shared by gltf_import.cpp, gltf_geometry.cpp,
// gltf_materials.cpp and gltf_animation.cpp (tinygltf underneath; see gltf_import.hpp).
#pragma once

#include "gltf_import.hpp"

#include "gltf/document.hpp"

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include <map>
#include <string>
#include <vector>

namespace gs::vrml::parsing {

/// The rotation of unit quaternion `q` (any length but 0; 0 gives no rotation) as VRML's
/// axis and angle, the angle in [0, pi].
Rotation gltfRotation(const glm::dquat& q);

/// One import: the built nodes, shared where the asset shares (a mesh used by two nodes is
/// one Shape list, USEd twice).
class GltfImporter {
 public:
  GltfImporter(const tinygltf::Model& model, const std::string& url, const ParseOptions& options,
               Scene& scene)
      : m_(model), url_(url), options_(options), scene_(scene) {}
  void run();

  // Node construction (gltf_import.cpp).
  static NodePtr make(std::string_view type);
  static void set(Node& node, std::string_view field, FieldValue value);
  void warn(const std::string& message);

 private:
  // gltf_import.cpp: the node hierarchy, cameras, lights.
  NodePtr buildNode(int index, int depth, const glm::dmat4& parentWorld);
  NodePtr camera(int index);
  void light(int index, const glm::dmat4& world);
  void checkExtensions();

  // gltf_geometry.cpp: meshes and primitives.
  const std::vector<NodePtr>& meshShapes(int mesh);
  NodePtr primitiveShape(const tinygltf::Mesh& mesh, const tinygltf::Primitive& p);

  // gltf_materials.cpp: materials, textures, samplers.
  NodePtr appearance(int material);
  NodePtr texture(int index);
  /// The TEXCOORD_n set the base colour texture reads (0 without one).
  int baseTexCoord(int material) const;
  /// The base colour texture's KHR_texture_transform as a 3x3 UV matrix (identity
  /// without one).
  glm::mat3 uvTransform(int material) const;

  // gltf_animation.cpp: animations as TimeSensors, interpolators and ROUTEs.
  void animations();

  const tinygltf::Model& m_;
  const std::string& url_;
  const ParseOptions& options_;
  Scene& scene_;
  std::vector<NodePtr> transforms_;  // per glTF node, once built
  std::map<int, std::vector<NodePtr>> meshes_;
  std::map<int, NodePtr> appearances_;
  std::map<int, NodePtr> textures_;
  std::vector<NodePtr> lights_;  // placed at the root, in world coordinates
  std::size_t nodesMade_ = 0;
  bool firstCamera_ = true;
};

}  // namespace gs::vrml::parsing
