// The Sound nodes (ISO/IEC 14772-1:1997 6.42) of one world and their AudioClips (6.3),
// heard from the viewer's place: each frame the scene graph is walked for Sounds (their
// coordinate systems through Transform, Group, Anchor, Billboard, Collision, the chosen
// Switch child and LOD's first level), each audible one gets the gain of the ellipsoid
// model (audio/sound_model.hpp), the device's voices go by priority, and the output
// plays them at the media time the execution model gives (docs/media.md).
#pragma once

#include "audio/audio_output.hpp"
#include "audio/sound_model.hpp"
#include "formats/audio.hpp"
#include "vrml/diagnostic.hpp"
#include "vrml/node.hpp"
#include "vrml/scene.hpp"

#include <glm/mat4x4.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace gs::audio {

/// What the execution model says of an AudioClip now (runtime::MediaState, as plain
/// values so audio/ needs no runtime/).
struct ClipTime {
  bool active = false;     // isActive
  double mediaTime = 0.0;  // seconds into the clip
};

/// The clip's state now; empty when the execution model does not know the node.
using ClipTimeQuery = std::function<std::optional<ClipTime>(const vrml::Node& clip)>;
/// Reads the bytes of an already resolved URL (the session's loader or a file read).
using ClipLoader =
    std::function<bool(const std::string& url, std::string& bytes, std::string& error)>;

/// One Sound as last heard (for tests and a panel).
struct HeardSound {
  const vrml::Node* sound = nullptr;
  float gain = 0.0f;     // 6.42's model times intensity, 0..1
  bool playing = false;  // chosen and its clip active
};

class SoundScene {
 public:
  /// AudioClip urls resolve against the scene's url; local files are read directly (as
  /// base::mayReference allows), others through `loader` (empty: local files only); each
  /// clip once, on first use.
  SoundScene(std::shared_ptr<const vrml::Scene> scene, ClipLoader loader);

  /// One frame: `worldToListener` is the viewer's view matrix (world to eye coordinates).
  /// Walks the scene, loads new clips, computes every Sound's gain, chooses voices and
  /// hands them to `output`.
  void update(const glm::mat4& worldToListener, const ClipTimeQuery& clipTime, AudioOutput& output);

  /// Durations (seconds; -1: unreadable) of clips loaded since the last call, for
  /// runtime::ExecutionModel::setMediaDuration.
  std::vector<std::pair<const vrml::Node*, double>> takeDurations();
  /// Every Sound of the last update, in scene order.
  const std::vector<HeardSound>& heard() const { return heard_; }
  /// Clips that could not be read, each once ("URL: why").
  const vrml::Diagnostics& diagnostics() const { return diagnostics_; }

 private:
  std::shared_ptr<const formats::AudioData> clipOf(const vrml::Node& clip);

  std::shared_ptr<const vrml::Scene> scene_;
  ClipLoader loader_;
  std::unordered_map<const vrml::Node*, std::shared_ptr<const formats::AudioData>> clips_;
  std::vector<std::pair<const vrml::Node*, double>> durations_;
  std::vector<HeardSound> heard_;
  vrml::Diagnostics diagnostics_;
};

}  // namespace gs::audio
