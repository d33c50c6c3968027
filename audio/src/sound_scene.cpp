// SoundScene: the Sounds of a world, their gains and voices each frame (6.42, 6.3, 6.28).
#include "audio/sound_scene.hpp"

#include "base/url.hpp"
#include "clip_loads.hpp"
#include "vrml/transform.hpp"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>

namespace gs::audio {

namespace {

struct FoundSound {
  const vrml::Node* node;
  glm::mat4 world;
  const vrml::Scene* scene;  // the world that holds it: its url is the clips' base
};

struct Walk {
  const InlineQuery& inlines;
  std::vector<FoundSound>& out;
  std::vector<SoundScene::GraphRoot>& graph;
  std::vector<AcousticSurface>& surfaces;
  std::vector<std::shared_ptr<const vrml::Scene>> keep;  // inline worlds met this frame
  std::vector<const vrml::Scene*> path;                  // the worlds being walked

  void node(const vrml::NodePtr& n, const glm::mat4& m, const vrml::Scene* scene, int depth) {
    if (!n || depth > 256) return;
    using vrml::NodeTypeId;
    const NodeTypeId type = n->typeId();
    if (type == NodeTypeId::Sound) {
      out.push_back({n.get(), m, scene});
      return;
    }
    if (type == NodeTypeId::Shape) {
      AcousticSurface s;
      if (acousticSurfaceOf(*n, m, s)) surfaces.push_back(s);
      return;
    }
    if (type == NodeTypeId::AudioDestination || type == NodeTypeId::StreamAudioDestination ||
        type == NodeTypeId::SpatialSound || type == NodeTypeId::ListenerPointSource) {
      graph.push_back({n.get(), m, n->urlBaseOr(scene->url)});
      return;
    }
    if (vrml::placesChildren(type)) {
      const glm::mat4 child = m * vrml::transformMatrix(*n);
      for (const vrml::NodePtr& c : n->mfnode("children")) node(c, child, scene, depth + 1);
    } else if (type == NodeTypeId::Switch) {
      const auto& choices = n->mfnode("choice");
      const int which = n->get<vrml::FieldType::SFInt32>("whichChoice", -1);
      if (which >= 0 && static_cast<std::size_t>(which) < choices.size())
        node(choices[static_cast<std::size_t>(which)], m, scene, depth + 1);
    } else if (type == NodeTypeId::LOD) {
      const auto& levels = n->mfnode("level");
      if (!levels.empty()) node(levels.front(), m, scene, depth + 1);
    } else if (n->is(vrml::AbstractType::X3DGroupingNode)) {
      for (const vrml::NodePtr& c : n->mfnode("children")) node(c, m, scene, depth + 1);
    } else if (type == NodeTypeId::Inline && inlines) {
      // The world the renderer loaded for it, in the Inline's coordinate system (6.25).
      std::shared_ptr<const vrml::Scene> world = inlines(*n);
      // A world that inlines itself, directly or not, is walked once on each path.
      if (!world || std::find(path.begin(), path.end(), world.get()) != path.end()) return;
      keep.push_back(world);
      path.push_back(world.get());
      for (const vrml::NodePtr& c : world->rootNodes) node(c, m, world.get(), depth + 1);
      path.pop_back();
    }
  }
};

}  // namespace

SoundScene::SoundScene(std::shared_ptr<const vrml::Scene> scene, base::Fetcher* fetcher)
    : scene_(std::move(scene)), fetcher_(fetcher), loads_(std::make_unique<detail::ClipLoads>()) {}

SoundScene::~SoundScene() = default;

std::shared_ptr<const formats::AudioData> SoundScene::clipOf(const vrml::Node& clip,
                                                             const std::string& inheritedBase) {
  const std::string& base = clip.urlBaseOr(inheritedBase);  // an EXTERNPROTO file's node
  if (const auto it = clips_.find(&clip); it != clips_.end()) return it->second;
  if (!loading_.insert(&clip).second) return nullptr;  // on the worker: silent until decoded
  // The URLs are resolved here, on the drawing thread, where the node's fields may be read
  // and the loader used; files are read and decoded on the worker (docs/media.md).
  detail::ClipJob job;
  job.clip = &clip;
  job.movie = clip.typeId() == vrml::NodeTypeId::MovieTexture;
  const auto urls = clip.get<vrml::FieldType::MFString>("url", std::vector<std::string>{});
  bool arriving = false;  // a remote URL still on its way: the clip is asked for again later
  for (const std::string& reference : urls) {
    if (reference.empty()) continue;
    detail::ClipSource s;
    s.url = base::resolveUrl(base, reference);
    s.path = base::localFileFor(s.url, base, s.error);  // refused: error set
    if (s.path.empty() && s.error.empty()) {
      base::Fetched got = base::fetcherOr(fetcher_).fetch(s.url, base, base::FetchMode::background);
      s.fetched = got.ready();
      s.bytes = std::move(got.bytes);
      s.error = std::move(got.error);
      arriving = arriving || got.pending();
    }
    job.sources.push_back(std::move(s));
  }
  if (arriving) {  // never wait for the network here: silent until every fetch answered
    loading_.erase(&clip);
    ++fetchesWaiting_;
    return nullptr;
  }
  loads_->submit(std::move(job));
  return nullptr;
}

void SoundScene::install() {
  for (detail::ClipResult& r : loads_->take()) {
    if (!r.data)
      diagnostics_.warning(r.clip->location,
                           std::string(r.movie ? "cannot play the sound of MovieTexture ("
                                               : "cannot load AudioClip (") +
                               (r.failures.empty() ? std::string("no url") : r.failures) +
                               "): silent");
    durations_.emplace_back(r.clip, r.duration);
    loading_.erase(r.clip);
    clips_.emplace(r.clip, std::move(r.data));
  }
}

void SoundScene::waitForClips() {
  loads_->waitIdle();
  install();
}

std::size_t SoundScene::clipsLoading() const {
  return loading_.size();
}

void SoundScene::update(const glm::mat4& worldToListener, double now, const ClipTimeQuery& clipTime,
                        AudioOutput& output, const InlineQuery& inlines) {
  install();  // clips decoded since the last frame
  std::vector<FoundSound> found;
  std::vector<GraphRoot> graph;
  std::vector<AcousticSurface> surfaces;
  Walk walk{inlines, found, graph, surfaces, {}, {scene_.get()}};
  if (scene_)
    for (const vrml::NodePtr& n : scene_->rootNodes) walk.node(n, glm::mat4(1.0f), scene_.get(), 0);
  // Inline worlds stay alive while their nodes key clips_ (a renderer made anew loads new
  // ones; the old nodes' addresses must not be reused under our keys).
  for (auto& w : walk.keep) inlineWorlds_.emplace(w.get(), std::move(w));
  occlusion_.setSurfaces(std::move(surfaces));
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
    if (h.gain > 0.0f && occlusion_.surfaceCount() > 0)  // acoustic surfaces in the way
      h.gain *= occlusion_.transmission(glm::vec3(f.world * glm::vec4(g.location, 1.0f)), listener);
    Voice v;
    v.key = &s;
    const vrml::NodePtr source = s.sfnode("source");
    std::optional<ClipTime> time;
    const std::string& base = f.scene->url;
    if (source && source->typeId() == vrml::NodeTypeId::AudioClip) {
      v.clip = clipOf(*source, base);
      if (clipTime) time = clipTime(*source);
      v.pitch = source->get<FieldType::SFFloat>("pitch", 1.0f);
      v.loop = source->get<FieldType::SFBool>("loop", false);
    } else if (source && source->typeId() == vrml::NodeTypeId::MovieTexture) {
      // Its audio stream, on the movie's own clock (6.28); backwards it is not heard.
      v.clip = clipOf(*source, base);
      if (clipTime) time = clipTime(*source);
      v.pitch = source->get<FieldType::SFFloat>("speed", 1.0f);
      v.loop = source->get<FieldType::SFBool>("loop", false);
      if (!(v.pitch > 0.0f)) v.clip = nullptr;
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
  updateGraph(graph, worldToListener, now, clipTime, output);
}

std::vector<std::pair<const vrml::Node*, double>> SoundScene::takeDurations() {
  std::vector<std::pair<const vrml::Node*, double>> out;
  out.swap(durations_);
  return out;
}

}  // namespace gs::audio
