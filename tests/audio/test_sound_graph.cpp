// X3D 4 audio graph worlds (clause 16) through the execution model, SoundScene and the null
// output, frame by frame as the window moves them: what the sources' time fields start,
// pause and stop is what is streamed.
#include "audio/acoustics.hpp"
#include "audio/audio_output.hpp"
#include "audio/sound_scene.hpp"
#include "encodings/parser.hpp"
#include "runtime/execution_model.hpp"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>

using namespace gs;

namespace {

struct GraphWorld {
  std::shared_ptr<vrml::Scene> scene;
  std::unique_ptr<runtime::ExecutionModel> model;
  audio::SoundScene sounds;
  audio::NullAudioOutput out;

  explicit GraphWorld(const std::string& body)
      : scene(std::make_shared<vrml::Scene>(
            vrml::parseVrml("#X3D V4.0 utf8\nPROFILE Full\n" + body,
                            std::string(GS_SOURCE_DIR) + "/assets/media/graph.x3dv"))),
        model(std::make_unique<runtime::ExecutionModel>(scene, 0.0)),
        sounds(scene, nullptr) {}

  /// One frame at `time`, heard from the origin looking down -Z.
  void frame(double time) {
    model->advanceTo(time);
    sounds.update(
        glm::mat4(1.0f), time,
        [this](const vrml::Node& n) -> std::optional<audio::ClipTime> {
          const auto m = model->media(n);
          if (!m) return std::nullopt;
          return audio::ClipTime{m->active, m->mediaTime};
        },
        out);
    sounds.waitForClips();
    for (const auto& [node, seconds] : sounds.takeDurations())
      model->setMediaDuration(*node, seconds);
    model->sendDrawnOutputs(sounds.takeOutputs());  // as app::WorldSounds sends them
  }
  /// Frames from `from` to `to` every 1/50 s, the stream of the last `seconds` kept.
  void play(double from, double to) {
    for (double t = from; t <= to + 1e-9; t += 0.02) frame(t);
  }
  /// The node DEFed `name` (anywhere below the root nodes).
  vrml::Node& def(const std::string& name) {
    vrml::Node* found = nullptr;
    std::function<void(const vrml::NodePtr&)> visit = [&](const vrml::NodePtr& n) {
      if (!n || found) return;
      if (n->defName == name) found = n.get();
      for (std::size_t i = 0; i < n->fieldCount() && !found; ++i) {
        const vrml::FieldValue& v = n->fieldAt(i);
        if (v.type() == vrml::FieldType::SFNode) visit(v.get<vrml::FieldType::SFNode>());
        if (v.type() == vrml::FieldType::MFNode)
          for (const vrml::NodePtr& c : v.get<vrml::FieldType::MFNode>()) visit(c);
      }
    };
    for (const vrml::NodePtr& n : scene->rootNodes) visit(n);
    REQUIRE(found != nullptr);
    return *found;
  }
  /// Sends `value` to `field` of the node DEFed `name`, processed at the next frame.
  void send(const std::string& name, const std::string& field, vrml::FieldValue value) {
    vrml::Node& n = def(name);
    REQUIRE(model->postEvent(n, n.type().findField(field), std::move(value)));
  }
  float peakOfLast(std::size_t frames, int channel) const {
    const std::vector<float>& s = out.streamed();
    float m = 0.0f;
    const std::size_t n = s.size() / 2;
    for (std::size_t i = n > frames ? n - frames : 0; i < n; ++i)
      m = std::max(m, std::fabs(s[2 * i + static_cast<std::size_t>(channel)]));
    return m;
  }
};

}  // namespace

TEST_CASE("Sound graph: an oscillator through a Gain to the AudioDestination", "[audio][graph]") {
  GraphWorld w(R"(AudioDestination { children [
    DEF G Gain { gain 0.5 children [ DEF O OscillatorSource { frequency 441 startTime 1 } ] } ] })");
  w.play(0.0, 0.5);
  CHECK(w.out.streamed().size() == 2 * 22050);  // half a second rendered
  CHECK(w.peakOfLast(22050, 0) == 0.0f);        // before startTime: silent
  REQUIRE(w.model->media(w.def("O")));
  CHECK_FALSE(w.model->media(w.def("O"))->active);
  w.play(0.52, 1.5);
  CHECK(w.model->media(w.def("O"))->active);
  // X_ITE's default wave (PeriodicWave's SQUARE), peak 1, through gain 0.5.
  CHECK(w.peakOfLast(4410, 0) == Approx(0.5f).margin(0.01));
  CHECK(w.peakOfLast(4410, 1) == Approx(0.5f).margin(0.01));
  CHECK(w.def("O").get<vrml::FieldType::SFTime>("elapsedTime", -1.0) == Approx(0.5).margin(0.021));
  // The Gain node's gain event is heard from the next frame on.
  w.send("G", "gain", vrml::FieldValue::make<vrml::FieldType::SFFloat>(0.25f));
  w.play(1.52, 1.6);
  CHECK(w.peakOfLast(2205, 0) == Approx(0.25f).margin(0.01));
}

TEST_CASE("Sound graph: a DynamicsCompressor sends its reduction", "[audio][graph]") {
  GraphWorld w(R"(AudioDestination { children [ DEF C DynamicsCompressor { children [
      DEF O OscillatorSource { frequency 441 stopTime 2 } ] } ] }
    DEF G Gain { gain 1 }
    ROUTE C.reduction TO G.set_gain)");
  w.frame(0.0);
  CHECK(w.sounds.takeOutputs().empty());  // nothing rendered yet: no event
  w.play(0.02, 1.0);
  // A full-scale tone over the default -24 dB threshold at ratio 12: pulled down by about
  // 20 dB (Web Audio's curve); the event reached the Gain through the ROUTE.
  const float held = w.def("C").get<vrml::FieldType::SFFloat>("reduction", 0.0f);
  CHECK(held < -10.0f);
  CHECK(held > -30.0f);
  CHECK(w.def("G").get<vrml::FieldType::SFFloat>("gain", 1.0f) == held);
  CHECK(w.peakOfLast(2205, 0) < 0.5f);
  // Silence after stopTime: the reduction is released (0.25 s) back towards 0 dB.
  w.play(2.0, 3.5);
  CHECK(w.def("C").get<vrml::FieldType::SFFloat>("reduction", -99.0f) > -0.5f);
  CHECK(w.def("G").get<vrml::FieldType::SFFloat>("gain", -99.0f) > -0.5f);
}

TEST_CASE("Sound graph: pauseTime, resumeTime and stopTime", "[audio][graph]") {
  GraphWorld w(R"(AudioDestination { children [ DEF O OscillatorSource { stopTime 3 } ] })");
  w.play(0.0, 0.98);
  CHECK(w.peakOfLast(2205, 0) > 0.9f);
  w.send("O", "pauseTime", vrml::FieldValue::make<vrml::FieldType::SFTime>(1.0));
  w.play(1.0, 1.5);
  CHECK(w.def("O").get<vrml::FieldType::SFBool>("isPaused", false));
  CHECK(w.peakOfLast(4410, 0) == 0.0f);
  const double elapsedAtPause = w.def("O").get<vrml::FieldType::SFTime>("elapsedTime", -1.0);
  CHECK(elapsedAtPause == Approx(1.0).margin(0.021));
  w.send("O", "resumeTime", vrml::FieldValue::make<vrml::FieldType::SFTime>(2.0));
  w.play(2.0, 2.5);
  CHECK_FALSE(w.def("O").get<vrml::FieldType::SFBool>("isPaused", true));
  CHECK(w.peakOfLast(2205, 0) > 0.9f);
  // Paused seconds are not counted.
  CHECK(w.def("O").get<vrml::FieldType::SFTime>("elapsedTime", -1.0) == Approx(1.5).margin(0.03));
  w.play(2.52, 3.5);
  CHECK_FALSE(w.def("O").get<vrml::FieldType::SFBool>("isActive", true));
  CHECK(w.peakOfLast(4410, 0) == 0.0f);
}

TEST_CASE("Sound graph: a BufferAudioSource's buffer plays once, for its duration",
          "[audio][graph]") {
  // 3000 frames at 3000 Hz, channel-major stereo: one second, left 0.25, right -0.5.
  std::string buffer;
  for (int i = 0; i < 3000; ++i) buffer += "0.25 ";
  for (int i = 0; i < 3000; ++i) buffer += "-0.5 ";
  GraphWorld w(
      "AudioDestination { children [ DEF B BufferAudioSource { load FALSE "
      "numberOfChannels 2 sampleRate 3000 startTime 0.5 buffer [ " +
      buffer + "] } ] }");
  w.play(0.0, 1.0);
  CHECK(w.model->media(w.def("B"))->active);
  CHECK(w.peakOfLast(4410, 0) == Approx(0.25f));
  CHECK(w.peakOfLast(4410, 1) == Approx(0.5f));
  w.play(1.02, 1.8);
  CHECK(w.model->media(w.def("B"))->duration == Approx(1.0));
  w.play(1.82, 2.0);  // past startTime + 1 s: stopped
  CHECK_FALSE(w.model->media(w.def("B"))->active);
  CHECK(w.peakOfLast(4410, 0) == 0.0f);
}

TEST_CASE("Sound graph: a SpatialSound under a Transform, an AudioClip in a filter",
          "[audio][graph]") {
  // tone.wav: 0.5 s of 440 Hz at 8 kHz, peak 0.125. Placed 2 m to the right: heard in the
  // right ear only, at the inverse model's 1/2.
  GraphWorld w(R"(Transform { translation 2 0 0 children [
    SpatialSound { children [ BiquadFilter { type "HIGHPASS" frequency 20 children [
      DEF C AudioClip { url "tone.wav" loop TRUE } ] } ] } ] })");
  w.play(0.0, 0.5);
  REQUIRE(w.model->media(w.def("C")));
  CHECK(w.model->media(w.def("C"))->active);
  CHECK(w.peakOfLast(4410, 0) < 1e-4f);
  CHECK(w.peakOfLast(4410, 1) == Approx(0.0625f).margin(0.003));
}

namespace {

/// An output whose "microphone" recorded a constant 0.25 since the last call (as much as
/// asked for), and that keeps what is streamed to it.
class ConstantMicrophone final : public audio::AudioOutput {
 public:
  bool isNull() const override { return true; }
  std::string name() const override { return "constant microphone"; }
  void update(const std::vector<audio::Voice>&) override {}
  std::size_t maxVoices() const override { return 32; }
  void stream(const std::vector<float>& stereo) override {
    streamed.insert(streamed.end(), stereo.begin(), stereo.end());
  }
  std::size_t capture(std::vector<float>& mono, std::size_t maxFrames, std::string&) override {
    const std::size_t n = std::min<std::size_t>(maxFrames, 882);  // 1/50 s
    mono.insert(mono.end(), n, 0.25f);
    ++captures;
    return n;
  }
  std::vector<float> streamed;
  int captures = 0;
};

}  // namespace

TEST_CASE("Sound graph: a MicrophoneSource plays what the capture device recorded",
          "[audio][graph]") {
  GraphWorld w(R"(AudioDestination { children [
    Gain { gain 2 children [ DEF MIC MicrophoneSource { stopTime 1 } ] } ] })");
  ConstantMicrophone mic;
  const auto frameWith = [&](double t) {
    w.model->advanceTo(t);
    w.sounds.update(
        glm::mat4(1.0f), t,
        [&](const vrml::Node& n) -> std::optional<audio::ClipTime> {
          const auto m = w.model->media(n);
          if (!m) return std::nullopt;
          return audio::ClipTime{m->active, m->mediaTime};
        },
        mic);
  };
  for (double t = 0.0; t <= 0.5; t += 0.02) frameWith(t);
  CHECK(mic.captures > 20);
  REQUIRE(mic.streamed.size() > 2 * 4410);
  // Past the first block: 0.25 times the Gain's 2, in both ears.
  const std::size_t at = mic.streamed.size() - 2 * 1000;
  CHECK(mic.streamed[at] == Approx(0.5f));
  CHECK(mic.streamed[at + 1] == Approx(0.5f));
  // Stopped: nothing is captured any more, and nothing heard.
  const int before = mic.captures;
  for (double t = 1.0; t <= 1.2; t += 0.02) frameWith(t);
  CHECK(mic.captures == before);
  CHECK(mic.streamed.back() == 0.0f);
  // The null output has no microphone: a warning, once, and silence.
  GraphWorld silent(R"(AudioDestination { children [ MicrophoneSource { } ] })");
  silent.play(0.0, 0.2);
  CHECK(silent.sounds.diagnostics().items.size() == 1);
  CHECK(silent.peakOfLast(4410, 0) == 0.0f);
}

TEST_CASE("Sound graph: acoustic surfaces between a SpatialSound and the listener",
          "[audio][graph][acoustics]") {
  // As above (the right ear hears 0.0625 from 2 m), with a 10 cm wall at x = 1: its two
  // faces on the path each keep `refraction` of the sound (X3D 4.0 12.4.1).
  const auto heard = [](const std::string& acoustics, const std::string& wallAt) {
    GraphWorld w("Transform { translation " + wallAt +
                 " children Shape { appearance Appearance { " + acoustics +
                 " } geometry Box { size 0.1 4 4 } } }\n" +
                 R"(Transform { translation 2 0 0 children [
      SpatialSound { children [ AudioClip { url "tone.wav" loop TRUE } ] } ] })");
    w.play(0.0, 0.5);
    return w.peakOfLast(4410, 1);
  };
  CHECK(heard("", "1 0 0") == Approx(0.0625f).margin(0.003));  // no AcousticProperties
  CHECK(heard("acousticProperties AcousticProperties { refraction 0.5 }", "1 0 0") ==
        Approx(0.0625f * 0.25f).margin(0.001));
  CHECK(heard("acousticProperties AcousticProperties { refraction 0.5 }", "1 0 5") ==
        Approx(0.0625f).margin(0.003));  // beside the path
  CHECK(heard("acousticProperties AcousticProperties { refraction 0.5 }", "3 0 0") ==
        Approx(0.0625f).margin(0.003));  // behind the sound
  CHECK(heard("acousticProperties AcousticProperties { refraction 0.5 enabled FALSE }", "1 0 0") ==
        Approx(0.0625f).margin(0.003));
  CHECK(heard("acousticProperties AcousticProperties { absorption 1 }", "1 0 0") < 1e-6f);
}

TEST_CASE("acoustic surfaces: crossings of the segment, each keeping its refraction",
          "[audio][acoustics]") {
  const auto scene = vrml::parseVrml(R"(#X3D V4.0 utf8
PROFILE Full
Shape { appearance Appearance { acousticProperties AcousticProperties { refraction 0.3 } }
  geometry IndexedFaceSet { coord Coordinate { point [ -1 -1 0, 1 -1 0, 1 1 0, -1 1 0 ] }
                            coordIndex [ 0 1 2 3 -1 ] } }
Shape { geometry Box {} }
)",
                                     "quad.x3dv");
  REQUIRE(scene.rootNodes.size() == 2);
  audio::AcousticSurface quad;
  // Two metres up: the quad at z = 2.
  REQUIRE(audio::acousticSurfaceOf(*scene.rootNodes[0],
                                   glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 2)), quad));
  CHECK(quad.refraction == Approx(0.3f));
  audio::AcousticSurface none;
  CHECK_FALSE(audio::acousticSurfaceOf(*scene.rootNodes[1], glm::mat4(1.0f), none));
  audio::AcousticOcclusion o;
  o.setSurfaces({quad});
  CHECK(o.surfaceCount() == 1);
  CHECK(o.transmission({0, 0, 0}, {0, 0, 5}) == Approx(0.3f));
  CHECK(o.transmission({0, 0, 5}, {0.5f, 0.5f, -1}) == Approx(0.3f));  // either face
  CHECK(o.transmission({0, 0, 0}, {0, 0, 1.9f}) == 1.0f);              // stops short
  CHECK(o.transmission({3, 0, 0}, {3, 0, 5}) == 1.0f);                 // beside it
  o.setSurfaces({quad, quad});                                         // two surfaces in the way
  CHECK(o.transmission({0, 0, 0}, {0, 0, 5}) == Approx(0.09f));
  o.setSurfaces({});
  CHECK(o.transmission({0, 0, 0}, {0, 0, 5}) == 1.0f);
}
