// Sound sources decoded on a worker thread (docs/media.md, "Threading"): the frame that
// first meets a clip does not decode it; the Sound is silent until the worker is done and
// plays from the next frame on, at the media time of that frame. Deterministic: the test
// waits for the worker (SoundScene::waitForClips), it never sleeps.
#include "base/file.hpp"
#include "movie_maker.hpp"
#include "sound_world.hpp"

#include <catch2/catch.hpp>

#include <filesystem>

using namespace gs;

namespace {

std::string clipDir() {
  const std::string dir = std::string(GS_BINARY_DIR) + "/test_audio_worker";
  std::filesystem::create_directories(dir);
  return dir;
}

/// Asks the execution model for the media time, as the window does, without waiting.
void frameWithoutWaiting(test::SoundWorld& w, double time) {
  w.model->advanceTo(time);
  w.sounds.update(
      glm::mat4(1.0f), time,
      [&w](const vrml::Node& n) -> std::optional<audio::ClipTime> {
        const auto m = w.model->media(n);
        if (!m) return std::nullopt;
        return audio::ClipTime{m->active, m->mediaTime};
      },
      w.out, w.inlines);
  for (const auto& [node, seconds] : w.sounds.takeDurations())
    w.model->setMediaDuration(*node, seconds);
}

}  // namespace

TEST_CASE("Sound: a MovieTexture's sound is decoded off the drawing thread",
          "[audio][sound][movie][worker]") {
  const std::string movie = clipDir() + "/worker_tone.mpg";
  std::string error;
  REQUIRE(test::writeMovie(movie, test::MovieSpec{}, error));
  test::SoundWorld w(R"(Sound { source DEF M MovieTexture { url "worker_tone.mpg" loop TRUE } })",
                     clipDir() + "/world.wrl");
  // The first frame only hands the movie to the worker: nothing decoded, nothing heard,
  // no duration yet.
  frameWithoutWaiting(w, 0.0);
  CHECK(w.sounds.clipsLoading() == 1);
  CHECK(w.out.playing().empty());
  const vrml::Node& node = *w.scene->rootNodes[0]->sfnode("source");
  CHECK_FALSE(w.model->media(node)->duration.has_value());
  // Asking again while it decodes starts no second decode.
  frameWithoutWaiting(w, 0.1);
  CHECK(w.sounds.clipsLoading() <= 1);
  // Once the worker is done, the duration is known and the sound plays at the movie's time.
  w.sounds.waitForClips();
  CHECK(w.sounds.clipsLoading() == 0);
  for (const auto& [n, seconds] : w.sounds.takeDurations()) w.model->setMediaDuration(*n, seconds);
  REQUIRE(w.model->media(node)->duration.has_value());
  CHECK(*w.model->media(node)->duration == Approx(1.0));
  frameWithoutWaiting(w, 10.25);  // looping from 0: 0.25 s into the 1 s movie
  REQUIRE(w.out.playing().size() == 1);
  CHECK(w.out.playing()[0].offset == Approx(0.25));
  REQUIRE(w.out.playing()[0].clip);
  CHECK(w.out.playing()[0].clip->sampleRate == 44100);
  CHECK(w.sounds.diagnostics().items.empty());
}

TEST_CASE("Sound: an AudioClip that cannot be read is reported once the worker gives up",
          "[audio][sound][worker]") {
  test::SoundWorld w(R"(Sound { source AudioClip { url "no_such_clip.wav" loop TRUE } })",
                     clipDir() + "/world.wrl");
  frameWithoutWaiting(w, 0.0);
  CHECK(w.sounds.diagnostics().items.empty());  // not known yet on this frame
  w.sounds.waitForClips();
  REQUIRE(w.sounds.diagnostics().items.size() == 1);
  CHECK(w.sounds.diagnostics().items[0].message.find("no_such_clip.wav") != std::string::npos);
  const auto durations = w.sounds.takeDurations();
  REQUIRE(durations.size() == 1);
  CHECK(durations[0].second == -1.0);
  frameWithoutWaiting(w, 1.0);
  CHECK(w.out.playing().empty());
  CHECK(w.sounds.clipsLoading() == 0);
}

TEST_CASE("Sound: a remote AudioClip is fetched without waiting, frame by frame",
          "[audio][sound][worker][remote]") {
  // A loader that answers "on its way" for three calls, then gives the WAV's bytes, as
  // net::Loader::fetchInBackground does: no frame may block on the transfer.
  std::string wav;
  std::string error;
  REQUIRE(base::readFile(std::string(GS_SOURCE_DIR) + "/assets/media/tone.wav", wav, error));
  int calls = 0;
  base::CallbackFetcher fetcher(
      [&](const std::string& url, const std::string& referrer, base::FetchMode mode) {
        CHECK(url == "http://example.org/media/tone.wav");
        CHECK(referrer == "http://example.org/media/world.wrl");
        CHECK(mode == base::FetchMode::background);
        if (++calls <= 3) return base::Fetched{base::FetchState::pending, {}, {}};  // arriving
        return base::fetchReady(wav);
      });
  test::SoundWorld w(R"(Sound { source AudioClip { url "tone.wav" loop TRUE } })",
                     "http://example.org/media/world.wrl", &fetcher);
  for (int frame = 0; frame < 3; ++frame) {
    frameWithoutWaiting(w, 0.1 * frame);
    CHECK(w.sounds.clipsLoading() == 0);  // nothing handed to the worker yet
    CHECK(w.out.playing().empty());
  }
  CHECK(w.sounds.fetchesWaiting() == 3);
  CHECK(w.sounds.diagnostics().items.empty());
  frameWithoutWaiting(w, 0.3);  // the bytes arrived: handed to the worker
  CHECK(calls == 4);
  w.sounds.waitForClips();
  for (const auto& [n, seconds] : w.sounds.takeDurations()) w.model->setMediaDuration(*n, seconds);
  frameWithoutWaiting(w, 0.4);
  REQUIRE(w.out.playing().size() == 1);
  CHECK(w.sounds.diagnostics().items.empty());
  CHECK(calls == 4);  // asked no more once decoded
}

TEST_CASE("Sound: a remote AudioClip whose fetch fails is reported, not retried",
          "[audio][sound][worker][remote]") {
  int calls = 0;
  base::CallbackFetcher fetcher([&](const std::string& url, const std::string&, base::FetchMode) {
    ++calls;
    return base::fetchFailed(url + ": HTTP 404");
  });
  test::SoundWorld w(R"(Sound { source AudioClip { url "gone.wav" loop TRUE } })",
                     "http://example.org/media/world.wrl", &fetcher);
  frameWithoutWaiting(w, 0.0);
  w.sounds.waitForClips();
  frameWithoutWaiting(w, 0.1);
  CHECK(calls == 1);
  REQUIRE(w.sounds.diagnostics().items.size() == 1);
  CHECK(w.sounds.diagnostics().items[0].message.find("gone.wav: HTTP 404") != std::string::npos);
  CHECK(w.sounds.fetchesWaiting() == 0);
}
