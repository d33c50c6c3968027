// Private to audio/: the signal processing of the audio graph's processors, each a state
// kept across blocks and a function of one block (audio_processors.cpp, audio_sources.cpp).
// The formulas are the Web Audio API 1.0's, cited per function.
#pragma once

#include "audio/audio_graph.hpp"

#include <array>
#include <complex>
#include <map>
#include <vector>

namespace gs::audio::detail {

/// Makes `block` hold `channels` channels of kGraphBlock zeros.
void silence(SignalBlock& block, int channels);
/// Adds `in` into `sum`, up-mixing: a mono input is added to every channel of the sum, a
/// wider one widens it (missing channels are silent).
void mixInto(SignalBlock& sum, const SignalBlock& in);

// ---- sources (audio_sources.cpp) ----

/// A band-limited table of one period of a wave (Web Audio 1.0 1.25, PeriodicWave): the
/// Fourier series up to the harmonics below the Nyquist frequency, normalized to peak 1.
class WaveTables {
 public:
  /// The table (kTableSize samples of one period) for `params`' wave at `frequency` Hz.
  const std::vector<float>& table(const ProcessorParams& params, float frequency);
  static constexpr std::size_t kTableSize = 2048;

 private:
  std::map<std::pair<int, std::size_t>, std::vector<float>> cache_;  // (wave, harmonics)
  std::vector<float> customReal_, customImag_;
};

struct OscillatorState {
  double phase = 0.0;  // cycles, 0..1
  WaveTables tables;
};
/// OscillatorSource: mono, at frequency * 2^(detune / 1200) Hz.
void renderOscillator(const ProcessorParams& p, OscillatorState& s, SignalBlock& out);

struct BufferState {
  double cursor = -1.0;  // seconds into the sound; < 0: not placed yet
};
/// Places the cursor where `p.position` says the sound should be `seconds` before the end of
/// this render (a jump of more than 0.1 s from where it is, or the first time).
void placeBuffer(const ProcessorParams& p, BufferState& s, double seconds);
/// BufferAudioSource and AudioClip: the sound at its cursor, linearly interpolated, at
/// playbackRate * 2^(detune / 1200) times its own rate; silence past its end (not looping).
void renderBuffer(const ProcessorParams& p, BufferState& s, SignalBlock& out);

// ---- processors (audio_processors.cpp) ----

struct BiquadState {
  std::array<std::array<double, 2>, kGraphMaxChannels> z{};  // transposed direct form II
};
/// BiquadFilter (Web Audio 1.0 1.13.6: the Audio EQ Cookbook's coefficients).
void renderBiquad(const ProcessorParams& p, BiquadState& s, const SignalBlock& in,
                  SignalBlock& out);

struct DelayState {
  std::vector<std::vector<float>> ring;
  std::size_t write = 0;
};
/// Delay (Web Audio 1.0 1.16): the input delayTime seconds ago (0..maxDelayTime), linearly
/// interpolated.
void renderDelay(const ProcessorParams& p, DelayState& s, const SignalBlock& in, SignalBlock& out);

struct CompressorState {
  float reductionDb = 0.0f;  // <= 0, smoothed
};
/// DynamicsCompressor: a peak detector, a soft-knee gain curve (threshold, knee, ratio,
/// Web Audio 1.0 1.19's curve) and attack / release smoothing of the reduction.
void renderCompressor(const ProcessorParams& p, CompressorState& s, const SignalBlock& in,
                      SignalBlock& out);

/// WaveShaper (Web Audio 1.0 1.32.4): the curve's value at the input, linearly
/// interpolated; no oversampling.
void renderWaveShaper(const ProcessorParams& p, const SignalBlock& in, SignalBlock& out);

/// Uniformly partitioned convolution (overlap-add in the frequency domain, partitions of
/// kGraphBlock frames) of one channel with one impulse response.
class PartitionedConvolution {
 public:
  explicit PartitionedConvolution(const std::vector<float>& impulse);
  /// Convolves the next kGraphBlock frames of `in` into `out`.
  void process(const float* in, float* out);

 private:
  using Spectrum = std::vector<std::complex<float>>;
  std::vector<Spectrum> partitions_;  // the impulse response's blocks, transformed
  std::vector<Spectrum> history_;     // the inputs' blocks, transformed, newest at head_
  std::size_t head_ = 0;
  std::vector<float> overlap_;  // the second half of the last inverse transform
};

struct ConvolverState {
  const SampledSound* impulse = nullptr;  // the response the convolutions were made for
  bool normalize = false;
  std::vector<PartitionedConvolution> channels;
};
/// Convolver (Web Audio 1.0 1.15): each output channel c is input channel c (or the only
/// one) convolved with response channel c (or the only one), times the normalization
/// scale when `normalize`.
void renderConvolver(const ProcessorParams& p, ConvolverState& s, const SignalBlock& in,
                     SignalBlock& out);

/// SpatialSound (Web Audio 1.0 1.27, "equalpower" panning): the input down-mixed to mono,
/// times intensity, the distance and cone gains, panned to stereo by its azimuth as the
/// listener hears it (`worldToListener`); not spatialized: the input unchanged.
void renderSpatialSound(const ProcessorParams& p, const glm::mat4& worldToListener,
                        const SignalBlock& in, SignalBlock& out);

/// In-place radix-2 FFT of `x` (size a power of two); `inverse` without the 1/N.
void fft(std::vector<std::complex<float>>& x, bool inverse);

}  // namespace gs::audio::detail
