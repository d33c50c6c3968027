// What a ParticleSystem's particles look like (X3D 4.0 clause 40.4.7, drawn as X_ITE 15
// draws them): the mesh of geometry types LINE, POINT, QUAD, TRIANGLE and SPRITE, and the
// colour and texture-coordinate ramps. Units: metres, the ParticleSystem's coordinates.
#pragma once

#include "geometry/geometry.hpp"
#include "particles/particle_system.hpp"

#include <glm/glm.hpp>

#include <vector>

namespace gs::particles {

/// The colour ramp's colour (RGBA, [0, 1]) at age fraction `f` in [0, 1] (clause 40.2.3):
/// `keys` (colorKey) ascending, `colors` the ramp's (a Color node's alpha is 1; key k takes
/// colour k modulo the count); below the first key the first colour, above the last the
/// last, between two keys linear in RGBA. Empty keys or colours: white.
glm::vec4 rampColor(const std::vector<float>& keys, const std::vector<glm::vec4>& colors, float f);

/// The colours of a ParticleSystem's `color` node (Color: alpha 1; ColorRGBA); empty for
/// none or another node.
std::vector<glm::vec4> rampColors(const vrml::Node& system);

/// The texture-coordinate set (0-based) the stepped texture ramp (texCoordKey) gives at age
/// fraction `f`, as X_ITE steps it: 0 at or below the first key, the set of the largest key
/// <= f, keys.size() - 2 at or past the last key (X_ITE never uses the last set); 0 for fewer
/// than two keys.
std::size_t rampTexCoordSet(const std::vector<float>& keys, float f);

/// The mesh of `particles` (the visible ones) of ParticleSystem `system` drawn as `type`
/// (not GeometryType::geometry, which draws the system's `geometry` node per particle):
/// - point: Primitive::points, one per particle;
/// - line: Primitive::lines, a segment of length particleSize.y centred on the particle
///   along its velocity (+Z when it has none);
/// - quad, triangle: two triangles per particle, particleSize.x by particleSize.y in the
///   local XY plane, normal +Z, solid (back faces culled);
/// - sprite: the same rectangle parallel to the view plane: its axes are the viewer's right
///   and up seen in the system's coordinates (`eyeToLocal`: the inverse of the
///   modelview's upper 3x3, so that column 1 is the viewer's up and column 2 its back).
/// Colours from the colour ramp when the system has colorKey and a color node; texture
/// coordinates (quads, sprites) from its texCoord node's sets of 4 points (corners
/// (-1/2, -1/2), (1/2, -1/2), (1/2, 1/2), (-1/2, 1/2)) when it has texCoordKey, else the whole
/// texture. Particles are in slot order (X_ITE sorts none).
vrml::Mesh particleMesh(const vrml::Node& system, GeometryType type,
                        const std::vector<Particle>& particles, const glm::mat3& eyeToLocal);

}  // namespace gs::particles
