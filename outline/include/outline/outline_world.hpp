// A VRML97 world rewritten as outline groups (paper section 1.1, figure 1): every outline
// first, then the polygons group by group, largest first, so that a browser reading the
// file front to back can draw every group's outline early and replace each by its
// polygons as they arrive. The OutlineGroup node is documented in docs/vrml-extensions.md.
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "outline/outline_encoder.hpp"
#include "vrml/scene.hpp"

namespace gs::outline {

/// Figures of one writeOutlineWorld call.
struct OutlineWorldSummary {
  std::size_t groups = 0;
  std::size_t triangles = 0;         // triangles written (input triangles less dropped)
  std::size_t droppedTriangles = 0;  // zero-area triangles (no group)
  std::size_t outlineVertices = 0;   // points of all outlines
  std::size_t appearances = 0;       // distinct Appearance nodes written
  std::size_t bytes = 0;             // of the whole text
  /// Bytes before the first polygon: the header, bindable nodes, lights and every
  /// outline. A prefix of this length is a complete world showing only the outlines.
  std::size_t outlineBytes = 0;
};

/// Flattens `scene` as scene::worldTriangles does (scene/world_triangles.hpp: every
/// triangle drawn from the bound Viewpoint, Inlines included, in world coordinates,
/// counter-clockwise front, mirroring transforms undone), groups it with
/// encodeOutlineGroups and writes a VRML97 text world (UTF-8):
///
/// - `#VRML V2.0 utf8` and a comment with the figures;
/// - the bound NavigationInfo (type, headlight, speed, avatarSize, visibilityLimit),
///   Background (skyColor, skyAngle, groundColor, groundAngle), Fog, and every Viewpoint
///   (position, orientation, fieldOfView, description) in world coordinates; every light
///   met, in world coordinates, at the top level;
/// - one `OutlineGroup { groupId k appearance ... outline [...] outlineLengths [...] }`
///   per group in area order; each distinct Appearance is DEF'd (`DEF A0 Appearance`) at
///   its first use, which is in this outline section, and USE'd after;
/// - one `OutlineGroup { groupId k children [ Shape { ... IndexedFaceSet } ] }` per group
///   in the same order, with the group's own coordinates (`solid` as the source
///   geometry's; `ccw` TRUE; when the source's shading normals differ from the flat
///   ones, a Normal node: one normal and an index per face when the group shares one,
///   else one per vertex to 3 significant digits).
///
/// Appearance keeps the Material's diffuseColor, specularColor, emissiveColor,
/// ambientIntensity, shininess and transparency (a Shape without Material stays unlit).
/// A Color node becomes one Appearance per distinct triangle colour (the mean of its
/// corners: diffuseColor, or emissiveColor when unlit), so smooth per-vertex colour
/// gradients turn flat per triangle.
/// Dropped: textures and texture coordinates, lines and
/// points (IndexedLineSet, PointSet), Text, sensors, interpolators, Scripts and ROUTEs,
/// Switch choices and LOD levels not drawn from the bound Viewpoint, the Background's
/// textures and rotation, and the scoping of DirectionalLights (written at the top
/// level, they light everything). Numbers are written as the shortest text that reads
/// back to the same 32-bit float. Throws InputError (qnv/error.hpp) when the flattened
/// triangles break encodeOutlineGroups's limits.
std::string writeOutlineWorld(std::shared_ptr<const vrml::Scene> scene,
                              const OutlineOptions& options = {},
                              OutlineWorldSummary* summary = nullptr);

}  // namespace gs::outline
