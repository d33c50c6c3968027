// The Sound node's attenuation model (ISO/IEC 14772-1:1997 6.42, figure 6.14) and its
// priority rule, as pure functions: no device, no nodes.
//
// Two ellipsoids of revolution about the direction axis, each with one focus at the
// location: the inner one reaches minFront ahead of the location (along direction) and
// minBack behind it, the outer one maxFront and maxBack. Inside the inner ellipsoid the
// sound is at full loudness (0 dB); between the two the loudness falls linearly in dB,
// from 0 dB at the inner surface to -20 dB at the outer; outside the outer it is silent.
#pragma once

#include <glm/vec3.hpp>

#include <cstddef>
#include <vector>

namespace gs::audio {

/// A Sound's geometry in its own coordinate system (the fields of 6.42).
struct SoundGeometry {
  glm::vec3 location{0.0f};
  glm::vec3 direction{0.0f, 0.0f, 1.0f};    // need not be unit length; zero means +Z
  float minFront = 1.0f, minBack = 1.0f;    // >= 0
  float maxFront = 10.0f, maxBack = 10.0f;  // below the min values they are raised to them
};

/// Distance from the location (the shared focus) to the surface of the ellipsoid that
/// reaches `front` ahead and `back` behind, in the direction at angle theta from the
/// front (cosTheta = cos theta): r = 2 front back / (front + back - (front - back) cos
/// theta), the polar form of an ellipse about a focus. 0 when front or back is 0.
float ellipsoidRadius(float front, float back, float cosTheta);

/// The attenuation in dB (<= 0) at `listener` (same coordinate system as the geometry):
/// 0 inside the inner ellipsoid, -20 on the outer surface, linear in between; a
/// `silent` result (returned false) outside the outer one.
bool attenuationDb(const SoundGeometry& sound, const glm::vec3& listener, float& db);

/// The gain (linear amplitude factor, 0..1) at `listener`: intensity (clamped to 0..1)
/// times 10^(dB / 20); 0 outside the outer ellipsoid.
float soundGain(const SoundGeometry& sound, float intensity, const glm::vec3& listener);

/// A sound that could play, for choosing among more sounds than the device has voices.
struct SoundCandidate {
  float priority = 0.0f;  // Sound.priority, 0..1
  float gain = 0.0f;      // soundGain at the listener
};

/// The indices of the sounds to play when at most `voices` can (6.42: "the browser shall
/// use the priority field to determine which sounds to play"): silent sounds never; then
/// higher priority first, louder first among equal priorities, file order last. The
/// result is in that order.
std::vector<std::size_t> chooseSounds(const std::vector<SoundCandidate>& sounds,
                                      std::size_t voices);

}  // namespace gs::audio
