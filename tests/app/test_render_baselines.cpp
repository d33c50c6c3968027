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
  const char* time = nullptr;      // --time, for animated worlds
  const char* loadTime = nullptr;  // --load-time, for what runs from the load (particles)
};

const RenderCase kCases[] = {
    {"welcome", "assets/worlds/welcome.wrl", false},
    {"features", "assets/worlds/features.wrl", false},
    {"media_background", "assets/worlds/media/background.wrl", false},
    {"media_textures", "assets/worlds/media/textures.wrl", false},
    {"media_texture_transform", "assets/worlds/media/texture_transform.wrl", false},
    {"text", "assets/worlds/text.wrl", false},
    {"castle_specular_demo", "vrml/castle/lights_materials/specular_demo.wrl", true},
    {"castle_transparent_materials", "vrml/castle/lights_materials/transparent_materials.wrl",
     true},
    {"castle_directional_light_scope", "vrml/castle/lights_materials/directional_light_scope.wrl",
     true},
    {"castle_light_radius", "vrml/castle/lights_materials/light_radius.wrl", true},
    {"castle_cones", "vrml/castle/vrml_2/cones.wrl", true},
    {"castle_backface_culling", "vrml/castle/vrml_2/backface_culling.wrl", true},
    {"castle_proto_nested", "vrml/castle/prototypes/proto_nested.wrl", true},
    {"castle_proto_nested_expand", "vrml/castle/prototypes/proto_nested_expand.wrl", true},
    {"castle_indexed_line_set", "vrml/castle/vrml_2/indexed_line_set.wrl", true},
    {"castle_creaseangle", "vrml/castle/vrml_engine_doc_simple_examples/creaseangle.wrl", true},
    {"castle_teapot", "vrml/castle/vrml_2/teapot.wrl", true},
    {"kicad_cp_elec_5x3", "vrml/kicad/Capacitor_SMD__CP_Elec_5x3.wrl", true},
    // glTF models (castle's demo models), framed whole where they have no camera.
    {"gltf_castle", "gltf/castle/castle/castle.gltf", true},
    {"gltf_cat",
     "gltf/castle/bump_mapping/tangents/cat-16c3444c8d1440fc97fdf10f60ec58b0/scene.gltf", true},
    {"gltf_fox_t1", "gltf/castle/animation/gltf_skinned_animation/fox_from_khronos/Fox.gltf", true,
     "1"},
    {"gltf_punctual_lights", "gltf/castle/gltf/punctual_lights/test_lights.gltf", true},
    {"gltf_lines", "gltf/castle/gltf/lines/lines.gltf", true},
    {"gltf_baked_lighting",
     "gltf/castle/blender/baking_lighting/sample_level_using_baked_texture.gltf", true},
    {"gltf_vertex_paint", "gltf/castle/blender/per_vertex_colors/vertex_paint.glb", true},
    {"gltf_teapot_clearcoat", "gltf/castle/x3d/inline_geometry/utah_teapot_original/scene.gltf",
     true},
    {"gltf_camera_animation_t1", "gltf/castle/gltf/camera_animation/camera_animation.glb", true,
     "1"},
    // Skins (CPU skinning by the Skin node) and morph weights animation, at t = 1 s: the
    // poses castle-model-viewer --screenshot 1 shows.
    {"gltf_skinned_anim_t1", "gltf/castle/animation/blender_skinned_animation/skinned_anim.glb",
     true, "1"},
    {"gltf_bunny_t1",
     "gltf/castle/animation/gltf_skinned_animation/animals_from_quaternius/Bunny.gltf", true, "1"},
    {"gltf_monkey_morph_t1", "gltf/castle/gltf/morph_targets/monkey_morph.glb", true, "1"},
    // The rest of the corpus's glTF scenes: a camera-less mesh (castle's framing) and
    // Blender's custom properties (extras) beside a camera and a required point light.
    {"gltf_torus", "gltf/castle/x3d/inline_geometry/torus.glb", true},
    {"gltf_custom_properties",
     "gltf/castle/blender/custom_properties/blender_custom_properties.gltf", true},
    {"gltf_custom_properties_2",
     "gltf/castle/blender/custom_properties_2/blender_custom_properties.gltf", true},
    // X3D 4.1 EnvironmentLight: image-based light on PhysicalMaterial (docs/rendering.md).
    {"environment_light", "assets/worlds/environment_light.x3dv", false},
    // X3D VolumeData and IsoSurfaceVolumeData drawn as QNV splats (docs/x3d.md).
    {"volume_data", "assets/worlds/volume_data.x3dv", false},
    // X3D Layering (docs/x3d.md): a farther layer over layer 0, a Viewport's clipBoundary
    // cutting an animated cone in half at t = 1 s.
    {"layers_t1", "assets/worlds/layers.x3dv", false, "1"},
    // X3D Layout (docs/x3d.md): a LayoutLayer's 200x60-pixel panel with ScreenFontStyle text
    // 10 pixels from the top left corner, a ScreenGroup's 16-pixel square on a box.
    {"layout", "assets/worlds/layout.x3dv", false},
    // X3D particle systems (docs/x3d.md) 1.5 s after the load: SPRITE with a colour ramp and
    // wind, LINE falling and bouncing, POINT in a volume, QUAD from a surface, GEOMETRY.
    {"particles_t1.5", "assets/worlds/particles.x3dv", false, "1.5", "0"},
    // X3D Geospatial (docs/x3d.md): X_ITE's YUp test, a GD globe (GeoElevationGrid), UTM
    // grids in both orders, a GeoTransform, seen from a GeoViewpoint 10,000 km up in a
    // rotateYUp GeoOrigin's frame.
    {"geospatial_yup", "x3d/create3000/Tests/Components/Geospatial/YUp.x3d", true},
    // X3D Texture projection (docs/x3d.md): a global perspective projector, a scoped parallel
    // one, a lit and an unlit shape (1.4% from X_ITE's picture); X_ITE's apple thrown into a
    // corner (0.5% from X_ITE's).
    {"texture_projection", "assets/worlds/texture_projection.x3dv", false},
    // NURBS swept surface (docs/x3d.md): a closed NurbsCurve2D swept along a closed cubic
    // NurbsCurve, 1.1% from X_ITE's picture.
    {"nurbs_swept_b", "x3d/create3000/Tests/Components/NURBS/B.x3d", true},
    {"texture_projector_apple", "x3d/create3000/Tests/Components/TextureProjection/apple.x3d",
     true},
    // X3D volume render styles (docs/x3d.md "Volume render styles: a ray caster"): the nine
    // styles on a 32^3 ball, each volume turned (X_ITE shades turned volumes in the wrong
    // frame: unturned, each style is 6-15% from X_ITE's picture, docs/x3d.md).
    {"volume_styles", "assets/worlds/volume_styles.x3dv", false},
};

void checkAgainstBaseline(const RenderCase& c) {
  const std::string part = std::string(c.world).substr(0, std::string(c.world).find('/'));
  if (c.corpus && !gs::test::haveCorpus(part)) return;
  const fs::path world =
      c.corpus ? gs::test::corpusDir() / c.world : gs::test::sourceDir() / c.world;
  std::vector<std::string> args = {"--size", "300x300", world.string()};
  if (c.time != nullptr) args.insert(args.end(), {"--time", c.time});
  if (c.loadTime != nullptr) args.insert(args.end(), {"--load-time", c.loadTime});
  gs::test::checkBaseline(c.name, args);
}

}  // namespace

TEST_CASE("snapshots match their baselines", "[app][render][baseline]") {
  for (const auto& c : kCases) {
    SECTION(c.name) {
      checkAgainstBaseline(c);
    }
  }
}
