// Render tests: the real binary renders worlds with --snapshot at a fixed size; each image
// is compared with a baseline PNG in tests/render/baselines under the metric of
// docs/rendering-tests.md (render::compareImages): a pixel differs when any RGB channel
// differs by more than 16 of 255; a test passes when at most kMaxFractionDiffering of the
// pixels differ. A missing baseline writes the rendered image to the build folder and
// fails, so that a new baseline is made only by looking at it and copying it in.
#include "baseline.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

namespace fs = std::filesystem;

namespace {

struct RenderCase {
  const char* name;   // baseline file stem
  const char* world;  // relative to the corpus (corpus = true) or the source folder
  bool corpus;
};

const RenderCase kCases[] = {
    {"welcome", "assets/worlds/welcome.wrl", false},
    {"features", "assets/worlds/features.wrl", false},
    {"media_background", "assets/worlds/media/background.wrl", false},
    {"media_textures", "assets/worlds/media/textures.wrl", false},
    {"media_texture_transform", "assets/worlds/media/texture_transform.wrl", false},
    {"castle_specular_demo", "vrml/castle/lights_materials/specular_demo.wrl", true},
    {"castle_transparent_materials", "vrml/castle/lights_materials/transparent_materials.wrl",
     true},
    {"castle_directional_light_scope", "vrml/castle/lights_materials/directional_light_scope.wrl",
     true},
    {"castle_light_radius", "vrml/castle/lights_materials/light_radius.wrl", true},
    {"castle_cones", "vrml/castle/vrml_2/cones.wrl", true},
    {"castle_backface_culling", "vrml/castle/vrml_2/backface_culling.wrl", true},
    {"castle_proto_nested", "vrml/castle/prototypes/proto_nested.wrl", true},
    {"castle_indexed_line_set", "vrml/castle/vrml_2/indexed_line_set.wrl", true},
    {"castle_creaseangle", "vrml/castle/vrml_engine_doc_simple_examples/creaseangle.wrl", true},
    {"castle_teapot", "vrml/castle/vrml_2/teapot.wrl", true},
    {"kicad_cp_elec_5x3", "vrml/kicad/Capacitor_SMD__CP_Elec_5x3.wrl", true},
};

void checkAgainstBaseline(const RenderCase& c) {
  if (c.corpus && !gs::test::haveCorpus("vrml")) return;
  const fs::path world =
      c.corpus ? gs::test::corpusDir() / c.world : gs::test::sourceDir() / c.world;
  gs::test::checkBaseline(c.name, {"--size", "300x300", world.string()});
}

}  // namespace

TEST_CASE("snapshots match their baselines", "[app][render][baseline]") {
  for (const auto& c : kCases) {
    SECTION(c.name) {
      checkAgainstBaseline(c);
    }
  }
}
