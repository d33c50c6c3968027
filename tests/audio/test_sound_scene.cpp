// SoundScene with the execution model and the null output: an AudioClip's time rules
// decide what plays, at which offset, and the headless output is the null one.
#include "sound_world.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>

#include <fcntl.h>
#include <unistd.h>

#include "test_support.hpp"

using namespace gs;

using World = test::SoundWorld;

TEST_CASE("Sound: a WAV clip plays through the null output for its duration", "[audio][sound]") {
  World w(R"(Transform { translation 0 0 -5.5 children
  Sound { source DEF C AudioClip { url "tone.wav" startTime 1 } } })");
  w.frame(0.0);  // loads the clip: duration_changed 0.5
  CHECK(w.out.playing().empty());
  REQUIRE(w.model->media(*w.scene->rootNodes[0]->mfnode("children")[0]->sfnode("source")));
  w.frame(1.0);
  REQUIRE(w.out.playing().size() == 1);
  const audio::Voice& v = w.out.playing()[0];
  CHECK(v.offset == Approx(0.0));
  CHECK(v.gain == Approx(0.316228));  // 5.5 m from the default spheres: -10 dB
  CHECK(v.position.z == Approx(-5.5f));
  REQUIRE(v.clip);
  CHECK(v.clip->duration() == Approx(0.5));
  w.frame(1.25);
  REQUIRE(w.out.playing().size() == 1);
  CHECK(w.out.playing()[0].offset == Approx(0.25));
  w.frame(1.6);  // past startTime + duration: stopped
  CHECK(w.out.playing().empty());
  CHECK(w.sounds.heard().size() == 1);
  CHECK_FALSE(w.sounds.heard()[0].playing);
}

TEST_CASE("Sound: a looping clip, a listener out of range, a missing file", "[audio][sound]") {
  World w(R"(Sound { maxFront 2 maxBack 2 source AudioClip { url "tone.wav" loop TRUE } }
Sound { source AudioClip { url "missing.wav" loop TRUE } })");
  w.frame(0.0);
  w.frame(10.2);  // looping since 0: 0.2 s into the 21st cycle
  REQUIRE(w.out.playing().size() == 1);
  CHECK(w.out.playing()[0].offset == Approx(0.2));
  CHECK(w.out.playing()[0].loop);
  w.frame(10.3, {0.0f, 0.0f, 3.0f});  // beyond maxFront: silent, not played
  CHECK(w.out.playing().empty());
  REQUIRE(w.sounds.diagnostics().items.size() == 1);
  CHECK(w.sounds.diagnostics().items[0].message.find("missing.wav") != std::string::npos);
}

TEST_CASE("Sound: without an audio device the output is the null one", "[audio][sound]") {
  std::string note;
  auto off = audio::openAudioOutput(false, note);
  REQUIRE(off);
  CHECK(off->isNull());
  // No backend OpenAL Soft knows: the device cannot open, which is a note, not an error.
  ::setenv("ALSOFT_DRIVERS", "no-such-backend", 1);
  auto none = audio::openAudioOutput(true, note);
  REQUIRE(none);
  CHECK(none->isNull());
  CHECK(note.find("no audio device") != std::string::npos);
  none->update({});
}

TEST_CASE("Sound: opening the device prints nothing but the program's own note", "[audio][sound]") {
  // Issue 42, friction 5: without a sound card, OpenAL Soft and ALSA printed about ten
  // lines at every window launch before the one-line "no audio device".
  ::unsetenv("ALSOFT_DRIVERS");  // every backend OpenAL Soft tries
  std::fflush(stderr);
  char path[] = "/tmp/gs_audio_stderr_XXXXXX";
  const int file = ::mkstemp(path);
  REQUIRE(file >= 0);
  const int saved = ::dup(2);
  ::dup2(file, 2);
  std::string note;
  {
    auto output = audio::openAudioOutput(true, note);
    REQUIRE(output);
  }
  std::fflush(stderr);
  ::dup2(saved, 2);
  ::close(saved);
  const off_t printed = ::lseek(file, 0, SEEK_END);
  ::close(file);
  std::string text = gs::test::readBytes(path);
  ::unlink(path);
  INFO("stderr while opening: " << text);
  CHECK(printed == 0);
}
