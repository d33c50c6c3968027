// HAnimMotion (ISO/IEC 19774-1 H-Anim 2.0 / X3D 4.0 clause 26.3.5) as X_ITE 15 plays it:
// the motions a humanoid holds in `motions` (those motionsEnabled allows) drive its joints,
// found by `name` among the humanoid's `joints` ("HumanoidRoot" also names humanoid_root).
//
// - `channels` lists, per joint of `joints`, a count and its channel names (BVH's Xposition,
//   Yposition, Zposition, Xrotation, Yrotation, Zrotation, and Xscale, Yscale, Zscale);
//   `values` holds frameCount = floor(values / channels) frames, each every channel in that
//   order. Rotations are degrees, composed in the order the channels list them (R = R1 R2
//   R3; missing axes appended in X, Y, Z order), as X_ITE's Rotation4.setEuler.
// - Frame k is at fraction k / (frameCount - 1) of a cycle of (frameCount - 1) x
//   frameDuration seconds; between frames, positions and scales are linear and rotations
//   spherical (the PositionInterpolator and OrientationInterpolator X_ITE makes).
// - The cycle starts when the motion is first met (the world's load) and plays from
//   startFrame to endFrame (0: the last frame), once (stopping on endFrame) or looping;
//   frameIncrement 0 holds
//   it on frameIndex. Each frame the joints' translation, rotation and scale are set as
//   events (routes from them run), and elapsedTime is sent while it plays, frameCount
//   once.
// - While it plays, frameIndex says the frame shown, and cycleTime goes out when a cycle
//   starts. frameIncrement < 0 plays from endFrame to startFrame. `enabled` FALSE stops
//   it where it is; TRUE again starts it from the beginning (as X_ITE restarts its
//   TimeSensor).
// - `next` / `previous` TRUE step frameIndex by |frameIncrement| (1 when it is 0, where
//   X_ITE 15 does not move), wrapping at startFrame / endFrame when it loops, ignored past
//   them otherwise (X_ITE's rule); a playing motion goes on from the new frame.
// - channelsEnabled is read per channel when it has a value for each (motionKeys), else
//   per joint, as X_ITE reads it.
// `loa` is not used (the motion names its joints, whatever level of articulation they belong to;
// X_ITE does not read it either).
#include "execution_state.hpp"

#include "vrml/transform.hpp"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string_view>

namespace gs::runtime {

using vrml::FieldType;
using vrml::FieldValue;

namespace {

/// `text` split at white space and commas.
std::vector<std::string> motionWords(const std::string& text) {
  std::vector<std::string> out;
  std::string word;
  for (char c : text) {
    if (std::isspace(static_cast<unsigned char>(c)) || c == ',') {
      if (!word.empty()) out.push_back(std::move(word));
      word.clear();
    } else {
      word += c;
    }
  }
  if (!word.empty()) out.push_back(std::move(word));
  return out;
}

/// The channels of each joint: the names after each count (X_ITE splits at the counts).
std::vector<std::vector<std::string>> motionChannels(const std::string& text) {
  std::vector<std::vector<std::string>> joints;
  for (const std::string& w : motionWords(text)) {
    const bool number = std::all_of(
        w.begin(), w.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
    if (number) {
      joints.emplace_back();
    } else {
      if (joints.empty()) joints.emplace_back();
      joints.back().push_back(w);
    }
  }
  std::erase_if(joints, [](const auto& j) { return j.empty(); });
  return joints;
}

glm::quat eulerRotation(const glm::vec3& degrees, std::string order) {
  for (char axis : std::string("XYZ"))
    if (order.size() < 3 && order.find(axis) == std::string::npos) order += axis;
  glm::quat q(1.0f, 0.0f, 0.0f, 0.0f);
  for (char axis : order.substr(0, 3)) {
    const int a = axis - 'X';
    glm::vec3 unit(0.0f);
    unit[a] = 1.0f;
    q = q * glm::angleAxis(glm::radians(degrees[a]), unit);
  }
  return q;
}

/// The key frames of every joint of `motion` and its frame count. `channelsEnabled`
/// ("boolean values for each channel", X3D 4.0 26.3.5) is read per channel when it has one
/// value for each channel a frame holds (and the joints have more channels than one each):
/// a FALSE channel is read as if `channels` did not list it (a position or scale axis
/// keeps 0 or 1, a rotation axis turns by nothing; a joint left with none is not set).
/// Otherwise it is read per joint, as X_ITE 15 reads it: a FALSE joint is not set.
/// Missing values are TRUE.
std::vector<HAnimMotionJointKeys> motionKeys(const vrml::Node& motion, std::size_t& frameCount) {
  const std::vector<std::string> joints =
      motionWords(motion.get<FieldType::SFString>("joints", std::string()));
  const std::vector<std::vector<std::string>> channels =
      motionChannels(motion.get<FieldType::SFString>("channels", std::string()));
  const std::vector<float>& values = motion.get<FieldType::MFFloat>("values", std::vector<float>{});
  const std::vector<bool>& enabled =
      motion.get<FieldType::MFBool>("channelsEnabled", std::vector<bool>{});
  std::size_t perFrame = 0;
  for (const auto& c : channels) perFrame += c.size();
  frameCount = perFrame > 0 ? values.size() / perFrame : 0;
  const bool perChannel = enabled.size() == perFrame && perFrame != channels.size();
  const auto on = [&](std::size_t i) { return i >= enabled.size() || enabled[i]; };
  std::vector<HAnimMotionJointKeys> keys(channels.size());
  std::size_t v = 0;
  for (std::size_t frame = 0; frame < frameCount; ++frame)
    for (std::size_t j = 0, channel = 0; j < channels.size(); ++j) {
      glm::vec3 position(0.0f), rotation(0.0f), scale(1.0f);
      bool hasPosition = false, hasScale = false;
      std::string order;
      const bool jointOn = perChannel || on(j);
      for (const std::string& c : channels[j]) {
        const float x = values[v++];
        if (!jointOn || (perChannel && !on(channel++))) continue;
        if (c.size() != 9 && c.size() != 6) continue;
        const int axis = c[0] - 'X';
        if (axis < 0 || axis > 2) continue;
        const std::string kind = c.substr(1);
        if (kind == "position") {
          position[axis] = x;
          hasPosition = true;
        } else if (kind == "rotation") {
          rotation[axis] = x;
          order += c[0];
        } else if (kind == "scale") {
          scale[axis] = x;
          hasScale = true;
        }
      }
      HAnimMotionJointKeys& k = keys[j];
      if (j < joints.size()) k.joint = joints[j];
      if (hasPosition) k.translation.push_back(position);
      if (!order.empty()) k.rotation.push_back(eulerRotation(rotation, order));
      if (hasScale) k.scale.push_back(scale);
    }
  return keys;
}

template <class T, class Mix>
T keyAt(const std::vector<T>& keys, double fraction, Mix mix) {
  if (keys.size() == 1) return keys.front();
  const double at = std::clamp(fraction, 0.0, 1.0) * static_cast<double>(keys.size() - 1);
  const auto k = std::min(static_cast<std::size_t>(at), keys.size() - 2);
  return mix(keys[k], keys[k + 1], static_cast<float>(at - static_cast<double>(k)));
}

/// When a motion's frames play (its fields read once): frame k is at fraction
/// k / (frameCount - 1); startFrame..endFrame span `first`..`end`, played in `interval`
/// seconds.
struct MotionTiming {
  double last = 1.0;  // frameCount - 1, at least 1
  double first = 0.0, end = 1.0;
  double interval = 0.0;  // seconds
  int increment = 1;      // frameIncrement: 0 holds, < 0 plays backwards
  bool loop = false;
  std::size_t frameCount = 0;

  bool playing() const { return increment != 0 && interval > 0.0 && frameCount > 1; }
  double frameFraction(int frame) const {
    return std::clamp(frame, 0, static_cast<int>(frameCount) - 1) / last;
  }
  /// The fraction shown after `played` (0..1) of the interval.
  double fractionPlayed(double played) const {
    return increment > 0 ? first + played * (end - first) : end - played * (end - first);
  }
  /// `fractionPlayed`'s inverse (0 when startFrame is endFrame).
  double playedAt(double fraction) const {
    if (end <= first) return 0.0;
    const double p = (fraction - first) / (end - first);
    return increment > 0 ? p : 1.0 - p;
  }
  int frameAt(double fraction) const {
    return static_cast<int>(std::floor(fraction * last + 1e-6));
  }
};

MotionTiming motionTiming(const vrml::Node& motion, std::size_t frameCount) {
  MotionTiming t;
  t.frameCount = frameCount;
  t.last = static_cast<double>(std::max<std::size_t>(frameCount, 2) - 1);
  const auto frameField = [&](std::string_view name) {
    return std::clamp(motion.get<FieldType::SFInt32>(name, 0), 0, static_cast<int>(frameCount) - 1);
  };
  // endFrame 0, the field's default, is the last frame (X_ITE sets it so when it reads the
  // values).
  t.first = frameField("startFrame") / t.last;
  const int endFrame = motion.get<FieldType::SFInt32>("endFrame", 0);
  t.end = std::max(t.first, (endFrame > 0 ? frameField("endFrame") : t.last) / t.last);
  const double cycle = t.last * std::max(0.0, motion.get<FieldType::SFTime>("frameDuration", 0.1));
  t.interval = cycle * (t.end - t.first);
  t.increment = motion.get<FieldType::SFInt32>("frameIncrement", 1);
  t.loop = motion.get<FieldType::SFBool>("loop", false);
  return t;
}

}  // namespace

void ExecutionModel::State::stepHAnimMotion(NodeState& ns, int direction) {
  if (!ns.motion || ns.motion->frameCount == 0) return;  // not met in a humanoid yet
  HAnimMotionState& st = *ns.motion;
  const vrml::Node& motion = *ns.node;
  const MotionTiming t = motionTiming(motion, st.frameCount);
  const int lo = t.frameAt(t.first), hi = t.frameAt(t.end);
  const int step = std::max(1, std::abs(t.increment));
  int frame = t.frameAt(st.fraction) + step * direction;
  if (frame > hi || frame < lo) {
    if (!t.loop) return;
    frame = frame > hi ? lo : hi;
  }
  st.fraction = t.frameFraction(frame);
  st.frameSent = frame;
  emitOwn(ns, motion.type().findExact("frameIndex"), FieldValue::make<FieldType::SFInt32>(frame));
  if (t.playing()) {  // it goes on from the new frame
    st.startedAt = model.now() - t.playedAt(st.fraction) * t.interval;
    st.stopped = false;
  }
}

void ExecutionModel::State::enableHAnimMotion(NodeState& ns) {
  if (!ns.motion) return;  // not met in a humanoid yet: it starts when it is
  HAnimMotionState& st = *ns.motion;
  const bool enabled = ns.node->get<FieldType::SFBool>("enabled", true);
  if (enabled && !st.enabled) {
    st.startedAt = model.now();
    st.stopped = false;
    st.cycleSent = -1;
  }
  st.enabled = enabled;
}

void ExecutionModel::State::evaluateHAnimMotions() {
  const double now = model.now();
  for (NodeState* h : skins) {
    if (!h->skin || !h->skin->humanoid) continue;
    const vrml::Node& humanoid = *h->node;
    const auto& motions = humanoid.mfnode("motions");
    if (motions.empty()) continue;
    const std::vector<bool> enabledList =
        humanoid.get<FieldType::MFBool>("motionsEnabled", std::vector<bool>{});
    for (std::size_t i = 0; i < motions.size(); ++i) {
      const vrml::NodePtr& m = motions[i];
      if (!m || m->typeId() != vrml::NodeTypeId::HAnimMotion) continue;
      if (i < enabledList.size() && !enabledList[i]) continue;
      NodeState& ms = reach(m, false);
      if (!ms.motion) ms.motion = std::make_unique<HAnimMotionState>();
      HAnimMotionState& st = *ms.motion;
      const vrml::Node& motion = *m;
      if (!motion.get<FieldType::SFBool>("enabled", true)) continue;
      if (st.revision != motion.revision()) {
        st.revision = motion.revision();
        st.keys = motionKeys(motion, st.frameCount);
      }
      const auto out = [&](std::string_view name, FieldValue v) {
        const int f = motion.type().findExact(name);
        if (f >= 0 && motion.type().fields[static_cast<std::size_t>(f)].type == v.type())
          emitOwn(ms, f, std::move(v));
      };
      if (!st.frameCountSent) {
        st.frameCountSent = true;
        out("frameCount", FieldValue::make<FieldType::SFInt32>(static_cast<int>(st.frameCount)));
      }
      if (st.frameCount == 0) continue;
      const MotionTiming timing = motionTiming(motion, st.frameCount);
      double fraction = timing.frameFraction(motion.get<FieldType::SFInt32>("frameIndex", 0));
      if (!st.startedAt) st.startedAt = now;
      if (timing.playing()) {
        const double elapsed = now - *st.startedAt;
        double played = 0.0;  // of the interval from startFrame to endFrame
        if (timing.loop) {
          const double cycles = elapsed / timing.interval;
          const auto cycle = static_cast<std::int64_t>(std::floor(cycles));
          played = cycles - std::floor(cycles);
          if (cycle != st.cycleSent) {
            st.cycleSent = cycle;
            out("cycleTime", FieldValue::make<FieldType::SFTime>(
                                 *st.startedAt + static_cast<double>(cycle) * timing.interval));
          }
          out("elapsedTime", FieldValue::make<FieldType::SFTime>(elapsed));
        } else if (elapsed >= timing.interval) {
          played = 1.0;
          if (st.stopped) continue;  // the last frame was set: the joints are left alone
          st.stopped = true;
        } else {
          played = elapsed / timing.interval;
          if (st.cycleSent != 0) {
            st.cycleSent = 0;
            out("cycleTime", FieldValue::make<FieldType::SFTime>(*st.startedAt));
          }
          out("elapsedTime", FieldValue::make<FieldType::SFTime>(elapsed));
        }
        fraction = timing.fractionPlayed(played);
        // frameIndex says the frame shown while it plays (the nearest one at or before).
        if (const int frame = timing.frameAt(fraction); frame != st.frameSent) {
          st.frameSent = frame;
          out("frameIndex", FieldValue::make<FieldType::SFInt32>(frame));
        }
      }
      st.fraction = fraction;
      // The joints by name (X_ITE: trimmed names, "HumanoidRoot" for humanoid_root).
      for (std::size_t j = 0; j < st.keys.size(); ++j) {
        const HAnimMotionJointKeys& k = st.keys[j];
        if (k.translation.empty() && k.rotation.empty() && k.scale.empty()) continue;
        vrml::Node* joint = nullptr;
        for (const vrml::NodePtr& candidate : humanoid.mfnode("joints")) {
          if (!candidate) continue;
          std::string name = candidate->get<FieldType::SFString>("name", std::string());
          name.erase(0, name.find_first_not_of(" \t\n\r"));
          name.erase(name.find_last_not_of(" \t\n\r") + 1);
          if (name == k.joint || (k.joint == "HumanoidRoot" && name == "humanoid_root")) {
            joint = candidate.get();
            break;
          }
        }
        if (joint == nullptr || k.joint == "IGNORED") continue;
        NodeState& js = reach(*joint, false);
        const auto set = [&](const char* name, FieldValue v) {
          const int f = joint->type().findExact(name);
          if (f >= 0 && joint->type().fields[static_cast<std::size_t>(f)].type == v.type())
            queue.push_back({&js, f, std::move(v)});
        };
        const auto lerp = [](const glm::vec3& a, const glm::vec3& b, float t) {
          return glm::mix(a, b, t);
        };
        if (!k.translation.empty())
          set("translation",
              FieldValue::make<FieldType::SFVec3f>(keyAt(k.translation, fraction, lerp)));
        if (!k.scale.empty())
          set("scale", FieldValue::make<FieldType::SFVec3f>(keyAt(k.scale, fraction, lerp)));
        if (!k.rotation.empty()) {
          const glm::quat q = keyAt(
              k.rotation, fraction,
              [](const glm::quat& a, const glm::quat& b, float t) { return glm::slerp(a, b, t); });
          set("rotation",
              FieldValue::make<FieldType::SFRotation>(vrml::rotationFromQuaternion(glm::dquat(q))));
        }
      }
    }
  }
}

}  // namespace gs::runtime
