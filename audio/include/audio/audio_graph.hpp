// The X3D 4 audio graph (ISO/IEC 19775-1:2023 clause 16, "Sound" level 2) as signal
// processing, without nodes or devices: sources, processors, channel nodes, SpatialSound
// and destinations, each a processor keyed by its X3D node, rendered in blocks of 128
// frames (the render quantum of the Web Audio API, which clause 16 and X_ITE 15 follow).
//
// A processor's input is the sum of its inputs' outputs (up-mixed to the widest: a mono
// input is copied to every channel, "speakers" interpretation); its output is its
// processing of that sum times its `gain`. A processor that is disabled or not running
// (time-dependent: before startTime, paused, after stopTime) outputs silence. A cycle in
// the graph (a node among its own inputs) is broken: the input that closes it is silent.
// The formulas are the Web Audio API's (W3C Recommendation 2021, cited per field below);
// docs/media.md "The X3D 4 audio graph" says what is simplified.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <unordered_map>
#include <vector>

namespace gs::audio {

/// Frames per second the graph renders at.
inline constexpr int kGraphSampleRate = 44100;
/// Frames per block (Web Audio's render quantum).
inline constexpr std::size_t kGraphBlock = 128;
/// Most channels a signal carries (more are dropped).
inline constexpr int kGraphMaxChannels = 8;

enum class ProcessorType : std::uint8_t {
  destination,         // AudioDestination, StreamAudioDestination: mixed into the output
  spatialSound,        // SpatialSound: a PannerNode (distance, cone, equal-power panning)
  gain,                // Gain (and Sound-less pass-through)
  analyser,            // Analyser: passes its input on (X3D 4.0 gives it no outputs)
  biquadFilter,        // BiquadFilter
  convolver,           // Convolver
  delay,               // Delay
  dynamicsCompressor,  // DynamicsCompressor
  waveShaper,          // WaveShaper
  channelMerger,       // ChannelMerger: input i (down-mixed to mono) becomes channel i
  channelSelector,     // ChannelSelector: channel channelSelection of the input, mono
  channelSplitter,     // ChannelSplitter: channel i goes to its outputs[i]
  oscillator,          // OscillatorSource
  buffer,              // BufferAudioSource, AudioClip: sampled sound
  captured,            // MicrophoneSource: the samples of `captured`, mono
  silence,             // StreamAudioSource, ListenerPointSource: no signal
};

/// OscillatorSource's wave (PeriodicWave.type, X3D 4.1).
enum class WaveForm : std::uint8_t { sine, square, sawtooth, triangle, custom };

/// BiquadFilter.type, the filters of the Audio EQ Cookbook as Web Audio 1.0 1.13
/// defines them.
enum class BiquadType : std::uint8_t {
  lowpass,
  highpass,
  bandpass,
  lowshelf,
  highshelf,
  peaking,
  notch,
  allpass
};

/// SpatialSound.distanceModel (Web Audio 1.0 1.27.1).
enum class DistanceModel : std::uint8_t { linear, inverse, exponential };

/// Sampled sound, float samples in -1..1, channels interleaved.
struct SampledSound {
  int sampleRate = kGraphSampleRate;  // > 0
  int channels = 1;                   // 1..kGraphMaxChannels
  std::vector<float> samples;         // frames * channels values
  std::size_t frames() const { return channels > 0 ? samples.size() / channels : 0; }
};

/// What one processor does now: set every frame from its node's fields (the defaults are
/// X3D 4.0's).
struct ProcessorParams {
  ProcessorType type = ProcessorType::gain;
  bool enabled = true;
  bool running = true;  // time-dependent nodes: active and not paused
  float gain = 1.0f;    // the output's linear factor (X3DSoundNode.gain)
  /// The processors whose outputs are summed into this one's input (its `children`;
  /// keys as given to AudioGraph::set). For a ChannelMerger, input i is channel i.
  std::vector<const void*> inputs;

  // OscillatorSource: frequency in hertz, detune in cents.
  float frequency = 440.0f, detune = 0.0f;
  WaveForm wave = WaveForm::sine;
  /// PeriodicWave.optionsReal / optionsImag (custom): cosine and sine terms of harmonic
  /// k (index 0, the DC term, is ignored); normalized so that the peak is 1.
  std::vector<float> real, imag;

  // BufferAudioSource and AudioClip.
  std::shared_ptr<const SampledSound> sound;
  /// Seconds into the sound to be heard at the start of the next render (the node's media
  /// time, which the execution model computes); kept in step by the graph while it
  /// renders. A jump of more than 0.1 s from where the graph is moves it there.
  double position = 0.0;
  float playbackRate = 1.0f;  // > 0 (detune in cents scales it by 2^(detune/1200))
  bool loop = false;
  double loopStart = 0.0, loopEnd = 0.0;  // seconds; loopEnd <= loopStart: the whole sound

  // MicrophoneSource: the samples captured so far and not yet heard (mono, -1..1, at
  // kGraphSampleRate), taken from the front as blocks are rendered; silence when it runs dry.
  std::shared_ptr<std::deque<float>> captured;

  // BiquadFilter: frequency above, qualityFactor the Q, filterGain in dB (X3D 4.0 has no
  // field for it: 0, so LOWSHELF, HIGHSHELF and PEAKING pass the signal on, as in X_ITE 15).
  BiquadType biquad = BiquadType::lowpass;
  float qualityFactor = 1.0f, filterGain = 0.0f;

  // Convolver: the impulse response (`sound`) and its normalization.
  bool normalize = false;

  // Delay: seconds.
  double delayTime = 0.0, maxDelayTime = 1.0;

  // DynamicsCompressor: dB, dB, ratio, seconds, seconds.
  float threshold = -24.0f, knee = 30.0f, ratio = 12.0f;
  double attack = 0.003, release = 0.25;

  // WaveShaper: the transfer curve over input -1..1 (empty: identity).
  std::vector<float> curve;

  // ChannelSelector.
  int channelSelection = 0;
  // ChannelSplitter: where channel i goes.
  std::vector<const void*> outputs;

  // SpatialSound: location and direction in world coordinates (metres), the
  // cone angles in radians (0..2 pi), distances in metres.
  glm::vec3 location{0.0f}, direction{0.0f, 0.0f, 1.0f};
  float coneInnerAngle = 6.2832f, coneOuterAngle = 6.2832f, coneOuterGain = 0.0f;
  DistanceModel distanceModel = DistanceModel::inverse;
  float referenceDistance = 1.0f, rolloffFactor = 1.0f, maxDistance = 10000.0f;
  float intensity = 1.0f;
  bool spatialize = true;

  // AudioDestination: channels of its output (1..kGraphMaxChannels).
  int maxChannelCount = 2;
};

/// A block of signal: channels() buffers of kGraphBlock frames.
struct SignalBlock {
  std::vector<std::vector<float>> channel;
  int channels() const { return static_cast<int>(channel.size()); }
};

class AudioGraph {
 public:
  AudioGraph();
  ~AudioGraph();
  AudioGraph(const AudioGraph&) = delete;
  AudioGraph& operator=(const AudioGraph&) = delete;

  /// Sets (or adds) the processor of `key` for the next render. Processors not set since
  /// the last render are forgotten when it starts (their state with them).
  void set(const void* key, ProcessorParams params);
  /// Where the listener is: `worldToListener` the viewer's view matrix (world to eye
  /// coordinates: x right, y up, -z ahead; metres).
  void setListener(const glm::mat4& worldToListener);
  /// Renders `frames` frames (rounded up to whole blocks internally; the rest kept for the
  /// next call) of every destination's output mixed to stereo, appended to `stereo`
  /// (interleaved left, right; -1..1 not enforced). Destinations of one channel are heard
  /// in both ears; of more than two, channels 0 and 1 are left and right.
  void render(std::size_t frames, std::vector<float>& stereo);
  /// Processors known now.
  std::size_t size() const;
  /// A processor's gain reduction in dB (<= 0) after the last render: DynamicsCompressor's
  /// `reduction`; 0 for other processors and unknown keys.
  float reduction(const void* key) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// The gain of a PannerNode's distance model at distance `distance` (metres; Web Audio 1.0
/// 1.27.4): linear 1 - rolloff (clamp(d, ref, max) - ref) / (max - ref), inverse ref /
/// (ref + rolloff (max(d, ref) - ref)), exponential (max(d, ref) / ref)^-rolloff.
float distanceGain(DistanceModel model, float distance, float referenceDistance, float maxDistance,
                   float rolloffFactor);

/// The cone gain of a PannerNode (Web Audio 1.0 1.27.5): 1 within half the inner angle of
/// `direction` (as seen from the source), `outerGain` beyond half the outer angle, linear
/// in angle between. Angles in radians; `toListener` from the source to the listener.
/// An inner angle of 2 pi or more, or a zero direction, gives 1.
float coneGain(const glm::vec3& direction, const glm::vec3& toListener, float innerAngle,
               float outerAngle, float outerGain);

/// Web Audio's Convolver normalization scale (1.15.3, calculateNormalizationScale) for the
/// impulse response `sound`.
float convolverNormalization(const SampledSound& sound);

}  // namespace gs::audio
