// The X3D Script natives that describe the browser and a scene (ISO/IEC 19777-1 clause 7.2:
// Browser.supportedProfiles, supportedComponents, getProfile, getComponent,
// getRenderingProperty; clause 7.4: X3DScene.profile, components, units), installed on
// __gsX3D by installX3DHooks. The prelude (script_prelude_x3d.cpp) turns their arrays into
// ProfileInfo, ComponentInfo and UnitInfo objects.
#include "script_ecmascript_internal.hpp"
#include "vrml/scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <string>
#include <string_view>
#include <utility>

namespace gs::runtime::es {

namespace {

struct ComponentLevel {
  std::string_view name;
  int level;
};

struct ComponentEntry {
  std::string_view name;
  std::string_view title;
  int level;  // the highest level of ISO/IEC 19775-1:2023 (X3D 4.0) this browser supports
};

// X3D 4.0's components (ISO/IEC 19775-1:2023, clauses 7 to 42, each component's table of
// levels), with the titles X_ITE 15 gives them, and the X3D 4.1 draft's levels and
// components that the node model holds. Every node type of the node model
// (vrml/node_model.hpp) is in its component at or below the level given here (a test
// checks it).
constexpr ComponentEntry kComponents[] = {
    {"CADGeometry", "CAD geometry", 2},
    {"Core", "Core", 2},
    {"CubeMapTexturing", "Cube map environmental texturing", 3},
    {"DIS", "Distributed interactive simulation", 2},
    {"EnvironmentalEffects", "Environmental effects", 4},
    {"EnvironmentalSensor", "Environmental sensor", 3},
    {"EventUtilities", "Event utilities", 1},
    {"Followers", "Followers", 1},
    {"GaussianSplats", "Gaussian splats", 1},  // X_ITE's experimental node (docs/splats.md)
    {"Geometry2D", "Geometry2D", 2},
    {"Geometry3D", "Geometry3D", 4},
    {"Geospatial", "Geospatial", 2},
    {"Grouping", "Grouping", 3},
    {"HAnim", "Humanoid animation (HAnim)", 3},
    {"Interpolation", "Interpolation", 5},
    {"KeyDeviceSensor", "Key device sensor", 2},
    {"Layering", "Layering", 1},
    {"Layout", "Layout", 2},
    {"Lighting", "Lighting", 4},  // X3D 4.1's level 4: EnvironmentLight
    {"Navigation", "Navigation", 3},
    {"Networking", "Networking", 4},
    {"NURBS", "NURBS", 4},
    {"ParticleSystems", "Particle systems", 3},
    {"Picking", "Picking", 3},
    {"PointingDeviceSensor", "Pointing device sensor", 1},
    {"Rendering", "Rendering", 5},
    {"RigidBodyPhysics", "Rigid body physics", 2},
    {"Scripting", "Scripting", 1},
    {"Shaders", "Programmable shaders", 1},
    {"Shape", "Shape", 5},
    {"Sound", "Sound", 3},
    {"Text", "Text", 2},
    {"TextureProjection", "Texture projection", 2},
    {"Texturing", "Texturing", 4},
    {"Texturing3D", "Texturing3D", 2},
    {"Time", "Time", 2},
    {"VolumeRendering", "Volume rendering", 4},
};

struct ProfileEntry {
  std::string_view name;
  std::string_view title;
  std::span<const ComponentLevel> components;
  bool full = false;  // every component at its highest level (the Full profile)
};

// The profiles of ISO/IEC 19775-1:2023 (annexes A to F, H and I: each profile's table of
// component levels).
constexpr ComponentLevel kCore[] = {{"Core", 1}};
constexpr ComponentLevel kInterchange[] = {{"Core", 1},          {"EnvironmentalEffects", 1},
                                           {"Geometry3D", 2},    {"Grouping", 1},
                                           {"Interpolation", 2}, {"Lighting", 1},
                                           {"Navigation", 1},    {"Networking", 1},
                                           {"Rendering", 3},     {"Shape", 1},
                                           {"Texturing", 2},     {"Time", 1}};
constexpr ComponentLevel kInteractive[] = {{"Core", 1},
                                           {"EnvironmentalEffects", 1},
                                           {"EnvironmentalSensor", 1},
                                           {"EventUtilities", 1},
                                           {"Geometry3D", 3},
                                           {"Grouping", 2},
                                           {"Interpolation", 2},
                                           {"KeyDeviceSensor", 1},
                                           {"Lighting", 2},
                                           {"Navigation", 1},
                                           {"Networking", 2},
                                           {"PointingDeviceSensor", 1},
                                           {"Rendering", 3},
                                           {"Shape", 1},
                                           {"Texturing", 2},
                                           {"Time", 1}};
constexpr ComponentLevel kMpeg4Interactive[] = {{"Core", 1},
                                                {"EnvironmentalEffects", 1},
                                                {"EnvironmentalSensor", 1},
                                                {"Geometry3D", 2},
                                                {"Grouping", 2},
                                                {"Interpolation", 2},
                                                {"Lighting", 2},
                                                {"Navigation", 1},
                                                {"Networking", 2},
                                                {"PointingDeviceSensor", 1},
                                                {"Rendering", 1},
                                                {"Shape", 1},
                                                {"Texturing", 1},
                                                {"Time", 1}};
constexpr ComponentLevel kImmersive[] = {{"Core", 2},
                                         {"EnvironmentalEffects", 2},
                                         {"EnvironmentalSensor", 2},
                                         {"EventUtilities", 1},
                                         {"Geometry2D", 1},
                                         {"Geometry3D", 4},
                                         {"Grouping", 2},
                                         {"Interpolation", 2},
                                         {"KeyDeviceSensor", 2},
                                         {"Lighting", 2},
                                         {"Navigation", 2},
                                         {"Networking", 3},
                                         {"PointingDeviceSensor", 1},
                                         {"Rendering", 3},
                                         {"Scripting", 1},
                                         {"Shape", 2},
                                         {"Sound", 1},
                                         {"Text", 2},
                                         {"Texturing", 3},
                                         {"Time", 1}};
constexpr ComponentLevel kCadInterchange[] = {
    {"CADGeometry", 2}, {"Core", 1},      {"Grouping", 1}, {"Lighting", 1}, {"Navigation", 3},
    {"Networking", 2},  {"Rendering", 4}, {"Shaders", 1},  {"Shape", 2},    {"Texturing", 2}};
constexpr ComponentLevel kMedicalInterchange[] = {
    {"Core", 1},           {"EnvironmentalEffects", 1},
    {"EventUtilities", 1}, {"Geometry2D", 2},
    {"Geometry3D", 2},     {"Grouping", 3},
    {"Interpolation", 2},  {"Lighting", 1},
    {"Navigation", 3},     {"Networking", 2},
    {"Rendering", 5},      {"Shape", 3},
    {"Text", 2},           {"Texturing", 2},
    {"Texturing3D", 2},    {"Time", 1},
    {"VolumeRendering", 4}};

constexpr ProfileEntry kProfiles[] = {
    {"CADInterchange", "Computer-Aided Design (CAD) interchange", kCadInterchange},
    {"Core", "Core", kCore},
    {"Full", "Full", {}, true},
    {"Immersive", "Immersive", kImmersive},
    {"Interactive", "Interactive", kInteractive},
    {"Interchange", "Interchange", kInterchange},
    {"MedicalInterchange", "Medical interchange", kMedicalInterchange},
    {"MPEG4Interactive", "MPEG-4 interactive", kMpeg4Interactive},
};

const ComponentEntry* componentNamed(std::string_view name) {
  for (const ComponentEntry& e : kComponents)
    if (e.name == name) return &e;
  return nullptr;
}

const ProfileEntry* profileNamed(std::string_view name) {
  if (name == "MPEG-4") name = "MPEG4Interactive";  // the alias X_ITE and 19775-1 accept
  for (const ProfileEntry& e : kProfiles)
    if (e.name == name) return &e;
  return nullptr;
}

// Pushes [name, level, title] (a ComponentInfo's fields; the title "" for a component
// this browser does not know).
void pushComponent(duk_context* c, std::string_view name, int level) {
  const ComponentEntry* known = componentNamed(name);
  const std::string_view title = known != nullptr ? known->title : std::string_view();
  duk_push_array(c);
  duk_push_lstring(c, name.data(), name.size());
  duk_put_prop_index(c, -2, 0);
  duk_push_int(c, level);
  duk_put_prop_index(c, -2, 1);
  duk_push_lstring(c, title.data(), title.size());
  duk_put_prop_index(c, -2, 2);
}

// Pushes [name, title, [component ...]] (a ProfileInfo's fields).
void pushProfile(duk_context* c, const ProfileEntry& p) {
  duk_push_array(c);
  duk_push_lstring(c, p.name.data(), p.name.size());
  duk_put_prop_index(c, -2, 0);
  duk_push_lstring(c, p.title.data(), p.title.size());
  duk_put_prop_index(c, -2, 1);
  duk_push_array(c);
  duk_uarridx_t i = 0;
  if (p.full) {
    for (const ComponentEntry& e : kComponents) {
      pushComponent(c, e.name, e.level);
      duk_put_prop_index(c, -2, i++);
    }
  } else {
    for (const ComponentLevel& l : p.components) {
      pushComponent(c, l.name, l.level);
      duk_put_prop_index(c, -2, i++);
    }
  }
  duk_put_prop_index(c, -2, 2);
}

// profiles(): every supported profile, as pushProfile's arrays.
duk_ret_t x3dProfiles(duk_context* c) {
  duk_push_array(c);
  duk_uarridx_t i = 0;
  for (const ProfileEntry& p : kProfiles) {
    pushProfile(c, p);
    duk_put_prop_index(c, -2, i++);
  }
  return 1;
}

// components(): every supported component at its highest level.
duk_ret_t x3dComponents(duk_context* c) {
  duk_push_array(c);
  duk_uarridx_t i = 0;
  for (const ComponentEntry& e : kComponents) {
    pushComponent(c, e.name, e.level);
    duk_put_prop_index(c, -2, i++);
  }
  return 1;
}

// profile(name): the profile called `name` (pushProfile's array), or null.
duk_ret_t x3dProfile(duk_context* c) {
  const ProfileEntry* p = profileNamed(x3dString(c, 0));
  if (p == nullptr)
    duk_push_null(c);
  else
    pushProfile(c, *p);
  return 1;
}

// component(name, level): the component at `level` clamped to 1 .. its highest (0 or
// absent: the highest), or null when the browser has no component of that name.
duk_ret_t x3dComponent(duk_context* c) {
  const ComponentEntry* e = componentNamed(x3dString(c, 0));
  if (e == nullptr) {
    duk_push_null(c);
    return 1;
  }
  const double asked = duk_is_undefined(c, 1) ? 0.0 : duk_to_number(c, 1);
  const int level = std::isfinite(asked) && asked >= 1.0
                        ? static_cast<int>(std::min<double>(asked, e->level))
                        : e->level;
  pushComponent(c, e->name, level);
  return 1;
}

// sceneProfile(scene): the scene's PROFILE as pushProfile's array (an unknown name with no
// components and no title), or null when the scene has none (VRML97, or no statement).
duk_ret_t x3dSceneProfile(duk_context* c) {
  const vrml::Scene* scene = x3dSceneOf(EsScript::of(c), c, 0);
  const std::string name = scene != nullptr ? scene->x3d.profile : std::string();
  if (name.empty()) {
    duk_push_null(c);
  } else if (const ProfileEntry* p = profileNamed(name)) {
    pushProfile(c, *p);
  } else {
    pushProfile(c, ProfileEntry{name, "", {}});  // a name this browser does not know
  }
  return 1;
}

// sceneComponents(scene): the scene's COMPONENT statements, in file order.
duk_ret_t x3dSceneComponents(duk_context* c) {
  const vrml::Scene* scene = x3dSceneOf(EsScript::of(c), c, 0);
  duk_push_array(c);
  if (scene == nullptr) return 1;
  duk_uarridx_t i = 0;
  for (const auto& [name, level] : scene->x3d.components) {
    pushComponent(c, name, level);
    duk_put_prop_index(c, -2, i++);
  }
  return 1;
}

// sceneUnits(scene): [category, name, conversionFactor] for angle, force, length and mass,
// in that order (19775-1 4.3.6: the base units, radian, newton, metre and kilogram, unless
// a UNIT statement of the scene names another).
duk_ret_t x3dSceneUnits(duk_context* c) {
  const vrml::Scene* scene = x3dSceneOf(EsScript::of(c), c, 0);
  constexpr std::array<std::pair<std::string_view, std::string_view>, 4> kBase = {
      {{"angle", "radian"}, {"force", "newton"}, {"length", "metre"}, {"mass", "kilogram"}}};
  duk_push_array(c);
  duk_uarridx_t i = 0;
  for (const auto& [category, base] : kBase) {
    std::string name(base);
    double factor = 1.0;
    if (scene != nullptr)
      for (const vrml::X3dUnit& u : scene->x3d.units)
        if (u.category == category) {
          name = u.name;
          factor = u.conversionFactor;
        }
    duk_push_array(c);
    duk_push_lstring(c, category.data(), category.size());
    duk_put_prop_index(c, -2, 0);
    duk_push_lstring(c, name.data(), name.size());
    duk_put_prop_index(c, -2, 1);
    duk_push_number(c, factor);
    duk_put_prop_index(c, -2, 2);
    duk_put_prop_index(c, -2, i++);
  }
  return 1;
}

// renderingProperty(name): the value of one of 19775-2's rendering properties (clause
// 6.3.13, getRenderingProperties: Shading, MaxTextureSize, TextureUnits, MaxLights,
// Antialiased, ColorDepth, TextureMemory), or undefined for a property the host does not
// give (TextureMemory: the GL does not say) or a name that is none of them.
duk_ret_t x3dRenderingProperty(duk_context* c) {
  EsScript& self = EsScript::of(c);
  const std::string name = x3dString(c, 0);
  const RenderingProperties* r = self.context().renderingProperties();
  if (name == "Shading") {
    const std::string* shading = self.context().browserOption("Shading");
    if (shading != nullptr)
      duk_push_lstring(c, shading->data(), shading->size());
    else
      duk_push_undefined(c);
  } else if (r == nullptr) {
    duk_push_undefined(c);
  } else if (name == "MaxTextureSize") {
    duk_push_int(c, r->maxTextureSize);
  } else if (name == "TextureUnits") {
    duk_push_int(c, r->textureUnits);
  } else if (name == "MaxLights") {
    duk_push_int(c, r->maxLights);
  } else if (name == "Antialiased") {
    duk_push_boolean(c, r->antialiased);
  } else if (name == "ColorDepth") {
    duk_push_int(c, r->colorDepth);
  } else {
    duk_push_undefined(c);
  }
  return 1;
}

}  // namespace

void installX3DInfo(duk_context* c) {
  static constexpr NativeFunction kHooks[] = {
      {"profiles", x3dProfiles, 0},         {"components", x3dComponents, 0},
      {"profile", x3dProfile, 1},           {"component", x3dComponent, 2},
      {"sceneProfile", x3dSceneProfile, 1}, {"sceneComponents", x3dSceneComponents, 1},
      {"sceneUnits", x3dSceneUnits, 1},     {"renderingProperty", x3dRenderingProperty, 1},
  };
  putNativeFunctions(c, kHooks);
}

}  // namespace gs::runtime::es
