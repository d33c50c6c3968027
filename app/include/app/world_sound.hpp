// Sound in the window (docs/media.md): the Sound nodes of the world in the active viewport,
// heard from its camera through one audio output (OpenAL Soft, or the null output where no
// device opens), AudioClips timed by the world's execution model.
#pragma once

#include "audio/audio_output.hpp"
#include "audio/sound_scene.hpp"
#include "scene/camera.hpp"
#include "session/world_runtime.hpp"

#include <map>
#include <memory>
#include <string>

namespace gs::app {

class WorldSounds {
 public:
  /// Opens the audio output (`enabled` false: the null output). `fetcher` reads clip URLs
  /// that are not local files in the background (audio::SoundScene; the window passes its
  /// session's net::Loader; not owned, must outlive this).
  WorldSounds(bool enabled, base::Fetcher* fetcher);
  /// Why the output is the null one ("" when a device opened).
  const std::string& note() const { return note_; }
  /// One frame: `scene`'s Sounds heard from `camera`, clip durations to `runtimes`; the
  /// Sounds of the Inline worlds `traversal` (a renderer of `scene`; may be null) loaded too.
  void update(const std::shared_ptr<const vrml::Scene>& scene, const scene::Camera& camera,
              session::WorldRuntimes& runtimes, double now,
              const scene::SceneTraversal* traversal = nullptr);

 private:
  std::string note_;  // before output_: the output's constructor writes it
  std::unique_ptr<audio::AudioOutput> output_;
  base::Fetcher* fetcher_ = nullptr;
  std::map<const vrml::Scene*, std::unique_ptr<audio::SoundScene>> scenes_;
  std::map<const vrml::Scene*, std::size_t> shown_;  // diagnostics printed
};

}  // namespace gs::app
