// Per-stream progress of a progressive load (docs/progressive-loading.md): what the
// window's stream panel and the terminal progress bar show.
#pragma once

#include <cstdint>
#include <string>

namespace gs::net {

/// What a stream brings: a world's text, a QNV stream (or tileset), or a Gaussian
/// splatting scene file (.ply, .spz, SOG, ...; session/src/gaussian_scene_load.hpp).
enum class StreamKind { world, qnv, splats };

enum class StreamState {
  waiting,  // no byte yet
  loading,  // bytes arriving
  idle,     // everything asked for so far arrived (a QNV prefix); more may be asked for
  done,     // the whole resource arrived
  stopped,  // cut on purpose (--snapshot-at, cancel): a valid, smaller picture
  failed,   // ended by an error (message in `error`); what arrived is still shown
};

struct StreamProgress {
  std::string url;
  StreamKind kind = StreamKind::world;
  StreamState state = StreamState::waiting;
  std::uint64_t bytes = 0;            // bytes received (compressed, as on the wire)
  std::int64_t expectedBytes = -1;    // size of the resource when known
  std::uint64_t vectors = 0;          // QNV: vectors decoded
  std::uint64_t expectedVectors = 0;  // QNV: vectors in the whole stream (header)
  std::uint64_t wantedVectors = 0;    // QNV: prefix the views asked for
  std::uint64_t packetsLost = 0;      // QNV: damaged plus missing packets
  std::uint64_t rootNodes = 0;        // worlds: top-level nodes parsed
  double bytesPerSecond = 0.0;
  std::string error;  // the reason a stream failed or stopped, naming its URL
  /// What a stream still loading does once its bytes are in, for panels: "sorting",
  /// "building tree" (a splat scene file), else empty.
  std::string stage;

  /// Fraction done, 0..1: vectors of the wanted prefix for QNV, splats of the scene's for
  /// a splat scene file (`vectors` of `expectedVectors`; for a remote one the lesser of
  /// that and its bytes' fraction), bytes of the expected size for
  /// worlds and for a splat scene file whose count is not known yet; 0 when unknown.
  double fraction() const;
  /// Whether nothing more is coming without a new request.
  bool settled() const {
    return state == StreamState::idle || state == StreamState::done ||
           state == StreamState::stopped || state == StreamState::failed;
  }
};

/// "loading", "done", ... for panels and messages.
const char* toString(StreamState state);

}  // namespace gs::net
