// 6.42's ellipsoid attenuation and priority rule (audio/sound_model.hpp).
#include "audio/sound_model.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace gs::audio {

float ellipsoidRadius(float front, float back, float cosTheta) {
  front = std::max(front, 0.0f);
  back = std::max(back, 0.0f);
  const float denominator = front + back - (front - back) * cosTheta;
  if (front == 0.0f || back == 0.0f || denominator <= 0.0f) return 0.0f;
  return 2.0f * front * back / denominator;
}

bool attenuationDb(const SoundGeometry& s, const glm::vec3& listener, float& db) {
  const glm::vec3 offset = listener - s.location;
  const float r = glm::length(offset);
  glm::vec3 axis = s.direction;
  const float axisLength = glm::length(axis);
  axis = axisLength > 0.0f ? axis / axisLength : glm::vec3(0.0f, 0.0f, 1.0f);
  const float cosTheta = r > 0.0f ? std::clamp(glm::dot(offset, axis) / r, -1.0f, 1.0f) : 1.0f;
  const float minFront = std::max(s.minFront, 0.0f), minBack = std::max(s.minBack, 0.0f);
  const float inner = ellipsoidRadius(minFront, minBack, cosTheta);
  const float outer =
      ellipsoidRadius(std::max(s.maxFront, minFront), std::max(s.maxBack, minBack), cosTheta);
  if (r <= inner) {
    db = 0.0f;
    return true;
  }
  if (r > outer || outer <= inner) return false;
  db = -20.0f * (r - inner) / (outer - inner);
  return true;
}

float soundGain(const SoundGeometry& sound, float intensity, const glm::vec3& listener) {
  float db = 0.0f;
  if (!attenuationDb(sound, listener, db)) return 0.0f;
  return std::clamp(intensity, 0.0f, 1.0f) * std::pow(10.0f, db / 20.0f);
}

std::vector<std::size_t> chooseSounds(const std::vector<SoundCandidate>& sounds,
                                      std::size_t voices) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < sounds.size(); ++i)
    if (sounds[i].gain > 0.0f) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (sounds[a].priority != sounds[b].priority) return sounds[a].priority > sounds[b].priority;
    return sounds[a].gain > sounds[b].gain;
  });
  if (order.size() > voices) order.resize(voices);
  return order;
}

}  // namespace gs::audio
