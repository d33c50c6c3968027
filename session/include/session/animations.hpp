// The animations of a world as a user starts and stops them (the window's Animations
// menu): its TimeSensors that have a DEF name, which for a glTF asset are its animations
// (docs/gltf.md: one TimeSensor per animation, named after it). GL-free.
#pragma once

#include "runtime/execution_model.hpp"
#include "vrml/scene.hpp"

#include <cstddef>
#include <vector>

namespace gs::session {

/// The TimeSensors with a DEF name reachable from `scene`'s root nodes, each once, in file
/// order (depth first), at most `limit` of them.
std::vector<vrml::Node*> namedTimeSensors(const vrml::Scene& scene, std::size_t limit = 64);

/// True when TimeSensor `sensor` is running (its isActive eventOut last sent TRUE).
bool animationActive(const vrml::Node& sensor);

/// Starts TimeSensor `sensor` of `model`'s world at `model`'s current time, looping (VRML97
/// 6.50: loop TRUE, startTime now; a sensor already running is stopped first and restarted
/// at the next cascade); with `exclusive`, every other sensor of `others` that runs is
/// stopped (stopTime now), as castle-model-viewer plays one glTF animation at a time. The
/// events are processed at once (ExecutionModel::processEvents).
void startAnimation(runtime::ExecutionModel& model, vrml::Node& sensor,
                    const std::vector<vrml::Node*>& others, bool exclusive);

/// Stops TimeSensor `sensor` (stopTime = the model's current time), processed at once.
void stopAnimation(runtime::ExecutionModel& model, vrml::Node& sensor);

}  // namespace gs::session
