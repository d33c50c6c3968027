// A world of the audio tests: parsed VRML, its execution model, a SoundScene and the null
// output, moved frame by frame as the window moves them (app/src/world_sound.cpp).
#pragma once

#include "audio/audio_output.hpp"
#include "audio/sound_scene.hpp"
#include "encodings/parser.hpp"
#include "runtime/execution_model.hpp"

#include <memory>
#include <string>
#include <utility>

namespace gs::test {

struct SoundWorld {
  std::shared_ptr<vrml::Scene> scene;
  std::unique_ptr<runtime::ExecutionModel> model;
  audio::SoundScene sounds;
  audio::NullAudioOutput out;
  audio::InlineQuery inlines;  // empty: Inlines are not walked

  /// `body` after the VRML header, as if read from `url` (the base of its clip URLs).
  /// `fetcher` fetches the URLs that are not local files (none: only files play).
  explicit SoundWorld(const std::string& body,
                      const std::string& url = std::string(GS_SOURCE_DIR) +
                                               "/assets/media/test.wrl",
                      base::Fetcher* fetcher = nullptr)
      : scene(std::make_shared<vrml::Scene>(vrml::parseVrml("#VRML V2.0 utf8\n" + body, url))),
        model(std::make_unique<runtime::ExecutionModel>(scene, 0.0)),
        sounds(scene, fetcher) {}

  /// One frame at `time` heard from `listener` (a viewer looking down -Z).
  void frame(double time, glm::vec3 listener = {0.0f, 0.0f, 0.0f}) {
    model->advanceTo(time);
    glm::mat4 view(1.0f);
    view[3] = glm::vec4(-listener, 1.0f);
    sounds.update(
        view, time,
        [this](const vrml::Node& n) -> std::optional<audio::ClipTime> {
          const auto m = model->media(n);
          if (!m) return std::nullopt;
          return audio::ClipTime{m->active, m->mediaTime};
        },
        out, inlines);
    sounds.waitForClips();  // clips are decoded on a worker: wait, for the same result every run
    for (const auto& [node, seconds] : sounds.takeDurations())
      model->setMediaDuration(*node, seconds);
  }
};

}  // namespace gs::test
