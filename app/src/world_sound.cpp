#include "app/world_sound.hpp"

#include <cstdio>

namespace gs::app {

WorldSounds::WorldSounds(bool enabled, base::Fetcher* fetcher)
    : output_(audio::openAudioOutput(enabled, note_)), fetcher_(fetcher) {}

void WorldSounds::update(const std::shared_ptr<const vrml::Scene>& scene,
                         const scene::Camera& camera, session::WorldRuntimes& runtimes, double now,
                         const scene::SceneTraversal* traversal) {
  if (!scene) return;
  auto& s = scenes_[scene.get()];
  if (!s) s = std::make_unique<audio::SoundScene>(scene, fetcher_);
  runtime::ExecutionModel& model = runtimes.of(scene, now);
  s->update(
      scene::viewMatrix(camera), now,
      [&model](const vrml::Node& clip) -> std::optional<audio::ClipTime> {
        const auto m = model.media(clip);
        if (!m) return std::nullopt;
        return audio::ClipTime{m->active, m->mediaTime};
      },
      *output_,
      traversal ? audio::InlineQuery(
                      [traversal](const vrml::Node& inl) { return traversal->loadedInline(inl); })
                : audio::InlineQuery());
  runtimes.setMediaDurations(scene.get(), s->takeDurations());
  runtimes.sendDrawnOutputs(scene.get(), s->takeOutputs());
  // Clips that cannot be read: each once, as the renderer's diagnostics.
  std::size_t& shown = shown_[scene.get()];
  for (; shown < s->diagnostics().items.size(); ++shown)
    std::fprintf(stderr, "%s\n", s->diagnostics().items[shown].format().c_str());
}

}  // namespace gs::app
