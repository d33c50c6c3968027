// Private to runtime/: what the execution model keeps per MovieTexture (6.28) and
// AudioClip (6.3) (media_nodes.cpp).
#pragma once

#include "runtime/media_time.hpp"
#include "runtime/time_dependent.hpp"

namespace gs::runtime {

/// Field indices of a MovieTexture or AudioClip (-1 when absent) and its media state.
struct MediaNode {
  int loop = -1, startTime = -1, stopTime = -1;
  int rate = -1;  // MovieTexture.speed or AudioClip.pitch
  int durationChanged = -1, isActive = -1;
  MediaState state;
  TimeState time;
  bool durationPending = false;  // duration_changed still to be sent
  bool everStarted = false;      // has been active once: the media time stays where it stopped
};

}  // namespace gs::runtime
