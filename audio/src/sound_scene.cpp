// SoundScene: the Sounds of a world, their gains and voices each frame (6.42, 6.3).
#include "audio/sound_scene.hpp"

#include "base/file.hpp"
#include "base/url.hpp"
#include "vrml/transform.hpp"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_inverse.hpp>

namespace gs::audio {

namespace {

struct FoundSound {
  const vrml::Node* node;
  glm::mat4 world;
};

void walk(const vrml::NodePtr& n, const glm::mat4& m, std::vector<FoundSound>& out, int depth) {
  if (!n || depth > 256) return;
  const std::string& type = n->typeName();
  if (type == "Sound") {
    out.push_back({n.get(), m});
    return;
  }
  if (type == "Transform") {
    const glm::mat4 child = m * vrml::transformMatrix(*n);
    for (const vrml::NodePtr& c : n->mfnode("children")) walk(c, child, out, depth + 1);
  } else if (type == "Group" || type == "Anchor" || type == "Billboard" || type == "Collision") {
    for (const vrml::NodePtr& c : n->mfnode("children")) walk(c, m, out, depth + 1);
  } else if (type == "Switch") {
    const auto& choices = n->mfnode("choice");
    const int which = n->get<vrml::FieldType::SFInt32>("whichChoice", -1);
    if (which >= 0 && static_cast<std::size_t>(which) < choices.size())
      walk(choices[static_cast<std::size_t>(which)], m, out, depth + 1);
  } else if (type == "LOD") {
    const auto& levels = n->mfnode("level");
    if (!levels.empty()) walk(levels.front(), m, out, depth + 1);
  }
}

}  // namespace

SoundScene::SoundScene(std::shared_ptr<const vrml::Scene> scene, ClipLoader loader)
    : scene_(std::move(scene)), loader_(std::move(loader)) {}

std::shared_ptr<const formats::AudioData> SoundScene::clipOf(const vrml::Node& clip) {
  if (const auto it = clips_.find(&clip); it != clips_.end()) return it->second;
  std::shared_ptr<formats::AudioData> data;
  std::string failures;
  const std::string base = scene_ ? scene_->url : std::string();
  const auto urls = clip.get<vrml::FieldType::MFString>("url", std::vector<std::string>{});
  for (const std::string& reference : urls) {
    if (reference.empty()) continue;
    const std::string url = base::resolveUrl(base, reference);
    std::string bytes, error;
    bool ok = false;
    if (base::mayReference(base, url, error)) {
      const std::string path = base::localPathOfUrl(url);
      if (!path.empty()) ok = base::readFile(path, bytes, error);
      if (!ok && loader_) ok = loader_(url, bytes, error);
    }
    auto decoded = std::make_shared<formats::AudioData>();
    if (ok && formats::readAudio(bytes, url, *decoded, error)) {
      data = std::move(decoded);
      break;
    }
    failures += (failures.empty() ? "" : "; ") + (error.empty() ? url : error);
  }
  if (!data)
    diagnostics_.warning(clip.location, "cannot load AudioClip (" +
                                            (failures.empty() ? std::string("no url") : failures) +
                                            "): silent");
  durations_.emplace_back(&clip, data ? data->duration() : -1.0);
  clips_.emplace(&clip, data);
  return data;
}

void SoundScene::update(const glm::mat4& worldToListener, const ClipTimeQuery& clipTime,
                        AudioOutput& output) {
  std::vector<FoundSound> found;
  if (scene_)
    for (const vrml::NodePtr& n : scene_->rootNodes) walk(n, glm::mat4(1.0f), found, 0);
  const glm::mat4 listenerToWorld = glm::inverse(worldToListener);
  const glm::vec3 listener(listenerToWorld[3]);
  heard_.clear();
  std::vector<SoundCandidate> candidates;
  std::vector<Voice> voices;
  for (const FoundSound& f : found) {
    const vrml::Node& s = *f.node;
    using vrml::FieldType;
    SoundGeometry g;
    g.location = s.get<FieldType::SFVec3f>("location", glm::vec3(0.0f));
    g.direction = s.get<FieldType::SFVec3f>("direction", glm::vec3(0.0f, 0.0f, 1.0f));
    g.minFront = s.get<FieldType::SFFloat>("minFront", 1.0f);
    g.minBack = s.get<FieldType::SFFloat>("minBack", 1.0f);
    g.maxFront = s.get<FieldType::SFFloat>("maxFront", 10.0f);
    g.maxBack = s.get<FieldType::SFFloat>("maxBack", 10.0f);
    // The model is evaluated in the Sound's coordinate system, so a scaled Transform
    // scales its ellipsoids too.
    const glm::vec3 local(glm::inverse(f.world) * glm::vec4(listener, 1.0f));
    HeardSound h;
    h.sound = &s;
    h.gain = soundGain(g, s.get<FieldType::SFFloat>("intensity", 1.0f), local);
    Voice v;
    v.key = &s;
    const vrml::NodePtr source = s.sfnode("source");
    std::optional<ClipTime> time;
    if (source && source->typeName() == "AudioClip") {
      v.clip = clipOf(*source);
      if (clipTime) time = clipTime(*source);
      v.pitch = source->get<FieldType::SFFloat>("pitch", 1.0f);
      v.loop = source->get<FieldType::SFBool>("loop", false);
    }
    const bool audible = v.clip && time && time->active && h.gain > 0.0f;
    v.offset = time ? time->mediaTime : 0.0;
    v.gain = h.gain;
    v.spatialize = s.get<FieldType::SFBool>("spatialize", true);
    v.position = glm::vec3(worldToListener * f.world * glm::vec4(g.location, 1.0f));
    candidates.push_back({s.get<FieldType::SFFloat>("priority", 0.0f), audible ? h.gain : 0.0f});
    voices.push_back(std::move(v));
    heard_.push_back(h);
  }
  std::vector<Voice> chosen;
  for (std::size_t i : chooseSounds(candidates, output.maxVoices())) {
    heard_[i].playing = true;
    chosen.push_back(std::move(voices[i]));
  }
  output.update(chosen);
}

std::vector<std::pair<const vrml::Node*, double>> SoundScene::takeDurations() {
  std::vector<std::pair<const vrml::Node*, double>> out;
  out.swap(durations_);
  return out;
}

}  // namespace gs::audio
