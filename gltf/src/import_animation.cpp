// glTF animations (glTF 2.0 clause 3.11) as X3D's event model runs them, the way
// castle-engine converts them: one TimeSensor per animation, DEF-named after it, with
// cycleInterval the animation's length; per channel a PositionInterpolator (translation,
// scale) or OrientationInterpolator (rotation) ROUTEd from the sensor's fraction_changed
// to the target Transform. The first animation loops from time 0; the others are
// stopped until their TimeSensor is started. STEP samplers become keys doubled just before
// the next key; CUBICSPLINE samplers are interpolated linearly through their values.
// `weights` channels (morph target animation, clause 3.7.2.2) become per primitive a
// CoordinateInterpolator and NormalInterpolator of the morphed vertices at each key: the
// vertices are linear in the weights, so between LINEAR keys this is exact.
#include "importer.hpp"

#include "gltf/accessors.hpp"

#include <cmath>

namespace gs::gltf::x3d {

void addRoute(Scene& scene, const NodePtr& from, const char* fromField, const NodePtr& to,
              const char* toField, const std::string& url) {
  scene.routes.push_back(Route{from, fromField, to, toField, SourceLocation{url, 0, 0}});
}

std::set<int> GltfImporter::morphAnimatedNodes() const {
  std::set<int> out;
  for (const tinygltf::Animation& anim : m_.animations)
    for (const tinygltf::AnimationChannel& ch : anim.channels)
      if (ch.target_path == "weights" && ch.target_node >= 0 &&
          static_cast<std::size_t>(ch.target_node) < m_.nodes.size() &&
          m_.nodes[static_cast<std::size_t>(ch.target_node)].mesh >= 0)
        out.insert(ch.target_node);
  return out;
}

void GltfImporter::animations() {
  std::vector<NodePtr> made;
  for (std::size_t a = 0; a < m_.animations.size(); ++a) {
    const tinygltf::Animation& anim = m_.animations[a];
    // Each sampler's times, read once; the animation lasts until its last key.
    std::vector<std::vector<float>> times(anim.samplers.size());
    float duration = 0.0f;
    for (std::size_t s = 0; s < anim.samplers.size(); ++s) {
      times[s] = gltf::readFloats(m_, anim.samplers[s].input, 1, url_, "animation input");
      for (float t : times[s])
        if (std::isfinite(t)) duration = std::max(duration, t);
    }
    if (!(duration > 0.0f)) continue;
    NodePtr sensor = make("TimeSensor");
    sensor->defName = anim.name.empty() ? "animation_" + std::to_string(a) : anim.name;
    set(*sensor, "cycleInterval",
        FieldValue::make<FieldType::SFTime>(static_cast<double>(duration)));
    set(*sensor, "loop", FieldValue::make<FieldType::SFBool>(a == 0));
    made.push_back(sensor);
    // EXPORTed by name, so that a world Inlining the asset can IMPORT and start it (as
    // castle-engine exports glTF animations).
    scene_.x3d.exports.push_back(X3dExport{sensor->defName, sensor->defName, sensor, {url_, 0, 0}});
    for (const tinygltf::AnimationChannel& ch : anim.channels) {
      if (ch.sampler < 0 || static_cast<std::size_t>(ch.sampler) >= anim.samplers.size() ||
          ch.target_node < 0 || static_cast<std::size_t>(ch.target_node) >= transforms_.size() ||
          !transforms_[static_cast<std::size_t>(ch.target_node)])
        continue;  // a channel to a node outside the scene drawn animates nothing
      const tinygltf::AnimationSampler& sampler =
          anim.samplers[static_cast<std::size_t>(ch.sampler)];
      const bool rotation = ch.target_path == "rotation";
      const bool weights = ch.target_path == "weights";
      if (ch.target_path != "translation" && ch.target_path != "scale" && !rotation && !weights)
        continue;
      const std::vector<float>& t = times[static_cast<std::size_t>(ch.sampler)];
      const bool cubic = sampler.interpolation == "CUBICSPLINE";
      const bool step = sampler.interpolation == "STEP";
      // The keys as fractions of the cycle, each with the sampler key whose value it holds:
      // a STEP key is doubled just before the next one, so it holds until then.
      std::vector<float> key;
      std::vector<std::size_t> source;
      for (std::size_t i = 0; i < t.size(); ++i) {
        key.push_back(std::clamp(t[i] / duration, 0.0f, 1.0f));
        source.push_back(i);
        if (step && i + 1 < t.size()) {
          key.push_back(std::nextafter(std::clamp(t[i + 1] / duration, 0.0f, 1.0f), 0.0f));
          source.push_back(i);
        }
      }
      if (weights) {
        const std::vector<float> out =
            gltf::readFloats(m_, sampler.output, 1, url_, "animation output");
        morphChannel(sensor, ch.target_node, key, source, out, t.size(), cubic, made);
        continue;
      }
      const int comps = rotation ? 4 : 3;
      std::vector<float> out =
          gltf::readFloats(m_, sampler.output, comps, url_, "animation output");
      const std::size_t per = cubic ? 3 : 1;  // in-tangent, value, out-tangent
      if (out.size() != t.size() * per * static_cast<std::size_t>(comps))
        gltf::fail(url_, "animation " + std::to_string(a) +
                             ": a sampler's output count does not match its input count");
      std::vector<glm::vec3> vec;
      std::vector<Rotation> rot;
      for (std::size_t i : source) {
        const std::size_t at = (i * per + (cubic ? 1 : 0)) * static_cast<std::size_t>(comps);
        if (rotation)
          rot.push_back(gltfRotation(glm::dquat(out[at + 3], out[at], out[at + 1], out[at + 2])));
        else
          vec.emplace_back(out[at], out[at + 1], out[at + 2]);
      }
      NodePtr interp = make(rotation ? "OrientationInterpolator" : "PositionInterpolator");
      set(*interp, "key", FieldValue::make<FieldType::MFFloat>(key));
      if (rotation)
        set(*interp, "keyValue", FieldValue::make<FieldType::MFRotation>(std::move(rot)));
      else
        set(*interp, "keyValue", FieldValue::make<FieldType::MFVec3f>(std::move(vec)));
      made.push_back(interp);
      const NodePtr& target = transforms_[static_cast<std::size_t>(ch.target_node)];
      addRoute(scene_, sensor, "fraction_changed", interp, "set_fraction", url_);
      addRoute(scene_, interp, "value_changed", target,
               rotation                    ? "set_rotation"
               : ch.target_path == "scale" ? "set_scale"
                                           : "set_translation",
               url_);
    }
  }
  for (NodePtr& n : made) {
    scene_.rootNodes.push_back(n);
    if (options_.onRootNode) options_.onRootNode(n);
  }
}

}  // namespace gs::gltf::x3d
