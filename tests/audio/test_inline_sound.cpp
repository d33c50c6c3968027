// Sounds inside Inline worlds (ISO/IEC 14772-1:1997 6.25, 6.42) are heard: SoundScene
// walks the worlds its InlineQuery gives (in the window, the renderer's loaded Inlines),
// in the Inline's coordinate system, their clip URLs relative to the inlined world.
#include "encodings/parser.hpp"
#include "sound_world.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

using namespace gs;

TEST_CASE("Sound: an AudioClip inside an Inline world is heard", "[audio][sound][inline]") {
  // dir/main.wrl inlines dir/sub/inner.wrl, whose clip "tone.wav" is dir/sub/tone.wav.
  const std::string dir = std::string(GS_BINARY_DIR) + "/test_audio_inline";
  std::filesystem::create_directories(dir + "/sub");
  std::filesystem::copy_file(std::string(GS_SOURCE_DIR) + "/assets/media/tone.wav",
                             dir + "/sub/tone.wav",
                             std::filesystem::copy_options::overwrite_existing);
  std::ofstream(dir + "/sub/inner.wrl")
      << "#VRML V2.0 utf8\nTransform { translation 0 0 -0.5 children Sound {\n"
         "  source AudioClip { url \"tone.wav\" startTime 1 } } }\n"
         "Inline { url \"inner.wrl\" }\n";
  test::SoundWorld w(R"(Transform { translation 0 0 -5 children Inline { url "sub/inner.wrl" } })",
                     dir + "/main.wrl");
  // One world per URL, as the renderer's Inline loader keeps them; inner.wrl also inlines
  // itself, which is walked once.
  std::shared_ptr<const vrml::Scene> inner;
  w.inlines = [&](const vrml::Node&) -> std::shared_ptr<const vrml::Scene> {
    if (!inner) {
      vrml::Scene scene = vrml::loadVrmlFile(dir + "/sub/inner.wrl");
      scene.url = dir + "/sub/inner.wrl";  // as the renderer's Inline loader sets it
      inner = std::make_shared<const vrml::Scene>(std::move(scene));
      w.model->addInlineScene(inner);  // as session::WorldRuntimes::addInlines does
    }
    return inner;
  };
  w.frame(0.0);
  CHECK(w.sounds.diagnostics().items.empty());
  REQUIRE(w.sounds.heard().size() == 1);
  CHECK(w.out.playing().empty());
  w.frame(1.25);
  REQUIRE(w.out.playing().size() == 1);
  const audio::Voice& v = w.out.playing()[0];
  CHECK(v.offset == Approx(0.25));
  CHECK(v.gain == Approx(0.316228));  // 5.5 m away through both transforms: -10 dB
  CHECK(v.position.z == Approx(-5.5f));
  REQUIRE(v.clip);
  CHECK(v.clip->duration() == Approx(0.5));
  w.frame(1.6);
  CHECK(w.out.playing().empty());

  // Without the query (the main scene only) the Inline's Sound is not found.
  test::SoundWorld plain(R"(Inline { url "sub/inner.wrl" })", dir + "/main.wrl");
  plain.frame(1.25);
  CHECK(plain.sounds.heard().empty());
}
