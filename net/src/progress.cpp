#include "net/progress.hpp"

#include <algorithm>

namespace gs::net {

double StreamProgress::fraction() const {
  if (state == StreamState::done) return 1.0;
  if (kind == StreamKind::qnv && wantedVectors > 0)
    return std::clamp(static_cast<double>(vectors) / static_cast<double>(wantedVectors), 0.0, 1.0);
  if (kind == StreamKind::splats && expectedVectors > 0) {
    // The lesser of splats and bytes: a compressed PLY's splats all arrive with a quarter
    // of its bytes (its SH come after them).
    double f =
        std::clamp(static_cast<double>(vectors) / static_cast<double>(expectedVectors), 0.0, 1.0);
    if (expectedBytes > 0)
      f = std::min(
          f, std::clamp(static_cast<double>(bytes) / static_cast<double>(expectedBytes), 0.0, 1.0));
    return f;
  }
  if (expectedBytes > 0)
    return std::clamp(static_cast<double>(bytes) / static_cast<double>(expectedBytes), 0.0, 1.0);
  return 0.0;
}

const char* toString(StreamState state) {
  switch (state) {
    case StreamState::waiting:
      return "waiting";
    case StreamState::loading:
      return "loading";
    case StreamState::idle:
      return "idle";
    case StreamState::done:
      return "done";
    case StreamState::stopped:
      return "stopped";
    case StreamState::failed:
      return "failed";
  }
  return "?";
}

}  // namespace gs::net
