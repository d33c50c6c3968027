// Private to runtime/: what the execution model keeps per MovieTexture (6.28) and
// AudioClip (6.3), and per X3D 4 sound source or processing node (X3DTimeDependentNode of
// ISO/IEC 19775-1 8.3.1 and clause 16) (media_nodes.cpp).
#pragma once

#include "runtime/media_time.hpp"
#include "runtime/time_dependent.hpp"

namespace gs::runtime {

/// Field indices of a MovieTexture or AudioClip (-1 when absent) and its media state.
struct MediaNode {
  int loop = -1, startTime = -1, stopTime = -1;
  int rate = -1;  // MovieTexture.speed or AudioClip.pitch
  int durationChanged = -1, isActive = -1;
  // X3DTimeDependentNode's (X3D): enabled, pause and resume, isPaused, elapsedTime.
  int enabled = -1, pauseTime = -1, resumeTime = -1, isPaused = -1, elapsedTime = -1;
  /// An X3D sound node without a duration (OscillatorSource, the processing nodes...):
  /// active from startTime until stopTime, or for ever.
  bool unbounded = false;
  bool paused = false;
  double pausedSince = 0.0;  // when it paused (seconds, simulated time)
  double pausedFor = 0.0;    // seconds paused since it became active
  double activatedAt = 0.0;
  MediaState state;
  TimeState time;
  bool durationPending = false;  // duration_changed still to be sent
  bool everStarted = false;      // has been active once: the media time stays where it stopped
};

}  // namespace gs::runtime
