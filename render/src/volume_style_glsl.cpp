// X3D volume render styles as X_ITE 15 writes them in GLSL (volume_style_glsl.hpp): the
// shared helpers, VolumeStyle.fs's helper functions, and the data nodes' arrangement of
// their styles as X_ITE 15.0.1's VolumeData.js, SegmentedVolumeData.js and
// IsoSurfaceVolumeData.js createShader() make it (dist/assets/components/
// VolumeRenderingComponent.js). The style nodes are in volume_style_glsl_styles.cpp.
#include "volume_style_glsl.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <string_view>
#include <utility>

namespace gs::render::detail {

std::string volumeStyleFloat(double v, bool single) {
  if (std::isnan(v)) return "0.0";
  if (std::isinf(v)) v = std::copysign(static_cast<double>(std::numeric_limits<float>::max()), v);
  char buffer[64];
  const std::to_chars_result r =
      single ? std::to_chars(buffer, buffer + sizeof buffer, static_cast<float>(v))
             : std::to_chars(buffer, buffer + sizeof buffer, v);
  std::string s(buffer, r.ptr);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

std::string volumeStyleText(std::string_view text, const std::string& id) {
  std::string out;
  out.reserve(text.size() + 8 * id.size());
  for (const char c : text) {
    if (c == '@')
      out += id;
    else
      out += c;
  }
  return out;
}

const vrml::Node* volumeStyleCast(const vrml::NodePtr& p, vrml::AbstractType t) {
  return p && !p->unresolved && p->is(t) ? p.get() : nullptr;
}

bool volumeStyleEnabled(const vrml::Node& style) {
  return style.get<vrml::FieldType::SFBool>("enabled", true);
}

std::vector<const vrml::Node*> volumeStyleComposables(const vrml::Node& n) {
  std::vector<const vrml::Node*> out;
  for (const vrml::NodePtr& p : n.mfnode("renderStyle"))
    if (const vrml::Node* s =
            volumeStyleCast(p, vrml::AbstractType::X3DComposableVolumeRenderStyleNode))
      out.push_back(s);
  return out;
}

namespace {

/// The double a JavaScript browser holds for a field value written in a file: the float's
/// shortest decimal read as a double (0.3f gives 0.3, not 0.30000001192092896).
double volumeStyleDouble(float v) {
  if (!std::isfinite(v)) return static_cast<double>(v);
  char buffer[64];
  const std::to_chars_result r = std::to_chars(buffer, buffer + sizeof buffer, v);
  double d = static_cast<double>(v);
  std::from_chars(buffer, r.ptr, d);
  return d;
}

// ---- VolumeStyle.fs's helpers (X_ITE 15), emitted when a style defines their switch ----

constexpr std::string_view kVolumeStyleHsvGlsl = R"(
// X3D_HSV (VolumeStyle.fs)

vec3
rgb2hsv (in vec3 color)
{
   float h = 0.0;
   float s = 0.0;
   float v = 0.0;
   float minC = min (min (color .r, color .g), color .b);
   float maxC = max (max (color .r, color .g), color .b);

   v = maxC;

   float delta = maxC - minC;

   if (maxC != 0.0 && delta != 0.0)
   {
      s = delta / maxC;

      if (color .r == maxC)
         h = (color .g - color .b) / delta;
      else if (color .g == maxC)
         h = 2.0 + (color .b - color .r) / delta;
      else
         h = 4.0 + (color .r - color .g) / delta;

      h *= M_PI / 3.0;

      if (h < 0.0)
         h += M_PI * 2.0;
   }
   else
      s = h = 0.0;

   return vec3 (h, s, v);
}

vec3
hsv2rgb (in vec3 hsv)
{
   float h = hsv [0];
   float s = clamp (hsv [1], 0.0, 1.0);
   float v = clamp (hsv [2], 0.0, 1.0);

   if (s == 0.0)
   {
      return vec3 (v, v, v);
   }
   else
   {
      float w = (h * (180.0 / M_PI)) / 60.0;
      float i = floor (w);
      float f = w - i;
      float p = v * (1.0 - s);
      float q = v * (1.0 - s * f);
      float t = v * (1.0 - s * (1.0 - f));

      switch (int (i) % 6)
      {
         case 0:  return vec3 (v, t, p);
         case 1:  return vec3 (q, v, p);
         case 2:  return vec3 (p, v, t);
         case 3:  return vec3 (p, q, v);
         case 4:  return vec3 (t, p, v);
         default: return vec3 (v, p, q);
      }
   }

   return vec3 (0.0);
}

vec3
mix_hsv (in vec3 a, in vec3 b, in float t)
{
   float ha = a [0];
   float sa = a [1];
   float va = a [2];
   float hb = b [0];
   float sb = b [1];
   float vb = b [2];

   if (sa == 0.0)
      ha = hb;

   if (sb == 0.0)
      hb = ha;

   float range = abs (hb - ha);

   if (range <= M_PI)
   {
      float h = ha + t * (hb - ha);
      float s = sa + t * (sb - sa);
      float v = va + t * (vb - va);
      return vec3 (h, s, v);
   }

   float PI2   = M_PI * 2.0;
   float stepH = (PI2 - range) * t;
   float h     = ha < hb ? ha - stepH : ha + stepH;

   if (h < 0.0)
      h += PI2;
   else if (h > PI2)
      h -= PI2;

   float s = sa + t * (sb - sa);
   float v = va + t * (vb - va);
   return vec3 (h, s, v);
}
)";

constexpr std::string_view kVolumeStylePlaneGlsl = R"(
// X3D_PLANE (VolumeStyle.fs)

struct Plane3
{
   vec3  normal;
   float distanceFromOrigin;
};

Plane3
plane3 (const in vec3 point, const in vec3 normal)
{
   return Plane3 (normal, dot (normal, point));
}

vec3
plane3_perpendicular_vector (const in Plane3 plane, const in vec3 point)
{
   return plane .normal * (dot (point, plane .normal) - plane .distanceFromOrigin);
}
)";

constexpr std::string_view kVolumeStyleShadingGlsl = R"(
// X3D_SHADING (VolumeStyle.fs)

float
getSpotFactor (const in float cutOffAngle, const in float beamWidth, const in vec3 L, const in vec3 d)
{
   float spotAngle = acos (clamp (dot (-L, d), -1.0, 1.0));

   if (spotAngle >= cutOffAngle)
      return 0.0;
   else if (spotAngle <= beamWidth)
      return 1.0;

   return (spotAngle - cutOffAngle) / (beamWidth - cutOffAngle);
}
)";

/// X_ITE's x3d_LightSource[i].matrix, which the ray caster's light struct lacks.
constexpr std::string_view kVolumeStyleLightMatrixGlsl = R"(
// x3d_LightSource [i] .matrix of X_ITE: the inverse of the upper-left 3x3 of light i's
// model-view matrix (eye-space vectors to the light's coordinates, where radius is).
uniform mat3 x3d_LightMatrix [8];
)";

}  // namespace

void VolumeStyleWriter::define(const std::string& line) {
  if (!hasDefine(line)) defines_.push_back(line);
}

bool VolumeStyleWriter::hasDefine(const std::string& line) const {
  for (const std::string& d : defines_)
    if (d == line) return true;
  return false;
}

std::string VolumeStyleWriter::sampler(const std::string& uniform, const vrml::Node& texture,
                                       int dimensions) {
  samplers_.push_back({uniform, &texture, dimensions});
  return std::string(dimensions == 3 ? "uniform sampler3D " : "uniform sampler2D ") + uniform +
         ";\n";
}

VolumeStyleGlsl VolumeStyleWriter::finish(std::string uniforms, std::string functions) {
  VolumeStyleGlsl out;
  std::string helpers;
  for (const std::string& d : defines_) out.defines += d + "\n";
  if (hasDefine("#define X3D_HSV")) helpers += kVolumeStyleHsvGlsl;
  if (hasDefine("#define X3D_PLANE")) helpers += kVolumeStylePlaneGlsl;
  if (hasDefine("#define X3D_SHADING")) helpers += kVolumeStyleShadingGlsl;
  if (lightMatrix_) helpers += kVolumeStyleLightMatrixGlsl;
  out.uniforms = helpers + uniforms;
  out.functions = std::move(functions);
  out.samplers = std::move(samplers_);
  return out;
}

namespace {

/// X_ITE's IsoSurfaceVolumeData.createShader: the surfaces of surfaceValues (with
/// contourStepSize, the contours around a single value), each coloured by its value and
/// then by its style; every other sample transparent (X_ITE discards it).
VolumeStyleGlsl volumeStyleIsoSurface(const vrml::Node& data) {
  VolumeStyleWriter w;
  VolumeStyleCode base = w.opacityMap(nullptr);
  std::string uniforms = std::move(base.uniforms), functions = std::move(base.functions);

  static const std::vector<float> kNoValues;
  const vrml::FieldValue* field = data.field("surfaceValues");
  const std::vector<float>& values = field != nullptr && field->type() == vrml::FieldType::MFFloat
                                         ? field->get<vrml::FieldType::MFFloat>()
                                         : kNoValues;
  const std::string id = w.nextId();
  const std::string surfaceValues = "surfaceValues_" + id;
  const std::string surfaceTolerance = "surfaceTolerance_" + id;
  // X_ITE's uniforms `float surfaceValues [max (n, 1)]` (0 when n is 0) and
  // `float surfaceTolerance`, as constants.
  const std::size_t n = std::max<std::size_t>(values.size(), 1);
  std::string array;
  for (std::size_t i = 0; i < n; ++i)
    array += (i > 0 ? ", " : "") + volumeStyleFloat(i < values.size() ? values[i] : 0.0f);
  uniforms += "\nconst float " + surfaceValues + " [" + std::to_string(n) + "] = float [" +
              std::to_string(n) + "] (" + array + ");\n";
  uniforms += "const float " + surfaceTolerance + " = " +
              volumeStyleFloat(data.get<vrml::FieldType::SFFloat>("surfaceTolerance", 0.0f)) +
              ";\n";

  std::vector<VolumeStyleCode> styles;
  for (const vrml::Node* s : volumeStyleComposables(data)) {
    styles.push_back(w.style(*s, false, 0));
    uniforms += styles.back().uniforms;
  }

  functions += "\n   // IsoSurfaceVolumeData\n\n";
  if (const vrml::Node* gradients =
          volumeStyleCast(data.sfnode("gradients"), vrml::AbstractType::X3DTexture3DNode)) {
    uniforms += "\n" + w.sampler("gradients_" + id, *gradients, 3);
    functions += "   if (length (texture (gradients_" + id + ", texCoord) .xyz * 2.0 - 1.0) < " +
                 surfaceTolerance + ")\n      return vec4 (0.0);\n";
  } else {
    uniforms += volumeStyleText(kVolumeStyleGradientNormal, id);
    functions += "   if (getNormal_" + id + " (texCoord) .w < " + surfaceTolerance +
                 ")\n      return vec4 (0.0);\n";
  }
  functions += "\n   float intensity = textureColor .r;\n\n";

  const auto styleOf = [&styles](std::size_t i) {
    return styles.empty() ? std::string() : styles[std::min(i, styles.size() - 1)].functions;
  };
  const std::string otherwise = "   else\n   {\n      return vec4 (0.0);\n   }\n\n";
  if (values.size() == 1) {
    const float step = std::abs(data.get<vrml::FieldType::SFFloat>("contourStepSize", 0.0f));
    if (step == 0.0f) {
      functions += "   if (intensity > " + surfaceValues + " [0])\n   {\n";
      functions += "      textureColor = vec4 (vec3 (" + surfaceValues + " [0]), 1.0);\n";
      functions += styleOf(0) + "   }\n" + otherwise;
    } else {
      // X_ITE lists the contours v0 - k step > 0, v0, v0 + k step < 1 (in JavaScript
      // doubles), then writes one branch for index 0 only (its loop runs over the one
      // surfaceValues entry): the lowest contour above 0, alone.
      const double first = [&] {
        const double d = volumeStyleDouble(step), start = volumeStyleDouble(values[0]);
        double lowest = start;
        double v = start - d;
        for (int k = 0; v > 0.0 && k < (1 << 20); ++k, v -= d) lowest = v;
        if (v > 0.0) {  // a step too small to walk: the same, closed form
          lowest = std::fmod(v, d);
          if (!(lowest > 0.0)) lowest = d;
        }
        return lowest;
      }();
      const std::string value = volumeStyleFloat(first, false);
      functions += "   if (false)\n   { }\n";
      functions += "   else if (intensity > " + value + ")\n   {\n";
      functions += "      textureColor = vec4 (vec3 (" + value + "), 1.0);\n";
      functions += styleOf(0) + "   }\n" + otherwise;
    }
  } else {
    functions += "   if (false)\n   { }\n";
    for (std::size_t i = values.size(); i-- > 0;) {
      const std::string v = surfaceValues + " [" + std::to_string(i) + "]";
      functions += "   else if (intensity > " + v + ")\n   {\n";
      functions += "      textureColor = vec4 (vec3 (" + v + "), 1.0);\n";
      functions += styleOf(i) + "   }\n";
    }
    functions += otherwise;
  }
  return w.finish(std::move(uniforms), std::move(functions));
}

/// X_ITE's SegmentedVolumeData.createShader: segment s (segmentIdentifiers' value times
/// 255, else 0) takes style s of renderStyle, or is transparent when segmentEnabled[s] is
/// FALSE; a segment without a style keeps the default opacity map's colour.
VolumeStyleGlsl volumeStyleSegmented(const vrml::Node& data) {
  VolumeStyleWriter w;
  VolumeStyleCode base = w.opacityMap(nullptr);
  std::string uniforms = std::move(base.uniforms), functions = std::move(base.functions);
  if (const vrml::Node* ids = volumeStyleCast(data.sfnode("segmentIdentifiers"),
                                              vrml::AbstractType::X3DTexture3DNode)) {
    const std::string name = "segmentIdentifiers_" + w.nextId();
    uniforms += "\n" + w.sampler(name, *ids, 3) + "\n";
    functions += "\n   int segment = int (texture (" + name + ", texCoord) .r * 255.0);\n";
  } else {
    functions += "   int segment = 0;\n";
  }
  const std::vector<const vrml::Node*> styles = volumeStyleComposables(data);
  if (!styles.empty()) {
    const vrml::FieldValue* field = data.field("segmentEnabled");
    const std::vector<bool>* enabled = field != nullptr && field->type() == vrml::FieldType::MFBool
                                           ? &field->get<vrml::FieldType::MFBool>()
                                           : nullptr;
    functions += "\n   switch (segment)\n   {\n";
    for (std::size_t i = 0; i < styles.size(); ++i) {
      functions += "      case " + std::to_string(i) + ":\n      {\n";
      if (enabled == nullptr || i >= enabled->size() || (*enabled)[i]) {
        VolumeStyleCode code = w.style(*styles[i], false, 0);
        uniforms += code.uniforms;
        functions += code.functions + "         break;\n";
      } else {
        functions += "         return vec4 (0.0);\n";
      }
      functions += "      }\n";
    }
    functions += "   }\n";
  }
  return w.finish(std::move(uniforms), std::move(functions));
}

/// Whether `style` (enabled) is one the splats cannot show: anything but an
/// OpacityMapVolumeStyle.
bool volumeStyleNeedsRaycast(const vrml::Node* style) {
  return style != nullptr && volumeStyleEnabled(*style) &&
         style->typeId() != vrml::NodeTypeId::OpacityMapVolumeStyle;
}

}  // namespace

VolumeStyleGlsl volumeStyleGlsl(const vrml::Node& volumeData) {
  switch (volumeData.typeId()) {
    case vrml::NodeTypeId::IsoSurfaceVolumeData:
      return volumeStyleIsoSurface(volumeData);
    case vrml::NodeTypeId::SegmentedVolumeData:
      return volumeStyleSegmented(volumeData);
    default: {
      // VolumeData.createShader: the default opacity map, then renderStyle (any
      // X3DVolumeRenderStyleNode, ProjectionVolumeStyle included).
      VolumeStyleWriter w;
      VolumeStyleCode code = w.opacityMap(nullptr);
      if (volumeData.typeId() == vrml::NodeTypeId::VolumeData)
        if (const vrml::Node* s = volumeStyleCast(volumeData.sfnode("renderStyle"),
                                                  vrml::AbstractType::X3DVolumeRenderStyleNode)) {
          VolumeStyleCode style = w.style(*s, true, 0);
          code.uniforms += style.uniforms;
          code.functions += style.functions;
        }
      return w.finish(std::move(code.uniforms), std::move(code.functions));
    }
  }
}

bool needsVolumeRaycast(const vrml::Node& volumeData) {
  switch (volumeData.typeId()) {
    case vrml::NodeTypeId::VolumeData:
      return volumeStyleNeedsRaycast(volumeStyleCast(volumeData.sfnode("renderStyle"),
                                                     vrml::AbstractType::X3DVolumeRenderStyleNode));
    case vrml::NodeTypeId::SegmentedVolumeData: {
      if (volumeStyleCast(volumeData.sfnode("segmentIdentifiers"),
                          vrml::AbstractType::X3DTexture3DNode) != nullptr)
        return true;
      for (const vrml::Node* s : volumeStyleComposables(volumeData))
        if (volumeStyleNeedsRaycast(s)) return true;
      return false;
    }
    case vrml::NodeTypeId::IsoSurfaceVolumeData:
      return !volumeStyleComposables(volumeData).empty();
    default:
      return false;
  }
}

}  // namespace gs::render::detail
