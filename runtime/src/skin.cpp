// Skinned meshes (the GhostSpace Skin extension node, docs/vrml-extensions.md; glTF 2.0
// clause 3.8 "Skins"): after each cascade, every Skin whose skeleton moved writes its
// Coordinate's `point` (and its Normal's `vector`) as the weighted sum of its joints'
// matrices applied to the rest pose:
//   jointMatrix_j = inverse(M_skinnedTransform) * M_joint_j * inverseBindMatrix_j
//   point_v       = (sum_k weight_vk * jointMatrix_{joint_vk}) * restPoint_v
// where M_x is node x's matrix relative to the skeleton roots (a factor common to all of
// them cancels). Normals use the same matrix's upper 3x3, renormalized.
#include "execution_state.hpp"

#include "vrml/transform.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <unordered_map>

namespace gs::runtime {

using vrml::FieldType;

namespace {

/// Limits of one skeleton walk: hostile or cyclic graphs end early (the skin then uses
/// identity for what the walk did not reach).
constexpr std::size_t kMaxSkeletonNodes = 65536;
constexpr int kMaxSkeletonDepth = 256;

int fieldIndex(const vrml::Node& node, std::string_view name, FieldType type) {
  const int i = node.type().findExact(name);
  if (i < 0 || node.type().fields[static_cast<std::size_t>(i)].type != type) return -1;
  return i;
}

/// Field `index` of `node` (found by fieldIndex, so of type T), or an empty value of T.
template <FieldType T>
const auto& fieldOr(const vrml::Node& node, int index) {
  static const vrml::FieldValue empty(T);
  return (index < 0 ? empty : node.fieldAt(static_cast<std::size_t>(index))).template get<T>();
}

std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
  h ^= v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
  return h;
}

/// Every grouping node under `roots` with its matrix relative to them (the first path to
/// a node wins) into `matrices` (cleared first), and a signature of their revisions: equal
/// signatures, same matrices. `stack` is scratch space.
std::uint64_t walkSkeleton(const std::vector<vrml::NodePtr>& roots,
                           std::unordered_map<const vrml::Node*, glm::mat4>& matrices,
                           std::vector<SkeletonItem>& stack) {
  std::uint64_t signature = 0;
  matrices.clear();
  stack.clear();
  for (auto r = roots.rbegin(); r != roots.rend(); ++r)
    if (*r) stack.push_back({r->get(), glm::mat4(1.0f), 0});
  while (!stack.empty() && matrices.size() < kMaxSkeletonNodes) {
    const SkeletonItem item = stack.back();
    stack.pop_back();
    const vrml::Node& n = *item.node;
    // (H-Anim's joints and sites place children without being X3DGroupingNodes.)
    if (!n.type().is(vrml::AbstractType::X3DGroupingNode) && !vrml::placesChildren(n.type().id()))
      continue;
    const glm::mat4 m =
        vrml::placesChildren(n.type().id()) ? item.parent * vrml::transformMatrix(n) : item.parent;
    if (!matrices.emplace(&n, m).second) continue;
    signature = mix(mix(signature, reinterpret_cast<std::uintptr_t>(&n)), n.revision());
    if (item.depth >= kMaxSkeletonDepth) continue;
    const std::vector<vrml::NodePtr>& kids = n.mfnode("children");
    for (auto c = kids.rbegin(); c != kids.rend(); ++c)
      if (*c) stack.push_back({c->get(), m, item.depth + 1});
  }
  return signature;
}

}  // namespace

bool ExecutionModel::State::classifySkin(NodeState& ns) {
  const vrml::Node& n = *ns.node;
  if (n.type().id() != vrml::NodeTypeId::Skin) return false;
  ns.skin = std::make_unique<SkinState>();
  SkinState& st = *ns.skin;
  st.skeleton = fieldIndex(n, "skeleton", FieldType::MFNode);
  st.joints = fieldIndex(n, "joints", FieldType::MFNode);
  st.inverseBindMatrices = fieldIndex(n, "inverseBindMatrices", FieldType::MFFloat);
  st.skinnedTransform = fieldIndex(n, "skinnedTransform", FieldType::SFNode);
  st.coord = fieldIndex(n, "coord", FieldType::SFNode);
  st.normal = fieldIndex(n, "normal", FieldType::SFNode);
  st.restPoint = fieldIndex(n, "restPoint", FieldType::MFVec3f);
  st.restNormal = fieldIndex(n, "restNormal", FieldType::MFVec3f);
  st.vertexJoints = fieldIndex(n, "vertexJoints", FieldType::MFInt32);
  st.vertexWeights = fieldIndex(n, "vertexWeights", FieldType::MFFloat);
  skins.push_back(&ns);
  return true;
}

void ExecutionModel::State::evaluateSkins() {
  for (NodeState* s : skins) {
    if (s->skin->humanoid)
      evaluateHumanoid(*s);
    else
      evaluateSkin(*s);
  }
}

void ExecutionModel::State::evaluateSkin(NodeState& ns) {
  const vrml::Node& skin = *ns.node;
  SkinState& st = *ns.skin;
  const std::vector<vrml::NodePtr>& roots = fieldOr<FieldType::MFNode>(skin, st.skeleton);
  const std::uint64_t signature = mix(walkSkeleton(roots, st.matrices, st.stack), skin.revision());
  if (st.evaluated && signature == st.signature) return;
  st.evaluated = true;
  st.signature = signature;

  const std::vector<vrml::NodePtr>& joints = fieldOr<FieldType::MFNode>(skin, st.joints);
  const auto& ibm = fieldOr<FieldType::MFFloat>(skin, st.inverseBindMatrices);
  const auto& rest = fieldOr<FieldType::MFVec3f>(skin, st.restPoint);
  const auto& restNormal = fieldOr<FieldType::MFVec3f>(skin, st.restNormal);
  const auto& vj = fieldOr<FieldType::MFInt32>(skin, st.vertexJoints);
  const auto& vw = fieldOr<FieldType::MFFloat>(skin, st.vertexWeights);
  const vrml::NodePtr& mesh = fieldOr<FieldType::SFNode>(skin, st.skinnedTransform);
  const vrml::NodePtr& coord = fieldOr<FieldType::SFNode>(skin, st.coord);
  const vrml::NodePtr& normal = fieldOr<FieldType::SFNode>(skin, st.normal);
  const int point = coord ? fieldIndex(*coord, "point", FieldType::MFVec3f) : -1;
  const int vector = normal ? fieldIndex(*normal, "vector", FieldType::MFVec3f) : -1;
  const std::size_t count = rest.size();
  const std::size_t per = count == 0 ? 0 : vj.size() / count;
  if (point < 0 || count == 0 || per == 0 || per * count != vj.size() || vw.size() != vj.size() ||
      (vector >= 0 && restNormal.size() != count)) {
    if (!st.problemReported)
      report(vrml::Severity::error, skin,
             "needs a Coordinate, restPoint, and vertexJoints and vertexWeights of the same "
             "whole multiple of restPoint's count (and restNormal as many as restPoint with a "
             "Normal); the mesh stays as it is");
    st.problemReported = true;
    return;
  }

  auto matrixOf = [&](const vrml::NodePtr& n) {
    const auto it = n ? st.matrices.find(n.get()) : st.matrices.end();
    return it == st.matrices.end() ? glm::mat4(1.0f) : it->second;
  };
  const glm::mat4 toMesh = glm::inverse(matrixOf(mesh));
  std::vector<glm::mat4>& jointMatrix = st.jointMatrices;
  jointMatrix.resize(joints.size());
  for (std::size_t j = 0; j < joints.size(); ++j) {
    glm::mat4 inverseBind(1.0f);
    if (16 * (j + 1) <= ibm.size()) inverseBind = glm::make_mat4(ibm.data() + 16 * j);
    jointMatrix[j] = toMesh * matrixOf(joints[j]) * inverseBind;
  }

  // Written in place (the change contract: markChanged after a write through fieldAt).
  // Neither target is a field of the Skin, so the rest pose read here stays as it was.
  auto& points = coord->fieldAt(static_cast<std::size_t>(point)).get<FieldType::MFVec3f>();
  points.resize(count);
  std::vector<glm::vec3>* normals =
      vector >= 0 ? &normal->fieldAt(static_cast<std::size_t>(vector)).get<FieldType::MFVec3f>()
                  : nullptr;
  if (normals != nullptr) normals->resize(count);
  for (std::size_t v = 0; v < count; ++v) {
    glm::mat4 m(0.0f);
    float total = 0.0f;
    for (std::size_t k = v * per; k < (v + 1) * per; ++k) {
      const std::int32_t j = vj[k];
      const float w = vw[k];
      if (!(w != 0.0f) || j < 0 || static_cast<std::size_t>(j) >= jointMatrix.size()) continue;
      m += w * jointMatrix[static_cast<std::size_t>(j)];
      total += w;
    }
    if (!(total > 0.0f)) m = glm::mat4(1.0f);  // no influence: the rest pose
    points[v] = glm::vec3(m * glm::vec4(rest[v], 1.0f));
    if (normals != nullptr) {
      const glm::vec3 n = glm::mat3(m) * restNormal[v];
      const float len = glm::length(n);
      (*normals)[v] = len > 0.0f ? n / len : restNormal[v];
    }
  }
  coord->markChanged();
  if (normals != nullptr) normal->markChanged();
}

// ---- H-Anim (X3D 4.0 clause 26) ----
//
// An HAnimHumanoid's skin is deformed by its joints: each joint j moves the skinCoord points
// its skinCoordIndex lists, by its skinCoordWeight, with the matrix that takes the bind
// pose (the skeleton as first seen) to the pose now:
//   M_j     = matrix_j(now) * inverse(matrix_j(bind))
//   point_v = sum_j w_vj * M_j * bind_v + (1 - sum_j w_vj) * bind_v
// where matrix_j is joint j's matrix relative to the humanoid (its skeleton's roots); a
// weight missing from skinCoordWeight is 1. skinNormal's vectors turn with the upper 3x3.
// The joints' HAnimDisplacers then move the points they list (26.4.2, as X_ITE 15 does):
//   point_v += sum over displacers d of joint j: mat3(M_j) displacement_dv weight_d

bool ExecutionModel::State::classifyHumanoid(NodeState& ns) {
  const vrml::Node& n = *ns.node;
  if (n.type().id() != vrml::NodeTypeId::HAnimHumanoid) return false;
  ns.skin = std::make_unique<SkinState>();
  SkinState& st = *ns.skin;
  st.humanoid = true;
  st.skeleton = fieldIndex(n, "skeleton", FieldType::MFNode);
  st.joints = fieldIndex(n, "joints", FieldType::MFNode);
  st.skinCoord = fieldIndex(n, "skinCoord", FieldType::SFNode);
  st.skinNormal = fieldIndex(n, "skinNormal", FieldType::SFNode);
  skins.push_back(&ns);
  return true;
}

namespace {

/// The HAnimDisplacers of `owner` (a joint or segment) added to `out` (one entry per point
/// of a coord of `count` points), each displacement turned by `turn` and times its weight.
void addDisplacements(const vrml::Node& owner, const glm::mat3& turn, std::vector<glm::vec3>& out) {
  for (const vrml::NodePtr& d : owner.mfnode("displacers")) {
    if (!d || d->type().id() != vrml::NodeTypeId::HAnimDisplacer) continue;
    const float w = d->get<FieldType::SFFloat>("weight", 0.0f);
    const vrml::FieldValue* ci = d->field("coordIndex");
    const vrml::FieldValue* dv = d->field("displacements");
    if (!std::isfinite(w) || ci == nullptr || dv == nullptr || ci->type() != FieldType::MFInt32 ||
        dv->type() != FieldType::MFVec3f)
      continue;
    const auto& coordIndex = ci->get<FieldType::MFInt32>();
    const auto& displacements = dv->get<FieldType::MFVec3f>();
    for (std::size_t k = 0; k < coordIndex.size() && k < displacements.size(); ++k) {
      const std::int32_t v = coordIndex[k];
      if (v >= 0 && static_cast<std::size_t>(v) < out.size())
        out[static_cast<std::size_t>(v)] += turn * (displacements[k] * w);
    }
  }
}

/// A hash of the revisions of `owner`'s displacers (0 when it has none).
std::uint64_t displacerRevisions(const vrml::Node& owner) {
  std::uint64_t h = 0;
  for (const vrml::NodePtr& d : owner.mfnode("displacers"))
    if (d) h = h * 1099511628211ULL + d->revision() + 1;
  return h;
}

// An HAnimSegment's displacers move the points of its own `coord` (26.4.2, as X_ITE 15 does:
// in the segment's coordinates, not turned): point_v = rest_v + sum_d displacement_dv w_d.
void evaluateSegmentDisplacers(const vrml::Node& humanoid, SkinState& st) {
  for (const vrml::NodePtr& segment : humanoid.mfnode("segments")) {
    if (!segment || segment->type().id() != vrml::NodeTypeId::HAnimSegment) continue;
    const std::uint64_t revisions = displacerRevisions(*segment);
    const vrml::NodePtr& coord = segment->sfnode("coord");
    if (revisions == 0 || !coord) continue;
    const int point = fieldIndex(*coord, "point", FieldType::MFVec3f);
    if (point < 0) continue;
    auto& points = coord->fieldAt(static_cast<std::size_t>(point)).get<FieldType::MFVec3f>();
    auto [it, added] = st.segmentRest.try_emplace(segment.get(), points, 0);
    if (!added && it->second.second == revisions) continue;
    it->second.second = revisions;
    const std::vector<glm::vec3>& rest = it->second.first;
    std::vector<glm::vec3> moved(rest.size(), glm::vec3(0.0f));
    addDisplacements(*segment, glm::mat3(1.0f), moved);
    points.resize(rest.size());
    for (std::size_t v = 0; v < rest.size(); ++v) points[v] = rest[v] + moved[v];
    coord->markChanged();
  }
}

}  // namespace

void ExecutionModel::State::evaluateHumanoid(NodeState& ns) {
  const vrml::Node& humanoid = *ns.node;
  SkinState& st = *ns.skin;
  evaluateSegmentDisplacers(humanoid, st);
  const vrml::NodePtr& coord = fieldOr<FieldType::SFNode>(humanoid, st.skinCoord);
  if (!coord) return;  // no skin to deform
  const int point = fieldIndex(*coord, "point", FieldType::MFVec3f);
  if (point < 0) return;
  const std::vector<vrml::NodePtr>& roots = fieldOr<FieldType::MFNode>(humanoid, st.skeleton);
  const std::uint64_t signature = walkSkeleton(roots, st.matrices, st.stack);
  const vrml::NodePtr& normal = fieldOr<FieldType::SFNode>(humanoid, st.skinNormal);
  const int vector = normal ? fieldIndex(*normal, "vector", FieldType::MFVec3f) : -1;
  auto& points = coord->fieldAt(static_cast<std::size_t>(point)).get<FieldType::MFVec3f>();
  std::vector<glm::vec3>* normals =
      vector >= 0 ? &normal->fieldAt(static_cast<std::size_t>(vector)).get<FieldType::MFVec3f>()
                  : nullptr;
  // The joints' HAnimDisplacers (26.3.2): their weights are part of the pose.
  const std::vector<vrml::NodePtr>& joints = fieldOr<FieldType::MFNode>(humanoid, st.joints);
  std::uint64_t displacers = 0;
  for (const vrml::NodePtr& joint : joints)
    if (joint && joint->type().id() == vrml::NodeTypeId::HAnimJoint)
      displacers = displacers * 31 + displacerRevisions(*joint);
  const std::uint64_t pose = signature ^ (displacers * 0x9e3779b97f4a7c15ULL);
  if (!st.evaluated) {  // the bind pose
    st.evaluated = true;
    st.signature = pose;
    st.bindPoints = points;
    if (normals != nullptr) st.bindNormals = *normals;
    st.bindInverse.clear();
    for (const auto& [node, m] : st.matrices) st.bindInverse.emplace(node, glm::inverse(m));
    if (displacers == 0) return;
  } else {
    if (pose == st.signature) return;
    st.signature = pose;
  }

  const std::size_t count = st.bindPoints.size();
  st.sum.assign(count, glm::vec3(0.0f));
  st.weight.assign(count, 0.0f);
  std::vector<glm::vec3> normalSum;
  const bool withNormals = normals != nullptr && st.bindNormals.size() == count;
  if (withNormals) normalSum.assign(count, glm::vec3(0.0f));
  std::vector<glm::vec3> displaced(displacers != 0 ? count : 0, glm::vec3(0.0f));
  for (const vrml::NodePtr& joint : joints) {
    if (!joint || joint->type().id() != vrml::NodeTypeId::HAnimJoint) continue;
    const auto now = st.matrices.find(joint.get());
    const auto bind = st.bindInverse.find(joint.get());
    if (now == st.matrices.end() || bind == st.bindInverse.end()) continue;
    const glm::mat4 m = now->second * bind->second;
    // Displacements (26.4.2), turned as the joint turns the skin (X_ITE 15's skinning):
    // point v += mat3(M_j) * displacement * weight, on top of the skinned point.
    if (!displaced.empty()) addDisplacements(*joint, glm::mat3(m), displaced);
    const auto& index = fieldOr<FieldType::MFInt32>(
        *joint, fieldIndex(*joint, "skinCoordIndex", FieldType::MFInt32));
    const auto& weight = fieldOr<FieldType::MFFloat>(
        *joint, fieldIndex(*joint, "skinCoordWeight", FieldType::MFFloat));
    for (std::size_t k = 0; k < index.size(); ++k) {
      const std::int32_t v = index[k];
      if (v < 0 || static_cast<std::size_t>(v) >= count) continue;
      const float w = k < weight.size() ? weight[k] : 1.0f;
      if (!std::isfinite(w)) continue;
      const auto vi = static_cast<std::size_t>(v);
      st.sum[vi] += w * glm::vec3(m * glm::vec4(st.bindPoints[vi], 1.0f));
      st.weight[vi] += w;
      if (withNormals) normalSum[vi] += w * (glm::mat3(m) * st.bindNormals[vi]);
    }
  }
  // Written in place (the change contract: markChanged after a write through fieldAt).
  points.resize(count);
  for (std::size_t v = 0; v < count; ++v)
    points[v] = st.sum[v] + (1.0f - st.weight[v]) * st.bindPoints[v] +
                (displaced.empty() ? glm::vec3(0.0f) : displaced[v]);
  coord->markChanged();
  if (withNormals) {
    normals->resize(count);
    for (std::size_t v = 0; v < count; ++v) {
      const glm::vec3 n = normalSum[v] + (1.0f - st.weight[v]) * st.bindNormals[v];
      const float len = glm::length(n);
      (*normals)[v] = len > 0.0f ? n / len : st.bindNormals[v];
    }
    normal->markChanged();
  }
}

}  // namespace gs::runtime
