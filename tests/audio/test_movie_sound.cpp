// A MovieTexture as the source of a Sound (ISO/IEC 14772-1:1997 6.42, 6.28): its audio
// stream, decoded through FFmpeg and libswresample, plays through the null output on the
// movie's own clock. The clip is made at test time (movie_maker.hpp): MPEG-1 video and MP2
// audio, 1 s at 25 fps, a 440 Hz tone for the first half second and 880 Hz after.
#include "base/file.hpp"
#include "formats/movie_audio.hpp"
#include "movie_maker.hpp"
#include "sound_world.hpp"

#include <catch2/catch.hpp>

#include <filesystem>

#include <unistd.h>

using namespace gs;

namespace {

std::string testDir() {
  const std::string dir = std::string(GS_BINARY_DIR) + "/test_audio_media";
  std::filesystem::create_directories(dir);
  return dir;
}

/// Makes the clip once per process; its path. Written under a name of this process's own
/// and then renamed, so that test processes run side by side (ctest -j) never read a clip
/// another is still writing.
const std::string& toneMovie() {
  static const std::string path = [] {
    const std::string p = testDir() + "/tone_movie.mpg";
    const std::string part = p + "." + std::to_string(::getpid()) + ".part";
    std::string error;
    REQUIRE(test::writeMovie(part, test::MovieSpec{}, error));
    std::filesystem::rename(part, p);
    return p;
  }();
  return path;
}

/// Zero crossings per second of channel 0 over [from, to) seconds of `a`.
double crossingsPerSecond(const formats::AudioData& a, double from, double to) {
  const auto first = static_cast<std::size_t>(from * a.sampleRate);
  const auto last = static_cast<std::size_t>(to * a.sampleRate);
  int crossings = 0;
  for (std::size_t i = first + 1; i < last; ++i) {
    const int prev = a.samples[(i - 1) * static_cast<std::size_t>(a.channels)];
    const int cur = a.samples[i * static_cast<std::size_t>(a.channels)];
    if ((prev < 0) != (cur < 0)) ++crossings;
  }
  return crossings / (to - from);
}

}  // namespace

TEST_CASE("readMovieAudio: the audio stream of an MPEG-1 movie, in order", "[audio][movie]") {
  std::string bytes, error;
  REQUIRE(base::readFile(toneMovie(), bytes, error));
  formats::MovieAudio m;
  REQUIRE(formats::readMovieAudio(bytes, "tone_movie.mpg", m, error));
  CHECK(m.duration == Approx(1.0));  // the video's 25 frames at 25 fps
  CHECK(m.audio.sampleRate == 44100);
  CHECK(m.audio.channels == 1);
  CHECK(m.audio.duration() == Approx(1.0).margin(0.06));  // MP2 frames of 1152 samples
  // 440 Hz crosses zero 880 times a second, 880 Hz 1760 times (MP2's delay is ~0.01 s).
  CHECK(crossingsPerSecond(m.audio, 0.1, 0.4) == Approx(880.0).epsilon(0.03));
  CHECK(crossingsPerSecond(m.audio, 0.6, 0.9) == Approx(1760.0).epsilon(0.03));
}

TEST_CASE("readMovieAudio: a movie without sound, and what is no movie", "[audio][movie]") {
  std::string bytes, error;
  REQUIRE(base::readFile(std::string(GS_SOURCE_DIR) + "/assets/media/colours.mpg", bytes, error));
  formats::MovieAudio m;
  CHECK_FALSE(formats::readMovieAudio(bytes, "colours.mpg", m, error));
  CHECK(error.find("colours.mpg: no audio stream") != std::string::npos);
  CHECK(m.duration == Approx(1.0));  // still a movie: its duration is known
  CHECK(m.audio.samples.empty());
  // Truncated, or not a movie at all: an error naming it, never a crash.
  REQUIRE(base::readFile(toneMovie(), bytes, error));
  for (std::size_t n : {std::size_t{0}, std::size_t{100}, bytes.size() / 3}) {
    error.clear();
    if (!formats::readMovieAudio(bytes.substr(0, n), "cut.mpg", m, error))
      CHECK(error.find("cut.mpg") != std::string::npos);
  }
  CHECK_FALSE(formats::readMovieAudio("not a movie", "bad.mpg", m, error));
  CHECK(m.duration == -1.0);
}

TEST_CASE("Sound: a MovieTexture source plays its samples for the movie's duration",
          "[audio][sound][movie]") {
  test::SoundWorld w(R"(Transform { translation 0 0 -5.5 children
  Sound { source DEF M MovieTexture { url "tone_movie.mpg" startTime 1 } } })",
                     testDir() + "/world.wrl");
  toneMovie();
  w.frame(0.0);  // loads the movie: duration_changed 1
  CHECK(w.out.playing().empty());
  const vrml::Node& movie = *w.scene->rootNodes[0]->mfnode("children")[0]->sfnode("source");
  REQUIRE(w.model->media(movie));
  CHECK(w.model->media(movie)->duration == Approx(1.0));
  w.frame(1.0);
  REQUIRE(w.out.playing().size() == 1);
  const audio::Voice& v = w.out.playing()[0];
  CHECK(v.offset == Approx(0.0));
  CHECK(v.gain == Approx(0.316228));  // 5.5 m from the default spheres: -10 dB
  CHECK(v.pitch == 1.0f);
  REQUIRE(v.clip);
  CHECK(v.clip->sampleRate == 44100);
  CHECK(crossingsPerSecond(*v.clip, 0.1, 0.4) == Approx(880.0).epsilon(0.03));
  w.frame(1.75);
  REQUIRE(w.out.playing().size() == 1);
  CHECK(w.out.playing()[0].offset == Approx(0.75));
  w.frame(2.01);  // past startTime + duration: the movie stopped, and its sound
  CHECK(w.out.playing().empty());
  CHECK_FALSE(w.model->media(movie)->active);
  CHECK(w.sounds.diagnostics().items.empty());
}

TEST_CASE("Sound: a MovieTexture's speed is the pitch; backwards it is silent",
          "[audio][sound][movie]") {
  test::SoundWorld w(R"(Sound { source MovieTexture { url "tone_movie.mpg" speed 2 loop TRUE } }
Sound { source MovieTexture { url "tone_movie.mpg" speed -1 loop TRUE } }
Sound { source MovieTexture { url ")" +
                         std::string(GS_SOURCE_DIR) + R"(/assets/media/colours.mpg" loop TRUE } })",
                     testDir() + "/world.wrl");
  toneMovie();
  w.frame(0.0);
  w.frame(10.2);  // speed 2 from 0: 0.4 s into a 0.5 s cycle
  REQUIRE(w.out.playing().size() == 1);
  CHECK(w.out.playing()[0].pitch == 2.0f);
  CHECK(w.out.playing()[0].loop);
  CHECK(w.out.playing()[0].offset == Approx(0.4));
  REQUIRE(w.sounds.heard().size() == 3);
  CHECK_FALSE(w.sounds.heard()[1].playing);  // speed -1
  CHECK_FALSE(w.sounds.heard()[2].playing);  // a movie without sound
  REQUIRE(w.sounds.diagnostics().items.size() == 1);
  CHECK(w.sounds.diagnostics().items[0].message.find("colours.mpg: no audio stream") !=
        std::string::npos);
}
