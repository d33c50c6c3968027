// SoundScene's X3D 4 audio graph (ISO/IEC 19775-1:2023 clause 16, level 2): the
// AudioDestinations, SpatialSounds and ListenerPointSources of the scene graph and the
// sources, processing and channel nodes below them become the processors of an AudioGraph
// (audio/audio_graph.hpp), set from their fields every frame and rendered as simulated
// time passes. The wiring is X_ITE 15's (docs/media.md "The X3D 4 audio graph").
#include "audio/sound_scene.hpp"

#include "vrml/transform.hpp"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace gs::audio {

namespace {

using vrml::FieldType;
using vrml::NodeTypeId;

/// Whether `children` takes `n` in (X_ITE: X3DSoundChannelNode, X3DSoundProcessingNode and
/// X3DSoundSourceNode; any other child is ignored). A MovieTexture, a sound source in X3D 4,
/// is not (its sound plays through a Sound node).
bool feedsGraph(const vrml::Node& n) {
  using vrml::AbstractType;
  return n.typeId() != NodeTypeId::MovieTexture &&
         (n.is(AbstractType::X3DSoundChannelNode) || n.is(AbstractType::X3DSoundProcessingNode) ||
          n.is(AbstractType::X3DSoundSourceNode));
}

BiquadType biquadType(const std::string& s) {
  static const std::pair<const char*, BiquadType> kTypes[] = {
      {"LOWPASS", BiquadType::lowpass},     {"HIGHPASS", BiquadType::highpass},
      {"BANDPASS", BiquadType::bandpass},   {"LOWSHELF", BiquadType::lowshelf},
      {"HIGHSHELF", BiquadType::highshelf}, {"PEAKING", BiquadType::peaking},
      {"NOTCH", BiquadType::notch},         {"ALLPASS", BiquadType::allpass}};
  for (const auto& [name, type] : kTypes)
    if (s == name) return type;
  return BiquadType::lowpass;
}

DistanceModel distanceModel(const std::string& s) {
  if (s == "LINEAR") return DistanceModel::linear;
  if (s == "EXPONENTIAL") return DistanceModel::exponential;
  return DistanceModel::inverse;
}

/// OscillatorSource's wave: its periodicWave's type (X3D 4.1; X_ITE 15), SQUARE without
/// one, as X_ITE plays it (PeriodicWave's default type).
void waveOf(const vrml::Node& oscillator, ProcessorParams& p) {
  p.wave = WaveForm::square;
  if (oscillator.type().findExact("periodicWave") < 0) return;
  const vrml::NodePtr wave = oscillator.sfnode("periodicWave");
  if (!wave || wave->typeId() != NodeTypeId::PeriodicWave) return;
  const std::string type = wave->get<FieldType::SFString>("type", std::string("SQUARE"));
  if (type == "SINE") p.wave = WaveForm::sine;
  if (type == "SAWTOOTH") p.wave = WaveForm::sawtooth;
  if (type == "TRIANGLE") p.wave = WaveForm::triangle;
  if (type == "CUSTOM") {
    p.wave = WaveForm::custom;
    p.real = wave->get<FieldType::MFFloat>("optionsReal", std::vector<float>{});
    p.imag = wave->get<FieldType::MFFloat>("optionsImag", std::vector<float>{});
  }
}

}  // namespace

std::shared_ptr<const SampledSound> SoundScene::sampledOf(const vrml::Node& n,
                                                          const std::string& base) {
  const bool convolver = n.typeId() == NodeTypeId::Convolver;
  if (n.typeId() == NodeTypeId::BufferAudioSource || convolver) {
    const std::vector<float> data = n.get<FieldType::MFFloat>("buffer", std::vector<float>{});
    if (!data.empty() || convolver) {
      auto& [revision, sound] = buffers_[&n];
      if (!sound || revision != n.revision()) {
        // `buffer` is channel-major (X_ITE: buffer[c * length + k]), numberOfChannels long.
        auto s = std::make_shared<SampledSound>();
        s->channels =
            std::clamp(n.get<FieldType::SFInt32>("numberOfChannels", 1), 1, kGraphMaxChannels);
        const float rate = n.get<FieldType::SFFloat>("sampleRate", 0.0f);
        s->sampleRate =
            rate > 0.0f ? static_cast<int>(std::clamp(rate, 3000.0f, 768000.0f)) : kGraphSampleRate;
        const std::size_t length = data.size() / static_cast<std::size_t>(s->channels);
        s->samples.resize(length * static_cast<std::size_t>(s->channels));
        for (std::size_t c = 0; c < static_cast<std::size_t>(s->channels); ++c)
          for (std::size_t k = 0; k < length; ++k)
            s->samples[k * s->channels + c] = data[c * length + k];
        sound = std::move(s);
        revision = n.revision();
      }
      return sound;
    }
  }
  const std::shared_ptr<const formats::AudioData> clip = clipOf(n, base);
  if (!clip) return nullptr;
  std::shared_ptr<const SampledSound>& sound = sampled_[clip.get()];
  if (!sound) {
    auto s = std::make_shared<SampledSound>();
    s->sampleRate = clip->sampleRate;
    s->channels = clip->channels;
    s->samples.reserve(clip->samples.size());
    for (std::int16_t v : clip->samples) s->samples.push_back(static_cast<float>(v) / 32768.0f);
    sound = std::move(s);
  }
  return sound;
}

void SoundScene::setProcessor(const vrml::Node& n, const std::string& base,
                              const ClipTimeQuery& clipTime,
                              std::unordered_set<const vrml::Node*>& seen, int depth) {
  if (depth > 64 || !seen.insert(&n).second) return;
  ProcessorParams p;
  p.enabled = n.get<FieldType::SFBool>("enabled", true);
  p.gain = n.get<FieldType::SFFloat>("gain", 1.0f);
  const std::optional<ClipTime> time = clipTime ? clipTime(n) : std::nullopt;
  p.running = time && time->active;
  switch (n.typeId()) {
    case NodeTypeId::OscillatorSource:
      p.type = ProcessorType::oscillator;
      p.frequency = std::max(0.0f, n.get<FieldType::SFFloat>("frequency", 440.0f));
      p.detune = n.get<FieldType::SFFloat>("detune", 0.0f);
      waveOf(n, p);
      break;
    case NodeTypeId::AudioClip:
    case NodeTypeId::BufferAudioSource: {
      const bool clip = n.typeId() == NodeTypeId::AudioClip;
      p.type = ProcessorType::buffer;
      p.sound = sampledOf(n, base);
      p.position = time ? time->mediaTime : 0.0;
      p.playbackRate = clip ? n.get<FieldType::SFFloat>("pitch", 1.0f)
                            : n.get<FieldType::SFFloat>("playbackRate", 1.0f);
      p.detune = clip ? 0.0f : n.get<FieldType::SFFloat>("detune", 0.0f);
      p.loop = n.get<FieldType::SFBool>("loop", false);
      p.loopStart = clip ? 0.0 : std::max(0.0f, n.get<FieldType::SFFloat>("loopStart", 0.0f));
      p.loopEnd = clip ? 0.0 : std::max(0.0f, n.get<FieldType::SFFloat>("loopEnd", 0.0f));
      break;
    }
    case NodeTypeId::MicrophoneSource: {
      // The default capture device's sound (mediaDeviceID is not matched: one microphone),
      // queued for it by updateGraph.
      p.type = ProcessorType::captured;
      auto& fifo = microphones_[&n];
      if (!fifo) fifo = std::make_shared<std::deque<float>>();
      p.captured = fifo;
      if (p.enabled && p.running) microphoneLocation_ = &n.location;
      break;
    }
    case NodeTypeId::StreamAudioSource:
    case NodeTypeId::ListenerPointSource:
      p.type = ProcessorType::silence;
      break;
    case NodeTypeId::BiquadFilter:
      p.type = ProcessorType::biquadFilter;
      p.biquad = biquadType(n.get<FieldType::SFString>("type", std::string("LOWPASS")));
      p.frequency = std::max(0.0f, n.get<FieldType::SFFloat>("frequency", 350.0f));
      p.detune = n.get<FieldType::SFFloat>("detune", 0.0f);
      p.qualityFactor = std::clamp(n.get<FieldType::SFFloat>("qualityFactor", 1.0f), 1e-4f, 1e3f);
      break;
    case NodeTypeId::Convolver:
      p.type = ProcessorType::convolver;
      p.sound = sampledOf(n, base);
      p.normalize = n.get<FieldType::SFBool>("normalize", false);
      break;
    case NodeTypeId::Delay:
      p.type = ProcessorType::delay;
      p.maxDelayTime = std::max(0.0, n.get<FieldType::SFTime>("maxDelayTime", 1.0));
      p.delayTime = std::clamp(n.get<FieldType::SFTime>("delayTime", 0.0), 0.0, p.maxDelayTime);
      break;
    case NodeTypeId::DynamicsCompressor:
      p.type = ProcessorType::dynamicsCompressor;
      compressors_.push_back(&n);
      p.attack = n.get<FieldType::SFTime>("attack", 0.003);
      p.knee = n.get<FieldType::SFFloat>("knee", 30.0f);
      p.ratio = n.get<FieldType::SFFloat>("ratio", 12.0f);
      p.release = n.get<FieldType::SFTime>("release", 0.25);
      p.threshold = n.get<FieldType::SFFloat>("threshold", -24.0f);
      break;
    case NodeTypeId::WaveShaper:
      p.type = ProcessorType::waveShaper;
      if (n.type().findExact("curve") >= 0)
        p.curve = n.get<FieldType::MFFloat>("curve", std::vector<float>{});
      break;
    case NodeTypeId::Analyser:
      p.type = ProcessorType::analyser;
      break;
    case NodeTypeId::ChannelMerger:
      p.type = ProcessorType::channelMerger;
      break;
    case NodeTypeId::ChannelSelector:
      p.type = ProcessorType::channelSelector;
      p.channelSelection = n.get<FieldType::SFInt32>("channelSelection", 0);
      break;
    case NodeTypeId::ChannelSplitter:
      p.type = ProcessorType::channelSplitter;
      for (const vrml::NodePtr& o : n.mfnode("outputs"))
        if (o && feedsGraph(*o)) p.outputs.push_back(o.get());
      break;
    default:  // Gain
      p.type = ProcessorType::gain;
      break;
  }
  if (n.type().findExact("children") >= 0)
    for (const vrml::NodePtr& c : n.mfnode("children"))
      if (c && feedsGraph(*c)) {
        p.inputs.push_back(c.get());
        setProcessor(*c, base, clipTime, seen, depth + 1);
      }
  graph_.set(&n, std::move(p));
}

void SoundScene::updateGraph(const std::vector<GraphRoot>& roots, const glm::mat4& worldToListener,
                             double now, const ClipTimeQuery& clipTime, AudioOutput& output) {
  if (roots.empty() && graph_.size() == 0) {
    graphTime_ = now;
    return;
  }
  std::unordered_set<const vrml::Node*> seen;
  compressors_.clear();
  glm::mat4 listener = worldToListener;
  for (const GraphRoot& r : roots) {
    const vrml::Node& n = *r.node;
    // A ListenerPointSource not tracking the view: the listener stands at its position and
    // orientation (the last such one).
    if (n.typeId() == NodeTypeId::ListenerPointSource &&
        n.get<FieldType::SFBool>("enabled", true) &&
        !n.get<FieldType::SFBool>("trackCurrentView", false)) {
      const glm::mat4 pose =
          r.world *
          glm::translate(glm::mat4(1.0f), n.get<FieldType::SFVec3f>("position", glm::vec3(0.0f))) *
          vrml::rotationMatrix(
              n.get<FieldType::SFRotation>("orientation", vrml::Rotation{0, 0, 1, 0}));
      listener = glm::inverse(pose);
    }
  }
  const glm::vec3 listenerPosition(glm::inverse(listener)[3]);
  for (const GraphRoot& r : roots) {
    const vrml::Node& n = *r.node;
    if (n.typeId() == NodeTypeId::ListenerPointSource) continue;
    ProcessorParams p;
    p.enabled = n.get<FieldType::SFBool>("enabled", true);
    p.gain = n.get<FieldType::SFFloat>("gain", 1.0f);
    if (n.typeId() == NodeTypeId::SpatialSound) {
      p.type = ProcessorType::spatialSound;
      p.enabled = true;  // X_ITE 15 does not read SpatialSound.enabled
      p.location = glm::vec3(
          r.world * glm::vec4(n.get<FieldType::SFVec3f>("location", glm::vec3(0.0f)), 1.0f));
      p.direction = glm::vec3(
          r.world *
          glm::vec4(n.get<FieldType::SFVec3f>("direction", glm::vec3(0.0f, 0.0f, 1.0f)), 0.0f));
      p.coneInnerAngle = n.get<FieldType::SFFloat>("coneInnerAngle", 6.2832f);
      p.coneOuterAngle = n.get<FieldType::SFFloat>("coneOuterAngle", 6.2832f);
      p.coneOuterGain = n.get<FieldType::SFFloat>("coneOuterGain", 0.0f);
      p.distanceModel =
          distanceModel(n.get<FieldType::SFString>("distanceModel", std::string("INVERSE")));
      p.referenceDistance = n.get<FieldType::SFFloat>("referenceDistance", 1.0f);
      p.rolloffFactor = n.get<FieldType::SFFloat>("rolloffFactor", 1.0f);
      p.maxDistance = n.get<FieldType::SFFloat>("maxDistance", 10000.0f);
      p.intensity = n.get<FieldType::SFFloat>("intensity", 1.0f);
      p.spatialize = n.get<FieldType::SFBool>("spatialize", true);
      // Acoustic surfaces between it and the listener (audio/acoustics.hpp).
      if (occlusion_.surfaceCount() > 0)
        p.gain *= occlusion_.transmission(p.location, listenerPosition);
    } else {
      p.type = ProcessorType::destination;
      p.maxChannelCount = n.get<FieldType::SFInt32>("maxChannelCount", 2);
      // A StreamAudioDestination's output is a web page's MediaStream: not heard here.
      if (n.typeId() == NodeTypeId::StreamAudioDestination) p.enabled = false;
    }
    for (const vrml::NodePtr& c : n.mfnode("children"))
      if (c && feedsGraph(*c)) {
        p.inputs.push_back(c.get());
        setProcessor(*c, r.base, clipTime, seen, 1);
      }
    graph_.set(&n, std::move(p));
  }
  graph_.setListener(listener);
  if (graphTime_ < 0.0 || now < graphTime_) graphTime_ = now;
  const auto frames = static_cast<std::size_t>(std::clamp<long long>(
      std::llround(now * kGraphSampleRate) - std::llround(graphTime_ * kGraphSampleRate), 0,
      kGraphSampleRate / 2));
  graphTime_ = now;
  // MicrophoneSources: what the capture device recorded since the last frame, to each
  // playing one (at most half a second kept: the oldest is dropped).
  if (microphoneLocation_ != nullptr) {
    std::vector<float> captured;
    std::string note;
    output.capture(captured, kGraphSampleRate / 2, note);
    if (!note.empty()) diagnostics_.warning(*microphoneLocation_, note);
    for (auto& [node, fifo] : microphones_) {
      fifo->insert(fifo->end(), captured.begin(), captured.end());
      while (fifo->size() > kGraphSampleRate / 2) fifo->pop_front();
    }
  }
  microphoneLocation_ = nullptr;
  std::vector<float> stereo;
  graph_.render(frames, stereo);
  if (!stereo.empty()) output.stream(stereo);
  // The compressors' reduction events (takeOutputs).
  for (const vrml::Node* c : compressors_) {
    const float reduction = graph_.reduction(c);
    float& sent = sentReductions_.try_emplace(vrml::NodeKey(c), 0.0f).first->second;
    if (!(std::fabs(reduction - sent) >= 0.01f)) continue;
    sent = reduction;
    outputs_.push_back(
        {vrml::NodeKey(c), "reduction", vrml::FieldValue::make<FieldType::SFFloat>(reduction)});
  }
}

}  // namespace gs::audio
