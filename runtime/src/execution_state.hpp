// Private to runtime/: the state behind ExecutionModel, shared by its source files.
#pragma once

#include "media_nodes.hpp"
#include "runtime/execution_model.hpp"
#include "runtime/interpolators.hpp"
#include "runtime/interpolators_x3d.hpp"
#include "runtime/time_dependent.hpp"

#include "dis/pdu.hpp"
#include "dis/udp_socket.hpp"
#include "geometry/geometry.hpp"
#include "particles/particle_system.hpp"
#include "physics/rigid_body_world.hpp"

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <variant>
#include <vector>

namespace gs::runtime {

/// What the execution model does with events a node receives.
enum class NodeRole : std::uint8_t {
  plain,            // exposedFields store and echo; set_x eventIns write field x
  timeSensor,       // 6.50
  interpolator,     // 4.6.8
  bindable,         // 4.6.10
  script,           // 4.12
  grouping,         // addChildren / removeChildren (6.21, 6.52, ...)
  proximity,        // ProximitySensor (6.38)
  visibility,       // VisibilitySensor (6.52)
  transformSensor,  // X3D TransformSensor (X3D 4.0 clause 22.4.3): environment_sensors.cpp
  media,            // MovieTexture (6.28), AudioClip (6.3): media_nodes.cpp
  eventUtility,     // X3D Event Utilities (X3D 4.0 clause 30): event_utilities.cpp
  follower,         // X3D Followers, dampers and chasers (X3D 4.0 clause 39): followers.cpp
  keySensor,        // X3D KeySensor, StringSensor (X3D 4.0 clause 21): key_sensors.cpp
  loadSensor,       // X3D LoadSensor (X3D 4.0 clause 9.4.3): load_sensors.cpp
  // X3D NURBS interpolators (X3D 4.0 27.4.5, 27.4.6, 27.4.9): interpolators_nurbs.cpp
  nurbsInterpolator,
  geoInterpolator,  // X3D GeoPositionInterpolator (X3D 4.0 25.4.9): geo_interpolator.cpp
};

/// The X3D event-utility nodes (X3D 4.0 clause 30).
enum class EventUtilityKind : std::uint8_t {
  booleanFilter,
  booleanToggle,
  booleanTrigger,
  integerTrigger,
  timeTrigger,
  booleanSequencer,
  integerSequencer,
};

/// Field indices of an event-utility node (found once), -1 when absent, and the
/// sequencers' position in keyValue.
struct EventUtilityFields {
  EventUtilityKind kind = EventUtilityKind::booleanFilter;
  int input = -1;  // set_boolean, set_triggerTime; set_fraction (sequencers)
  int next = -1, previous = -1, key = -1, keyValue = -1;  // sequencers
  int value = -1;                                         // toggle, integerKey
  std::array<int, 3> out{-1, -1, -1};  // inputTrue / inputFalse / inputNegate, triggerTrue,
                                       // triggerValue, triggerTime, value_changed
  int index = -1;                      // sequencers: the keyValue last sent, -1 before any
};

/// One node waiting in a Skin's skeleton walk (skin.cpp): its parent's matrix and depth.
struct SkeletonItem {
  const vrml::Node* node = nullptr;
  glm::mat4 parent{1.0f};
  int depth = 0;
};

/// A Skin's record (skin.cpp): its field indices (found once, -1 when absent), the
/// signature of the skeleton it last skinned with, and buffers reused from one evaluation
/// to the next.
struct SkinState {
  int skeleton = -1, joints = -1, inverseBindMatrices = -1, skinnedTransform = -1;
  int coord = -1, normal = -1, restPoint = -1, restNormal = -1;
  int vertexJoints = -1, vertexWeights = -1;
  std::uint64_t signature = 0;
  bool evaluated = false;
  bool problemReported = false;
  std::unordered_map<const vrml::Node*, glm::mat4> matrices;  // skeleton node -> matrix
  std::vector<SkeletonItem> stack;
  std::vector<glm::mat4> jointMatrices;
  // An HAnimHumanoid's skin (skin.cpp): skinCoord's points and skinNormal's vectors
  // as they were first seen (the bind pose), and the inverse of each node's matrix then.
  bool humanoid = false;
  int skinCoord = -1, skinNormal = -1;
  std::vector<glm::vec3> bindPoints, bindNormals;
  std::unordered_map<const vrml::Node*, glm::mat4> bindInverse;
  /// HAnimSegments with displacers: their coord's points as first seen, and the
  /// displacers' revisions they were displaced for.
  std::unordered_map<const vrml::Node*, std::pair<std::vector<glm::vec3>, std::uint64_t>>
      segmentRest;
  std::vector<glm::vec3> sum;
  std::vector<float> weight;
};

/// What an X3D pick sensor last sent (pick_sensors.cpp).
struct PickSensorState {
  bool active = false;
  std::vector<const vrml::Node*> picked;  // the pickTarget members picked
  std::vector<glm::vec3> points;          // pickedPoint (Point and Line sensors)
};

/// A ParticleSystem's simulation (particle_systems.cpp).
struct ParticleSystemState {
  ParticleSystemState(std::uint64_t seed, double loadTime) : simulation(seed, loadTime) {}
  particles::ParticleSimulation simulation;
  int isActive = -1;  // field index of isActive
  bool sentActive = false;
  bool reportedClamp = false;
};

/// A RigidBodyCollection's Bullet world (rigid_body_physics.cpp).
struct RigidBodyCollectionState {
  std::unique_ptr<physics::RigidBodyWorld> world;
  double lastTime = 0.0;  // SFTime of the last step (or of the build)
  /// Each body's revision() after the world last wrote its outputs: another means an event
  /// set its fields (resetBody).
  std::unordered_map<const vrml::Node*, std::uint64_t> bodyRevisions;
  std::size_t warningsReported = 0;
};

/// The datagrams that arrived on one UDP address:port (dis_nodes.cpp): read once per
/// frame, decoded, and shared by every DIS node listening there.
struct DisInbox {
  std::unique_ptr<dis::UdpReceiver> socket;
  std::vector<dis::Pdu> pdus;  // this frame's, oldest first
  /// Per alternative of dis::Pdu: the index in `pdus` of the latest PDU of each entity
  /// (Entity State) or radio (Transmitter, Signal, Receiver), by disEntityKey/disRadioKey.
  std::array<std::unordered_map<std::uint64_t, std::size_t>, std::variant_size_v<dis::Pdu>> latest;
  std::size_t dropped = 0;  // datagrams that did not decode, since the socket opened
};

/// An entity a DISEntityManager made an EspduTransform for (dis_nodes.cpp).
struct DisEntityRecord {
  vrml::NodePtr transform;  // the EspduTransform sent in addedEntities
  double lastHeard = 0.0;   // SFTime of its latest Entity State PDU
};

/// A DIS node's record (dis_nodes.cpp): an EspduTransform, ReceiverPdu, SignalPdu or
/// TransmitterPdu (the UDP port it reads, when it last read, the latest PDU of its entity
/// or radio not yet sent), or a DISEntityManager (the entities it made).
struct EspduState {
  /// Its receiver in State::disReceivers ("address:port"), "" none.
  std::string key;
  double lastRead = -1e300;       // SFTime of the last read (readInterval apart)
  double lastWrite = -1e300;      // SFTime of the last PDU written (writeInterval apart)
  bool reported = false;          // a problem with its socket was reported
  bool dropReported = false;      // datagrams that did not decode were reported
  bool announced = false;         // isNetworkReader / isStandAlone sent
  bool active = false;            // isActive TRUE sent
  bool limitReported = false;     // a DISEntityManager: its entity limit was reported
  bool fireSent = false;          // a networkWriter: the Fire PDU of fired1/fired2 TRUE went
  std::uint16_t rtpSequence = 0;  // a networkWriter with rtpHeaderExpected: the next RTP one
  /// The latest PDU of its entity or radio since its last read.
  std::optional<dis::Pdu> pending;
  /// An EspduTransform reader: the last Entity State PDU read and when, which dead
  /// reckoning moves on from between reads.
  std::optional<dis::EntityStatePdu> reckoned;
  double reckonedAt = 0.0;
  /// A DISEntityManager: the entities it made, by entity (site, application, entity).
  std::unordered_map<std::uint64_t, DisEntityRecord> entities;
};

/// What a CollisionSensor last sent (rigid_body_physics.cpp), and the Contact nodes it
/// reuses from frame to frame.
struct CollisionSensorState {
  int isActive = -1, contacts = -1, intersections = -1;
  bool active = false;
  std::vector<vrml::NodePtr> contactNodes;
};

/// A damper's or chaser's motion (followers.cpp); values as flat lists of numbers.
struct FollowerState {
  bool damper = false;
  vrml::FieldType type = vrml::FieldType::SFFloat;  // of value_changed
  int setDestination = -1, setValue = -1, valueChanged = -1, isActive = -1;
  int tau = -1, tolerance = -1;  // dampers' inputOutput fields
  int order = 3;                 // dampers: stages, 0..5
  double duration = 1.0;         // chasers: seconds to reach a destination
  bool active = false;           // moving
  bool announced = false;        // isActive TRUE sent for this motion
  double lastTime = 0.0;
  std::vector<std::vector<double>> buffer;  // dampers: [0] the destination, then the stages
  std::vector<double> base, destination;    // chasers: value before the pending steps
  struct Step {
    double time = 0.0;
    std::vector<double> delta;  // destination change made at `time`
  };
  std::vector<Step> steps;  // chasers: changes still blending in
};

/// A KeySensor's or StringSensor's record (key_sensors.cpp): its field indices (found
/// once, -1 when absent), the keys it saw go down, a StringSensor's text.
struct KeySensorState {
  bool string = false;  // StringSensor (else KeySensor)
  int enabled = -1, isActive = -1;
  int keyPress = -1, keyRelease = -1, actionKeyPress = -1, actionKeyRelease = -1;  // KeySensor
  int shiftKey = -1, controlKey = -1, altKey = -1;                                 // KeySensor
  int deletionAllowed = -1, enteredText = -1, finalText = -1;                      // StringSensor
  bool active = false;    // isActive TRUE was sent last
  std::vector<Key> held;  // KeySensor: keys down, in press order
  std::string text;       // StringSensor: enteredText (UTF-8)
};

/// A LoadSensor's record (load_sensors.cpp): its field indices (found once, -1 when
/// absent) and the watch under way.
struct LoadSensorState {
  int enabled = -1, timeOut = -1, children = -1;
  int isActive = -1, isLoaded = -1, loadTime = -1, progress = -1;
  bool watching = false;  // a watch started and has not reported its end
  bool active = false;    // isActive TRUE was sent last
  double started = 0.0;   // SFTime the watch started (timeOut counts from here)
  float progressSent = -1.0f;
};

struct NodeState;

/// Whether writing `value` (an SFNode or MFNode) into field `field` of `target` would make
/// `target` its own descendant: the value holds `target`, or a node whose node-valued
/// fields lead to it (graph_cycles.cpp; fields that name nodes placed elsewhere, a
/// Script's, TransformSensor.targetObject, pickTarget, LoadSensor's, are not followed,
/// and a write into one is never refused). Other values: false.
bool wouldContainItself(const vrml::Node& target, int field, const vrml::FieldValue& value);
/// Empties each field of `node` that names nodes placed elsewhere (as above) and leads,
/// through any node-valued fields, back to `node`: a cycle of owners that would outlive
/// the world (graph_cycles.cpp). Other fields are left as they are.
void breakReferenceCycles(vrml::Node& node);

/// Appends the nodes of `n`'s SFNode and MFNode fields to `pending`, in field order (the
/// walks over a world that keep their own list instead of recursing).
inline void pushChildNodes(const vrml::Node& n, std::vector<vrml::Node*>& pending) {
  for (std::size_t i = 0; i < n.fieldCount(); ++i) {
    const vrml::FieldValue& v = n.fieldAt(i);
    if (v.type() == vrml::FieldType::SFNode) {
      if (const vrml::NodePtr& c = v.get<vrml::FieldType::SFNode>()) pending.push_back(c.get());
    } else if (v.type() == vrml::FieldType::MFNode) {
      for (const vrml::NodePtr& c : v.get<vrml::FieldType::MFNode>())
        if (c) pending.push_back(c.get());
    }
  }
}

/// One route from an eventOut, resolved: the receiving node and its field index.
struct RouteTarget {
  NodeState* to = nullptr;
  int field = -1;
  bool operator==(const RouteTarget&) const = default;
};

/// An eventOut's routes and the stamp of the last event it sent, side by side so that
/// sending touches one record (4.10.3).
/// The first route is kept in the record itself (most eventOuts have at most one), the
/// others in `more`, in the order they were added.
struct OutPort {
  std::uint64_t lastSent = 0;
  RouteTarget first;  // first.to null: no route
  std::vector<RouteTarget> more;

  /// Adds `t`; false when it is there already (4.10.2: a duplicate ROUTE is ignored).
  bool add(const RouteTarget& t) {
    if (first.to == nullptr) {
      first = t;
      return true;
    }
    if (first == t) return false;
    for (const RouteTarget& r : more)
      if (r == t) return false;
    more.push_back(t);
    return true;
  }
  /// Whether `t` is among the routes.
  bool has(const RouteTarget& t) const {
    if (first.to != nullptr && first == t) return true;
    return std::find(more.begin(), more.end(), t) != more.end();
  }
  /// Removes `t`; false when it is not there.
  bool remove(const RouteTarget& t) {
    if (first.to != nullptr && first == t) {
      if (more.empty()) {
        first = {};
      } else {
        first = more.front();
        more.erase(more.begin());
      }
      return true;
    }
    for (auto r = more.begin(); r != more.end(); ++r)
      if (*r == t) {
        more.erase(r);
        return true;
      }
    return false;
  }
};

/// One joint's key frames of an HAnimMotion (hanim_motion.cpp); empty: not driven.
struct HAnimMotionJointKeys {
  std::string joint;  // the joint's name
  std::vector<glm::vec3> translation, scale;
  std::vector<glm::quat> rotation;
};

/// What the execution model keeps of one HAnimMotion (hanim_motion.cpp).
struct HAnimMotionState {
  std::uint64_t revision = ~std::uint64_t{0};  // of the fields the keys were made from
  std::vector<HAnimMotionJointKeys> keys;
  std::size_t frameCount = 0;
  std::optional<double> startedAt;  // when the cycle started (the first evaluation)
  bool stopped = false;             // a motion that does not loop, after its last frame
  bool frameCountSent = false;
  bool enabled = true;          // `enabled` as last set (TRUE after FALSE restarts it)
  double fraction = 0.0;        // of the frames, at the last evaluation
  int frameSent = -1;           // the frameIndex last sent while it played
  std::int64_t cycleSent = -1;  // the cycle whose cycleTime went out
};

/// Field indices of a TimeSensor (6.50), -1 when absent.
struct TimeSensorFields {
  int cycleInterval = -1, enabled = -1, loop = -1, startTime = -1, stopTime = -1;
  int cycleTime = -1, fraction = -1, isActive = -1, time = -1;
};

/// The execution model's record of one node. Its first cache line holds what every event
/// to it reads (node, role, ports, prefetch hints), its second the role's field indices:
/// runCascade() prefetches both lines ahead of the event.
struct alignas(64) NodeState {
  vrml::Node* node = nullptr;
  NodeRole role = NodeRole::plain;
  bool scriptHadEvents = false;
  bool problemReported = false;
  /// Bit i set: eventOut i (< 32) has had a route (set by connect(), never cleared). An
  /// event from a field whose bit is clear is counted and goes nowhere without its port
  /// being read (emit); fields from 32 on always read their port.
  std::uint32_t routedFields = 0;
  /// Per field index: routes leaving it, and the stamp of the last event it sent.
  std::vector<OutPort> out;
  /// Where the node's fields, and an interpolator's key and keyValue elements, were last
  /// seen: addresses runCascade() prefetches ahead of the event (never read through: a
  /// stale one costs a wasted prefetch, not a fault).
  const vrml::FieldValue* fieldsHint = nullptr;
  const void* keysHint = nullptr;
  const void* keyValuesHint = nullptr;
  // Field indices used by the role (from the node table, found once).
  int setFraction = -1, key = -1, keyValue = -1, valueChanged = -1;  // interpolators
  int keyVelocity = -1, closed = -1, normalizeVelocity = -1;         // X3D spline interpolators
  int setBind = -1, isBound = -1, bindTime = -1;                     // bindables
  int addChildren = -1, removeChildren = -1, children = -1;          // grouping
  // NurbsSurfaceInterpolator's normal_changed (valueChanged: its position_changed).
  int normalChanged = -1;
  InterpolatorKind interpolator = InterpolatorKind::Scalar;
  BindableKind bindable = BindableKind::Viewpoint;
  /// The node, kept alive for as long as the execution model lives (node identity): once
  /// registered, a node's address names that node and no other while this record exists,
  /// so a node freed by a `children` assignment cannot lend its record (role, field
  /// indices, routes) to a node later allocated at the same address. Null only for a node
  /// first met without an owning pointer (an event to a node the caller owns).
  vrml::NodePtr keepAlive;
  TimeSensorFields timeFields;
  TimeState time;
  /// TimeSensor: its time fields as last read, valid while node->revision() is
  /// timeFieldsRevision (every write bumps the revision: the change contract).
  TimeFields timeFieldsCache;
  std::uint64_t timeFieldsRevision = ~std::uint64_t{0};
  bool sensorActive = false;  // ProximitySensor / VisibilitySensor: the viewer is inside / sees it
  glm::vec3 lastPosition{0.0f};
  vrml::Rotation lastOrientation{0.0f};
  std::unique_ptr<ScriptInstance> script;
  std::unique_ptr<MediaNode> media;                       // role media
  std::unique_ptr<EventUtilityFields> utility;            // role eventUtility
  std::unique_ptr<FollowerState> follower;                // role follower
  std::unique_ptr<SkinState> skin;                        // a Skin (role plain)
  std::unique_ptr<KeySensorState> keys;                   // role keySensor
  std::unique_ptr<LoadSensorState> load;                  // role loadSensor
  std::unique_ptr<ParticleSystemState> particles;         // a ParticleSystem (role plain)
  std::unique_ptr<PickSensorState> pick;                  // an X3D pick sensor (role plain)
  std::unique_ptr<RigidBodyCollectionState> rigidBodies;  // a RigidBodyCollection (plain)
  std::unique_ptr<CollisionSensorState> collision;        // a CollisionSensor (plain)
  std::unique_ptr<EspduState> espdu;                      // an EspduTransform (plain)
  std::unique_ptr<HAnimMotionState> motion;               // an HAnimMotion (plain)
  // Rarely read, so after the lines runCascade() fetches:
  bool cycleReported = false;  // an event that would make it its own descendant was refused
  /// Its world was unloaded (Browser.replaceWorld): in no list, its Script shut down. A take
  /// of a world that holds it again (a new Inline of the same world, a replaceWorld with
  /// it) registers it afresh (State::reach).
  bool unloaded = false;
};
static_assert(offsetof(NodeState, setFraction) == 64, "NodeState's first line: see above");

/// An event waiting to be delivered to eventIn `field` of `to`.
struct PendingEvent {
  NodeState* to = nullptr;
  int field = -1;
  vrml::FieldValue value;
};

/// Pointing-device sensors' state (pointer_sensors.cpp).
struct PointerState;
struct PointerStateDeleter {
  void operator()(PointerState* p) const;
};

struct ExecutionModel::State {
  ExecutionModel& model;
  std::shared_ptr<const vrml::Scene> scene;
  /// An Inline's scene and how much of it was taken in (it may still be growing).
  struct InlineCursor {
    std::shared_ptr<const vrml::Scene> scene;
    std::size_t roots = 0, hidden = 0, routes = 0;
  };
  std::vector<InlineCursor> inlineScenes;
  /// The Inline's world whose nodes takeScene is reaching (null for the main world; for
  /// createSceneFromString's, the asking Script's world or the text's own scene), and the
  /// world each Script and Anchor reached so came from (ScriptContext::sceneOf, requestUrl;
  /// an InlineCursor or urlScenes keeps the scene alive).
  const vrml::Scene* reachingInline = nullptr;
  std::unordered_map<const vrml::Node*, const vrml::Scene*> nodeScenes;
  std::unordered_set<const vrml::Scene*> inlineSceneSet;
  /// The world each Inline node showed (ExecutionModel::noteInlineWorld), and the Inline
  /// worlds unloaded with the world that held their Inline nodes: such a world is taken
  /// again only when an Inline that was not unloaded shows it.
  std::unordered_map<const vrml::Node*, const vrml::Scene*> inlineWorlds;
  std::unordered_set<const vrml::Scene*> unloadedInlineScenes;
  bool worldReplaced = false;  // Browser.replaceWorld was called (ExecutionModel::worldReplaced)
  /// The level each LOD shows as drawing last said (ExecutionModel::sendDrawnOutputs,
  /// drawn_outputs.cpp; VRML97's LOD too, which has no level_changed): what the sensors'
  /// walks follow. A LOD not listed shows its first level. (A GeoLOD's shown nodes are its
  /// `children` output's value.)
  std::unordered_map<const vrml::Node*, int> shownLevels;
  /// How many nodes the world's Scripts made (createSceneFromString), counted against
  /// ScriptLimits::madeNodes. A count suffices: the model registers them, and keeps every
  /// node it registered alive for the world's life.
  std::size_t madeNodes = 0;
  /// reach() registers afresh the nodes it meets that were unloaded (set while a world is
  /// taken: takeScene, replaceWorld's new roots).
  bool revivingUnloaded = false;
  /// ExecutionModel::worldLoaded was called (INITIALIZED_EVENT goes out once).
  bool worldLoadedSent = false;
  /// The scenes takeScene is reading now (innermost last): a root a Script adds to one of
  /// them meanwhile is only appended (the take reaches it), and none is removed.
  std::vector<const vrml::Scene*> taking;
  bool isTaking(const vrml::Scene& s) const {
    return std::find(taking.begin(), taking.end(), &s) != taking.end();
  }
  /// The scenes of texts Scripts read from a URL (createVrmlFromURL): the world of the
  /// Scripts among their nodes (nodeScenes), kept as long as the model.
  std::vector<std::shared_ptr<const vrml::Scene>> urlScenes;
  std::unordered_map<const vrml::Node*, std::unique_ptr<NodeState>> nodes;
  std::vector<NodeState*> timeSensors;
  std::vector<NodeState*> scripts;
  std::vector<NodeState*> mediaNodes;        // MovieTextures and AudioClips
  std::vector<NodeState*> skins;             // Skin nodes (skin.cpp)
  std::vector<NodeState*> followers;         // dampers and chasers (followers.cpp)
  std::vector<NodeState*> transformSensors;  // X3D TransformSensors (environment_sensors.cpp)
  std::vector<NodeState*> keySensors;        // KeySensors, StringSensors (key_sensors.cpp)
  std::vector<NodeState*> loadSensors;       // LoadSensors (load_sensors.cpp)
  std::vector<NodeState*> particleSystems;   // ParticleSystems (particle_systems.cpp)
  std::vector<NodeState*> pickSensors;       // X3D pick sensors (pick_sensors.cpp)
  // RigidBodyCollections and CollisionSensors (rigid_body_physics.cpp); the collections
  // whose world is not built yet.
  std::vector<NodeState*> rigidBodyCollections, collisionSensors, newRigidBodyCollections;
  /// The DIS nodes (dis_nodes.cpp: EspduTransforms, ReceiverPdus, SignalPdus,
  /// TransmitterPdus, DISEntityManagers, and the EspduTransforms the managers made) and
  /// the UDP receivers they read, by "address:port".
  std::vector<NodeState*> espduTransforms;
  std::unordered_map<std::string, DisInbox> disReceivers;
  /// The tessellations the pick sensors test, with the revisionWithFields they were made
  /// at (made again only when their geometry changed).
  vrml::NodeMap<std::pair<std::uint64_t, vrml::Mesh>> pickMeshes;
  std::vector<NodeState*> newLoadSensors;  // registered, their first watch not started
  /// What loaders reported of url objects (ExecutionModel::setUrlObjectState).
  std::unordered_map<const vrml::Node*, UrlLoadState> urlStates;
  std::size_t environmentSensors = 0;  // ProximitySensors and VisibilitySensors met
  /// The ProximitySensors, VisibilitySensors and TransformSensors that the last walk found
  /// active: one the next walk does not meet (a Switch or LOD turned away) goes inactive.
  std::vector<NodeState*> activeEnvironmentSensors;
  std::unordered_set<NodeState*> sensorScratch;  // evaluateEnvironmentSensors' sets, reused
  std::vector<NodeState*> sensorsMet;            // and the sensors its walk met, reused
  std::optional<ViewerPose> viewer;
  std::vector<NodeState*> newScripts;  // registered, initialize() not yet called
  /// Scripts whose url files are still on their way (FetchMode::background): made and
  /// initialized by startArrivedScripts() once every file they may need has answered.
  std::vector<NodeState*> arrivingScripts;
  std::array<std::vector<NodeState*>, kBindableKindCount> stacks;      // bottom first
  std::array<std::vector<NodeState*>, kBindableKindCount> candidates;  // file order
  /// The events of the cascade, first in first out: `queue[queueHead]` is next (a vector
  /// reused from cascade to cascade, no allocation per event once it has grown).
  std::vector<PendingEvent> queue;
  std::size_t queueHead = 0;
  std::vector<PendingEvent> posted;
  std::uint64_t stamp = 0;
  std::size_t eventsThisCascade = 0;
  bool cascadeOverflow = false;
  std::size_t rootsSeen = 0, hiddenSeen = 0, routesSeen = 0;
  std::unique_ptr<PointerState, PointerStateDeleter> pointer;

  explicit State(ExecutionModel& m) : model(m) {}

  // ---- graph (execution_model.cpp) ----
  /// The state of `node`, registering it (and every node reachable from its SFNode and
  /// MFNode fields) when new. `bindables`: whether bindable nodes join the candidates.
  NodeState& reach(vrml::Node& node, bool bindables);
  /// As reach(Node&), and keeps `node` alive with its record (NodeState::keepAlive).
  NodeState& reach(const vrml::NodePtr& node, bool bindables);
  void takeScene(const vrml::Scene& s, std::size_t& roots, std::size_t& hidden, std::size_t& routes,
                 bool bindables);
  /// takeScene of an Inline's world: its Scripts are known to come from it.
  void takeInlineScene(InlineCursor& c);
  bool connect(vrml::Node& from, int fromField, vrml::Node& to, int toField);

  // ---- events (execution_model.cpp) ----
  void emit(NodeState& from, int field, const vrml::FieldValue& value);
  void emitOwn(NodeState& from, int field, vrml::FieldValue value);
  void runCascade();
  void initializeScripts();
  /// Whether a url file `script` may run from is still on its way: each entry that is
  /// not inline source is asked for in the background, in order, up to the first that
  /// arrived (a frame never waits for a Script's file; the factory's fetchText then
  /// finds it ready).
  bool scriptFilesArriving(const vrml::Node& script);
  /// Makes and initializes the arrivingScripts whose files have all answered.
  void startArrivedScripts();

  // ---- node roles (node_roles.cpp) ----
  void classify(NodeState& ns);
  void deliver(NodeState& ns, int field, vrml::FieldValue value);
  void evaluateTimeSensor(NodeState& ns);
  void bind(NodeState& ns, bool on);
  void bindFirstCandidates();
  /// Browser.replaceWorld: the candidates made those reached from `roots` in file order
  /// (in a LayerSet, its active layer's only, as reach() takes them), every stack emptied
  /// (its top sent isBound FALSE, unless it is the new first of its kind, which stays bound
  /// without events) and the first of each kind bound (node_roles.cpp).
  void rebindFrom(const std::vector<vrml::NodePtr>& roots);
  /// The nodes of worlds Browser.replaceWorld replaced (their roots and the world's hidden
  /// nodes), unloaded at the start of the next advanceTo (a Script that replaces the world
  /// may be one of them, and is inside its call at replaceWorld).
  std::vector<vrml::NodePtr> replacedNodes;
  /// Unloads what replacedNodes reaches and the world's roots now do not (ISO/IEC 19775-2
  /// replaceWorld: the old world is unloaded, its Scripts see shutdown()): its Scripts are
  /// shut down and no longer run; its TimeSensors, media, key, load, pick, transform and
  /// collision sensors, followers, skins, particle systems, rigid bodies and DIS nodes
  /// stop. So do the worlds of its Inline nodes (inlineWorlds), and of theirs, unless an
  /// Inline that stays shows the same world. Node records stay, marked unloaded (routes
  /// may still name them).
  void unloadReplacedWorld();
  // ---- MovieTexture and AudioClip (media_nodes.cpp) ----
  /// Makes `ns` a media node when it is a MovieTexture or AudioClip.
  bool classifyMedia(NodeState& ns);
  void deliverMedia(NodeState& ns, int field, vrml::FieldValue value);
  void evaluateMedia(NodeState& ns);
  // ---- X3D event utilities (event_utilities.cpp) ----
  /// Makes `ns` an event utility when it is a node of X3D 4.0 clause 30.
  bool classifyEventUtility(NodeState& ns);
  void deliverEventUtility(NodeState& ns, int field, vrml::FieldValue value);
  // ---- Skin (skin.cpp) ----
  /// Makes `ns` a skin when it is a Skin node (its events stay plain).
  bool classifyFollower(NodeState& ns);
  void deliverFollower(NodeState& ns, int field, vrml::FieldValue value);
  void evaluateFollower(NodeState& ns);
  bool classifySkin(NodeState& ns);
  /// Makes `ns` a skinned humanoid when it is an HAnimHumanoid (skin.cpp).
  bool classifyHumanoid(NodeState& ns);
  /// The HAnimMotions of every humanoid (hanim_motion.cpp): their joints' translation,
  /// rotation and scale at the current time, queued as events for the frame's cascade.
  void evaluateHAnimMotions();
  /// An HAnimMotion's `next` or `previous` (`direction` +1 or -1) TRUE: frameIndex steps
  /// by |frameIncrement| (1 when 0) from the frame it shows, within startFrame..endFrame,
  /// wrapping when it loops and ignored past an end otherwise (X_ITE 15's rule); a playing
  /// motion goes on from there (hanim_motion.cpp).
  void stepHAnimMotion(NodeState& ns, int direction);
  /// An HAnimMotion's `enabled` was set: FALSE stops it where it is, TRUE after FALSE starts
  /// it again from its start at now() (X_ITE 15 restarts its TimeSensor).
  void enableHAnimMotion(NodeState& ns);
  void evaluateHumanoid(NodeState& ns);
  /// After a cascade: re-skins every Skin whose skeleton or own fields changed.
  void evaluateSkins();
  void evaluateSkin(NodeState& ns);
  // ---- KeySensor and StringSensor (key_sensors.cpp) ----
  /// Makes `ns` a key device sensor when it is a KeySensor or StringSensor.
  bool classifyKeySensor(NodeState& ns);
  /// `enabled` of a key device sensor: stores and echoes it; FALSE while active ends the
  /// activity (isActive FALSE, the keys held forgotten; a StringSensor's unfinished text
  /// is dropped: enteredText "" when it was not empty, no finalText).
  void deliverKeySensor(NodeState& ns, int field, vrml::FieldValue value);
  /// One key down (`press`) or up for every enabled key device sensor, in a cascade
  /// already begun.
  void keyEvent(const Key& key, bool press);
  // ---- LoadSensor (load_sensors.cpp) ----
  /// Makes `ns` a LoadSensor when it is one (its first watch starts at
  /// startNewLoadSensors(), once the routes of its scene are in).
  bool classifyLoadSensor(NodeState& ns);
  /// enabled, timeOut, children (watchList): stores and echoes the value; enabled TRUE and
  /// a new children list start a new watch, enabled FALSE ends one (isActive FALSE).
  void deliverLoadSensor(NodeState& ns, int field, vrml::FieldValue value);
  /// Starts the first watch of the LoadSensors registered since the last call, in the
  /// cascade under way.
  void startNewLoadSensors();
  /// Reports what the LoadSensors that are watching can report now (their nodes' states,
  /// their timeOut), in the cascade under way.
  void evaluateLoadSensors();
  void evaluateLoadSensor(NodeState& ns);
  void startLoadWatch(NodeState& ns);

  // ---- NURBS interpolators (interpolators_nurbs.cpp) ----
  /// Makes `ns` a NURBS interpolator when it is a NurbsPositionInterpolator,
  /// NurbsOrientationInterpolator or NurbsSurfaceInterpolator (X3D 4.0 27.4.5, 27.4.6, 27.4.9).
  bool classifyNurbsInterpolator(NodeState& ns);
  /// set_fraction `value` of a NURBS interpolator: value_changed (position_changed and
  /// normal_changed), or one error for the node (its fields make no curve) and no output.
  void deliverNurbsInterpolator(NodeState& ns, vrml::FieldValue value);

  // ---- GeoPositionInterpolator (geo_interpolator.cpp) ----
  bool classifyGeoInterpolator(NodeState& ns);
  /// set_fraction of a GeoPositionInterpolator: geovalue_changed and value_changed.
  void deliverGeoInterpolator(NodeState& ns, const vrml::FieldValue& value);

  // ---- Picking (pick_sensors.cpp) ----
  /// Makes `ns` a pick sensor when it is a Point, Line, Primitive or VolumePickSensor.
  bool classifyPickSensor(NodeState& ns);
  /// Tests every enabled pick sensor's pickingGeometry against its pickTargets (after
  /// the time-dependent nodes moved); isActive, pickedGeometry, pickedPoint on change.
  void evaluatePickSensors();

  // ---- ParticleSystem (particle_systems.cpp) ----
  /// Makes `ns` a particle system when it is a ParticleSystem (its events stay plain).
  bool classifyParticleSystem(NodeState& ns);
  /// Moves every particle system to the clock's time; isActive on change.
  void evaluateParticleSystems();

  // ---- Rigid body physics (rigid_body_physics.cpp) ----
  /// Makes `ns` a RigidBodyCollection or CollisionSensor record (their events stay plain).
  bool classifyRigidBodyPhysics(NodeState& ns);
  /// Builds the worlds of the collections met since the last call: each body's
  /// collidables are placed at its position and orientation (X3D 4.0 clause 37.4.8).
  void startNewRigidBodyCollections();
  /// One physics frame of every collection (after the cascade of the frame's time
  /// events, as X_ITE's sensor phase); the bodies' outputs, the collidables moved, the
  /// joints' forceOutput values and the CollisionSensors' contacts, as events.
  void evaluateRigidBodyPhysics();

  // ---- DIS (dis_nodes.cpp) ----
  /// Makes `ns` a DIS node record (its events stay plain): an EspduTransform, ReceiverPdu,
  /// SignalPdu, TransmitterPdu or DISEntityManager.
  bool classifyDis(NodeState& ns);
  /// Reads the PDUs waiting on each DIS node's UDP port (once per frame); each
  /// networkReader node sends what the latest PDU of its entity or radio says (every
  /// readInterval), each DISEntityManager its added and removed entities, in the cascade
  /// under way.
  void evaluateDis();

  // ---- environmental sensors (environment_sensors.cpp) ----
  void evaluateEnvironmentSensors();
  /// Opens a new timestamp at now() for events from outside the graph: the stamp and the
  /// cascade count move on, the cascade's event count and overflow start afresh.
  void beginTimestamp() {
    ++stamp;
    ++model.stats_.cascades;
    eventsThisCascade = 0;
    cascadeOverflow = false;
  }
  /// The nodes a LOD or GeoLOD shows as drawing last said (drawn_outputs.cpp): a LOD's
  /// level (its first until told), a GeoLOD's `children` output (its rootNode until told);
  /// empty for other nodes and for a level that is empty or NULL.
  std::span<const vrml::NodePtr> shownNodes(const vrml::Node& n) const;

  void report(vrml::Severity severity, const vrml::Node& node, const std::string& message);

  // ---- pointing-device sensors and Anchors (pointer_sensors.cpp) ----
  /// A url of Anchor or Browser.loadURL: `#Name` binds the Viewpoint DEFed Name (4.6.7,
  /// 6.2); anything else goes to ExecutionOptions::loadUrl. `anchor`: the Anchor asking,
  /// whose URLs, when it is written in an Inline's world or an EXTERNPROTO's file, are
  /// resolved against that file and kept only where its rules let it name them
  /// (base::mayReference: a remote world's Anchor names no local file), each refused one
  /// with a warning.
  void requestUrl(const std::vector<std::string>& url, const std::vector<std::string>& parameter,
                  const vrml::Node* anchor = nullptr);
};

}  // namespace gs::runtime
