// MovieTexture (6.28) and AudioClip (6.3) as time-dependent nodes (4.6.9): the rules of
// time_dependent.cpp with a cycle of duration / |rate|, duration_changed once the
// application knows the duration, and the media time the renderer and the audio output
// read (runtime/media_time.hpp). The X3D 4 sound sources and processing nodes (clause 16)
// are time-dependent nodes too (X3DTimeDependentNode, 8.3.1): BufferAudioSource as an
// AudioClip whose duration its `buffer` gives, the others without an end; all of them
// paused and resumed by pauseTime and resumeTime (isPaused), with elapsedTime sent each frame
// while active and not paused, the paused seconds not counted.
#include "execution_state.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace gs::runtime {

using vrml::FieldType;
using vrml::FieldValue;

namespace {

template <FieldType T, class V>
V fieldOr(const vrml::Node& n, int field, V fallback) {
  if (field < 0) return fallback;
  const FieldValue& f = n.fieldAt(static_cast<std::size_t>(field));
  return f.type() == T ? f.get<T>() : fallback;
}

double rateOf(const vrml::Node& n, const MediaNode& m) {
  return static_cast<double>(fieldOr<FieldType::SFFloat>(n, m.rate, 1.0f));
}

/// The X3D 4 sound nodes that are time-dependent without a duration of their own: the
/// sources and processing nodes but the sampled ones (AudioClip, BufferAudioSource) and
/// MovieTexture.
bool unboundedSoundNode(const vrml::NodeType& type) {
  using vrml::NodeTypeId;
  const NodeTypeId id = type.id();
  return (type.is(vrml::AbstractType::X3DSoundSourceNode) ||
          type.is(vrml::AbstractType::X3DSoundProcessingNode)) &&
         id != NodeTypeId::AudioClip && id != NodeTypeId::BufferAudioSource &&
         id != NodeTypeId::MovieTexture;
}

/// A BufferAudioSource's duration from its `buffer` (channel-major, numberOfChannels
/// channels at sampleRate); empty when it has no buffer data (its url gives it).
std::optional<double> bufferDuration(const vrml::Node& n) {
  const auto& data = n.get<FieldType::MFFloat>("buffer", std::vector<float>{});
  if (data.empty()) return std::nullopt;
  const int channels = std::clamp(n.get<FieldType::SFInt32>("numberOfChannels", 1), 1, 8);
  const float rate = n.get<FieldType::SFFloat>("sampleRate", 0.0f);
  const double sampleRate = rate > 0.0f ? std::clamp(rate, 3000.0f, 768000.0f) : 44100.0;
  return static_cast<double>(data.size() / static_cast<std::size_t>(channels)) / sampleRate;
}

}  // namespace

bool ExecutionModel::State::classifyMedia(NodeState& ns) {
  const vrml::NodeType& type = ns.node->type();
  const bool movie = type.id() == vrml::NodeTypeId::MovieTexture;
  const bool buffer = type.id() == vrml::NodeTypeId::BufferAudioSource;
  const bool unbounded = unboundedSoundNode(type);
  if (!movie && !buffer && !unbounded && type.id() != vrml::NodeTypeId::AudioClip) return false;
  ns.role = NodeRole::media;
  ns.media = std::make_unique<MediaNode>();
  MediaNode& m = *ns.media;
  m.unbounded = unbounded;
  m.loop = type.findExact("loop");
  m.startTime = type.findExact("startTime");
  m.stopTime = type.findExact("stopTime");
  m.rate = type.findExact(movie ? "speed" : buffer ? "playbackRate" : "pitch");
  m.durationChanged = type.findExact("duration_changed");
  m.isActive = type.findExact("isActive");
  m.enabled = type.findExact("enabled");
  m.pauseTime = type.findExact("pauseTime");
  m.resumeTime = type.findExact("resumeTime");
  m.isPaused = type.findExact("isPaused");
  m.elapsedTime = type.findExact("elapsedTime");
  m.state.movie = movie;
  m.state.rate = rateOf(*ns.node, m);
  m.state.mediaTime = 0.0;
  mediaNodes.push_back(&ns);
  return true;
}

void ExecutionModel::State::evaluateMedia(NodeState& ns) {
  MediaNode& m = *ns.media;
  const vrml::Node& n = *ns.node;
  MediaState& st = m.state;
  if (m.durationPending) {
    m.durationPending = false;
    emitOwn(ns, m.durationChanged, FieldValue::make<FieldType::SFTime>(st.duration.value_or(-1.0)));
  }
  // The rate is read when the node is inactive and kept while it plays (6.28: set_speed is
  // ignored while the movie plays; a changed pitch takes effect at the next start).
  if (!m.time.active) st.rate = m.unbounded ? 1.0 : rateOf(n, m);
  if (n.typeId() == vrml::NodeTypeId::BufferAudioSource)
    if (const std::optional<double> d = bufferDuration(n)) st.duration = *d;
  const double duration = m.unbounded                         ? 1.0e15
                          : st.duration && *st.duration > 0.0 ? *st.duration
                                                              : 0.0;
  const double now = model.now();
  TimeFields f;
  f.startTime = fieldOr<FieldType::SFTime>(n, m.startTime, 0.0);
  f.stopTime = fieldOr<FieldType::SFTime>(n, m.stopTime, 0.0);
  f.loop = fieldOr<FieldType::SFBool>(n, m.loop, false);
  f.enabled = fieldOr<FieldType::SFBool>(n, m.enabled, true);
  // No known duration, speed 0 or a pitch <= 0 (6.3: undefined): a node that never starts.
  const bool playable =
      duration > 0.0 && std::isfinite(st.rate) && (st.movie ? st.rate != 0.0 : st.rate > 0.0);
  f.cycleInterval = playable ? duration / std::fabs(st.rate) : 0.0;
  // Paused seconds do not count: the node's clock is `now` less them (X3D 8.3.1); stopTime
  // stays on the world's clock.
  const double pausedNow = m.paused ? now - m.pausedSince : 0.0;
  if (f.stopTime > f.startTime) f.stopTime -= m.pausedFor + pausedNow;
  const TimeStep step = evaluateTime(m.time, f, now - m.pausedFor - pausedNow);
  if (step.activated) {
    m.activatedAt = now;
    m.pausedFor = 0.0;
    emitOwn(ns, m.isActive, FieldValue::make<FieldType::SFBool>(true));
  }
  if (m.pauseTime >= 0 && m.resumeTime >= 0 && m.time.active) {
    const double pauseAt = fieldOr<FieldType::SFTime>(n, m.pauseTime, 0.0);
    const double resumeAt = fieldOr<FieldType::SFTime>(n, m.resumeTime, 0.0);
    const bool pause = pauseAt > resumeAt && now >= pauseAt && pauseAt >= m.activatedAt;
    if (pause && !m.paused) {
      m.paused = true;
      m.pausedSince = now;
      emitOwn(ns, m.isPaused, FieldValue::make<FieldType::SFBool>(true));
    } else if (!pause && m.paused) {
      m.paused = false;
      m.pausedFor += now - m.pausedSince;
      emitOwn(ns, m.isPaused, FieldValue::make<FieldType::SFBool>(false));
    }
  }
  if (m.time.active && !m.paused && m.elapsedTime >= 0)
    emitOwn(ns, m.elapsedTime,
            FieldValue::make<FieldType::SFTime>(now - m.activatedAt - m.pausedFor));
  if (step.output) {
    st.mediaTime = mediaTimeAt(step.fraction, duration, st.rate);
  } else if (!m.everStarted) {
    // Not started yet: frame 0, or the last frame for a movie played backwards (6.28).
    st.mediaTime = st.movie && st.rate < 0.0 ? duration : 0.0;
  }
  if (step.activated) m.everStarted = true;
  if (step.deactivated) {
    if (m.paused) {
      m.paused = false;
      emitOwn(ns, m.isPaused, FieldValue::make<FieldType::SFBool>(false));
    }
    emitOwn(ns, m.isActive, FieldValue::make<FieldType::SFBool>(false));
  }
  // What the audio graph hears: an active node that is not paused.
  st.active = m.time.active && !m.paused;
}

void ExecutionModel::State::deliverMedia(NodeState& ns, int field, FieldValue value) {
  MediaNode& m = *ns.media;
  if (m.time.active) {
    // 6.28 / 6.3 as 6.50: startTime (and a movie's speed) are ignored while active, and so
    // is a stopTime at or before startTime.
    if (field == m.startTime || (m.state.movie && field == m.rate)) return;
    if (field == m.stopTime) {
      TimeFields f;
      f.startTime = fieldOr<FieldType::SFTime>(*ns.node, m.startTime, 0.0);
      if (ignoresStopTime(m.time, f, value.get<FieldType::SFTime>())) return;
    }
  }
  const vrml::FieldSpec& spec = ns.node->type().fields[static_cast<std::size_t>(field)];
  if (spec.access != vrml::AccessType::exposedField) return;
  emitOwn(ns, field, std::move(value));
  evaluateMedia(ns);
}

void ExecutionModel::setMediaDuration(const vrml::Node& node, double seconds) {
  if (!std::isfinite(seconds) || seconds <= 0.0) seconds = -1.0;
  const auto it = s_->nodes.find(&node);
  if (it != s_->nodes.end() && it->second->media) {
    NodeState& ns = *it->second;
    MediaState& st = ns.media->state;
    if (!st.duration || *st.duration != seconds) {
      st.duration = seconds;
      ns.media->durationPending = true;
      ++s_->stamp;
      ++stats_.cascades;
      s_->eventsThisCascade = 0;
      s_->evaluateMedia(ns);
      s_->runCascade();
    }
  }
  // The load report of LoadSensors (load_sensors.cpp), after duration_changed: a duration
  // means the media opened.
  setUrlObjectState(node, seconds > 0.0 ? UrlLoadState::loaded : UrlLoadState::failed);
}

std::optional<MediaState> ExecutionModel::media(const vrml::Node& node) const {
  const auto it = s_->nodes.find(&node);
  if (it == s_->nodes.end() || !it->second->media) return std::nullopt;
  return it->second->media->state;
}

std::optional<double> ExecutionModel::mediaTime(const vrml::Node& node) const {
  const auto it = s_->nodes.find(&node);
  if (it == s_->nodes.end() || !it->second->media) return std::nullopt;
  return it->second->media->state.mediaTime;
}

}  // namespace gs::runtime
