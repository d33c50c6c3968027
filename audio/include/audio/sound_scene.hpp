// The Sound nodes (ISO/IEC 14772-1:1997 6.42) of one world and their sources, AudioClips
// (6.3) or MovieTextures (6.28, their audio stream), heard from the viewer's place: each
// frame the scene graph is walked for Sounds (their coordinate systems through Transform,
// Group, Anchor, Billboard, Collision, the chosen Switch child, LOD's first level and the
// worlds of loaded Inlines, 6.25), each audible one gets the gain of the ellipsoid
// model (audio/sound_model.hpp), the device's voices go by priority, and the output
// plays them at the media time the execution model gives (docs/media.md).
#pragma once

#include "audio/acoustics.hpp"
#include "audio/audio_graph.hpp"
#include "audio/audio_output.hpp"
#include "audio/sound_model.hpp"
#include "base/fetch.hpp"
#include "formats/audio.hpp"
#include "vrml/diagnostic.hpp"
#include "vrml/drawn_output.hpp"
#include "vrml/node.hpp"
#include "vrml/scene.hpp"

#include <glm/mat4x4.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace gs::audio {

namespace detail {
class ClipLoads;
}

/// What the execution model says of an AudioClip or MovieTexture now (runtime::MediaState, as plain
/// values so audio/ needs no runtime/).
struct ClipTime {
  bool active = false;     // isActive
  double mediaTime = 0.0;  // seconds into the clip
};

/// The clip's state now; empty when the execution model does not know the node.
using ClipTimeQuery = std::function<std::optional<ClipTime>(const vrml::Node& clip)>;
/// The world an Inline node (6.25) has loaded so far (the renderer loads Inlines; e.g.
/// scene::SceneTraversal::loadedInline); null when none (not yet, or failed). Its `url`
/// is the base of the clip URLs inside it.
using InlineQuery = std::function<std::shared_ptr<const vrml::Scene>(const vrml::Node& inlineNode)>;

/// One Sound as last heard (for tests and a panel).
struct HeardSound {
  const vrml::Node* sound = nullptr;
  float gain = 0.0f;     // 6.42's model times intensity, 0..1
  bool playing = false;  // chosen and its clip active
};

class SoundScene {
 public:
  /// AudioClip and MovieTexture urls resolve against the url of the scene that holds them;
  /// local files the rules allow (base::localFileFor) are read on a worker thread, others
  /// fetched through `fetcher` in the background (base::FetchMode::background: never
  /// waiting, asked again on a later frame while pending; called on the thread that calls
  /// update(); null: local files and data: URLs only; not owned, must outlive the scene);
  /// each clip once, from its first use, decoded on the worker: a Sound is silent until
  /// its clip is decoded.
  SoundScene(std::shared_ptr<const vrml::Scene> scene, base::Fetcher* fetcher);
  ~SoundScene();  // waits for the clip being decoded, if any
  SoundScene(const SoundScene&) = delete;
  SoundScene& operator=(const SoundScene&) = delete;

  /// One frame at simulated time `now` (seconds): `worldToListener` is the viewer's view
  /// matrix (world to eye coordinates). Walks the scene (and, through `inlines`, the Inline worlds
  /// loaded so far), loads new clips, computes every Sound's gain, chooses voices and hands them to
  /// `output`. A MovieTexture source plays its audio stream (formats/movie_audio.hpp) at its media
  /// time, at `speed` as the pitch; a movie played backwards (speed < 0) is silent.
  /// The X3D 4 audio graph (AudioDestinations and SpatialSounds and what they take in,
  /// audio/audio_graph.hpp) is rendered from the last update's time to `now` (at most half
  /// a second; nothing on the first update) and streamed to `output`; its sources play
  /// while `clipTime` says they are active (the execution model's X3DTimeDependentNode
  /// state) and are silent while it does not know them.
  void update(const glm::mat4& worldToListener, double now, const ClipTimeQuery& clipTime,
              AudioOutput& output, const InlineQuery& inlines = {});

  /// Durations (seconds; -1: unreadable) of clips loaded since the last call, for
  /// runtime::ExecutionModel::setMediaDuration (a MovieTexture's is its video's, the one
  /// the renderer reports).
  std::vector<std::pair<const vrml::Node*, double>> takeDurations();
  /// Waits until the worker has decoded every clip asked for so far and takes them in (their
  /// durations and diagnostics too): for tests and --snapshot-like callers that want the
  /// same result every run; the window never waits.
  void waitForClips();
  /// Clips being read or decoded on the worker now (asked for, not yet taken in).
  std::size_t clipsLoading() const;
  /// How many times a clip was asked for while one of its remote URLs was still arriving
  /// (the loader answered "on its way"): each such frame went on without waiting.
  std::size_t fetchesWaiting() const { return fetchesWaiting_; }
  /// Every Sound of the last update, in scene order.
  const std::vector<HeardSound>& heard() const { return heard_; }
  /// Clips that could not be read, each once ("URL: why").
  const vrml::Diagnostics& diagnostics() const { return diagnostics_; }
  /// The X3D 4 audio graph of the last update (sound_graph_scene.cpp).
  const AudioGraph& graph() const { return graph_; }
  /// The output events the updates since the last call computed, for
  /// runtime::ExecutionModel::sendDrawnOutputs: each DynamicsCompressor's `reduction` (X3D
  /// 4.0 clause 16, Sound: the gain reduction the compressor applies now, in dB, <= 0, as Web
  /// Audio's DynamicsCompressorNode.reduction) once it is 0.01 dB or more from the value
  /// last sent (0, the field's initial value, before any).
  vrml::DrawnOutputs takeOutputs() { return std::exchange(outputs_, {}); }

  /// An AudioDestination, SpatialSound or ListenerPointSource met in the scene graph, with
  /// its coordinate system and the url its clips resolve against.
  struct GraphRoot {
    const vrml::Node* node = nullptr;
    glm::mat4 world{1.0f};
    std::string base;
  };

 private:
  /// Sets the graph from `roots` and renders it to `now` (sound_graph_scene.cpp).
  void updateGraph(const std::vector<GraphRoot>& roots, const glm::mat4& worldToListener,
                   double now, const ClipTimeQuery& clipTime, AudioOutput& output);
  /// Sets the processor of `n` (a sound source, processing or channel node) and those of its
  /// children, once per update (`seen`).
  void setProcessor(const vrml::Node& n, const std::string& base, const ClipTimeQuery& clipTime,
                    std::unordered_set<const vrml::Node*>& seen, int depth);
  /// The sampled sound of an AudioClip or BufferAudioSource (its `buffer` data, or its url
  /// decoded like an AudioClip's); null while decoding or when it has none.
  std::shared_ptr<const SampledSound> sampledOf(const vrml::Node& n, const std::string& base);

  /// The clip's sound once decoded; null while on the worker (the first call starts it) or
  /// when it cannot be played. Its urls resolve against clip.urlBaseOr(base).
  std::shared_ptr<const formats::AudioData> clipOf(const vrml::Node& clip, const std::string& base);
  /// Takes in the clips the worker finished.
  void install();

  std::shared_ptr<const vrml::Scene> scene_;
  base::Fetcher* fetcher_ = nullptr;
  vrml::NodeMap<std::shared_ptr<const formats::AudioData>> clips_;
  std::unordered_set<const vrml::Node*> loading_;  // on the worker
  std::size_t fetchesWaiting_ = 0;
  std::vector<std::pair<const vrml::Node*, double>> durations_;
  std::vector<HeardSound> heard_;
  std::unordered_map<const vrml::Scene*, std::shared_ptr<const vrml::Scene>> inlineWorlds_;
  vrml::Diagnostics diagnostics_;
  AcousticOcclusion occlusion_;  // this frame's acoustic surfaces (audio/acoustics.hpp)
  AudioGraph graph_;
  std::vector<const vrml::Node*> compressors_;  // the DynamicsCompressors of the last update
  vrml::NodeMap<float> sentReductions_;         // each one's `reduction` as last sent
  vrml::DrawnOutputs outputs_;                  // not yet taken (takeOutputs)
  double graphTime_ = -1.0;  // the simulated time rendered up to; < 0 before the first update
  std::unordered_map<const formats::AudioData*, std::shared_ptr<const SampledSound>> sampled_;
  /// Each MicrophoneSource's captured samples not yet heard, and where the last playing one
  /// is (null: none this frame, nothing captured).
  std::unordered_map<const vrml::Node*, std::shared_ptr<std::deque<float>>> microphones_;
  const vrml::SourceLocation* microphoneLocation_ = nullptr;
  /// BufferAudioSources' `buffer` data as sampled sound, with the revision it was made at.
  std::unordered_map<const vrml::Node*,
                     std::pair<std::uint64_t, std::shared_ptr<const SampledSound>>>
      buffers_;
  std::unique_ptr<detail::ClipLoads> loads_;  // last: its worker stops first
};

}  // namespace gs::audio
