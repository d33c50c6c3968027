// MovieTexture (6.28) and AudioClip (6.3) as time-dependent nodes (4.6.9): the rules of
// time_dependent.cpp with a cycle of duration / |rate|, duration_changed once the
// application knows the duration, and the media time the renderer and the audio output
// read (runtime/media_time.hpp).
#include "execution_state.hpp"

#include <cmath>

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

}  // namespace

bool ExecutionModel::State::classifyMedia(NodeState& ns) {
  const vrml::NodeType& type = ns.node->type();
  const bool movie = type.id() == vrml::NodeTypeId::MovieTexture;
  if (!movie && type.id() != vrml::NodeTypeId::AudioClip) return false;
  ns.role = NodeRole::media;
  ns.media = std::make_unique<MediaNode>();
  MediaNode& m = *ns.media;
  m.loop = type.findExact("loop");
  m.startTime = type.findExact("startTime");
  m.stopTime = type.findExact("stopTime");
  m.rate = type.findExact(movie ? "speed" : "pitch");
  m.durationChanged = type.findExact("duration_changed");
  m.isActive = type.findExact("isActive");
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
  if (!m.time.active) st.rate = rateOf(n, m);
  const double duration = st.duration && *st.duration > 0.0 ? *st.duration : 0.0;
  TimeFields f;
  f.startTime = fieldOr<FieldType::SFTime>(n, m.startTime, 0.0);
  f.stopTime = fieldOr<FieldType::SFTime>(n, m.stopTime, 0.0);
  f.loop = fieldOr<FieldType::SFBool>(n, m.loop, false);
  // No known duration, speed 0 or a pitch <= 0 (6.3: undefined): a node that never starts.
  const bool playable =
      duration > 0.0 && std::isfinite(st.rate) && (st.movie ? st.rate != 0.0 : st.rate > 0.0);
  f.cycleInterval = playable ? duration / std::fabs(st.rate) : 0.0;
  const TimeStep step = evaluateTime(m.time, f, model.now());
  if (step.activated) emitOwn(ns, m.isActive, FieldValue::make<FieldType::SFBool>(true));
  if (step.output) {
    st.mediaTime = mediaTimeAt(step.fraction, duration, st.rate);
  } else if (!m.everStarted) {
    // Not started yet: frame 0, or the last frame for a movie played backwards (6.28).
    st.mediaTime = st.movie && st.rate < 0.0 ? duration : 0.0;
  }
  if (step.activated) m.everStarted = true;
  if (step.deactivated) emitOwn(ns, m.isActive, FieldValue::make<FieldType::SFBool>(false));
  st.active = m.time.active;
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
