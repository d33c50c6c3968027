// The audio graph's sources (audio_processors.hpp): OscillatorSource through band-limited
// wave tables, BufferAudioSource and AudioClip through a cursor into their sound.
#include "audio_processors.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gs::audio::detail {

namespace {

/// Fourier coefficients (cosine a_k, sine b_k) of harmonic k >= 1 of Web Audio's built-in
/// waves (Web Audio 1.0 1.24.4.1, "Basic Waveform Phase").
void basicWaveTerm(WaveForm wave, std::size_t k, float& a, float& b) {
  const double pi = std::numbers::pi;
  const double kd = static_cast<double>(k);
  a = 0.0f;
  switch (wave) {
    case WaveForm::sine:
      b = k == 1 ? 1.0f : 0.0f;
      break;
    case WaveForm::square:
      b = static_cast<float>(2.0 / (kd * pi) * (1.0 - std::pow(-1.0, kd)));
      break;
    case WaveForm::sawtooth:
      b = static_cast<float>(std::pow(-1.0, kd + 1.0) * 2.0 / (kd * pi));
      break;
    case WaveForm::triangle:
      b = static_cast<float>(8.0 * std::sin(kd * pi / 2.0) / (kd * kd * pi * pi));
      break;
    case WaveForm::custom:
      b = 0.0f;
      break;
  }
}

}  // namespace

const std::vector<float>& WaveTables::table(const ProcessorParams& p, float frequency) {
  const std::size_t maxHarmonics = kTableSize / 2 - 1;
  const double nyquist = kGraphSampleRate / 2.0;
  std::size_t harmonics = frequency > 0.0f ? static_cast<std::size_t>(nyquist / frequency) : 1;
  harmonics = std::clamp<std::size_t>(harmonics, 1, maxHarmonics);
  if (p.wave == WaveForm::custom) {
    // A custom wave is cached by its coefficients: a change clears its tables.
    if (p.real != customReal_ || p.imag != customImag_) {
      customReal_ = p.real;
      customImag_ = p.imag;
      std::erase_if(cache_, [](const auto& e) { return e.first.first == int(WaveForm::custom); });
    }
    harmonics = std::min(harmonics, std::max(p.real.size(), p.imag.size()));
    harmonics = std::max<std::size_t>(harmonics, 1);
  }
  const auto key = std::make_pair(static_cast<int>(p.wave), harmonics);
  if (const auto it = cache_.find(key); it != cache_.end()) return it->second;
  // The inverse transform of the spectrum: one period of the wave.
  std::vector<std::complex<float>> spectrum(kTableSize);
  for (std::size_t k = 1; k <= harmonics; ++k) {
    float a = 0.0f, b = 0.0f;
    if (p.wave == WaveForm::custom) {
      a = k < p.real.size() ? p.real[k] : 0.0f;
      b = k < p.imag.size() ? p.imag[k] : 0.0f;
    } else {
      basicWaveTerm(p.wave, k, a, b);
    }
    // x(t) = sum a_k cos(2 pi k t) + b_k sin(2 pi k t): X[k] = (a_k - i b_k) / 2, mirrored.
    spectrum[k] = std::complex<float>(a, -b) * 0.5f;
    spectrum[kTableSize - k] = std::conj(spectrum[k]);
  }
  fft(spectrum, true);
  std::vector<float> values(kTableSize);
  float peak = 0.0f;
  for (std::size_t i = 0; i < kTableSize; ++i) {
    values[i] = spectrum[i].real();
    peak = std::max(peak, std::fabs(values[i]));
  }
  if (peak > 0.0f)
    for (float& v : values) v /= peak;  // Web Audio's normalization: peak 1
  return cache_.emplace(key, std::move(values)).first->second;
}

void renderOscillator(const ProcessorParams& p, OscillatorState& s, SignalBlock& out) {
  silence(out, 1);
  const float frequency = std::max(0.0f, p.frequency) * std::exp2(p.detune / 1200.0f);
  const std::vector<float>& table = s.tables.table(p, frequency);
  const double step = static_cast<double>(frequency) / kGraphSampleRate;
  float* o = out.channel[0].data();
  for (std::size_t i = 0; i < kGraphBlock; ++i) {
    const double at = s.phase * WaveTables::kTableSize;
    const auto k = static_cast<std::size_t>(at) % WaveTables::kTableSize;
    const float f = static_cast<float>(at - std::floor(at));
    o[i] = table[k] * (1.0f - f) + table[(k + 1) % WaveTables::kTableSize] * f;
    s.phase += step;
    s.phase -= std::floor(s.phase);
  }
}

namespace {

/// The loop of `p` in seconds of its sound: [start, end), the whole sound when not set.
void loopBounds(const ProcessorParams& p, double duration, double& start, double& end) {
  start = 0.0;
  end = duration;
  if (p.loopEnd > p.loopStart && p.loopStart >= 0.0) {
    start = std::min(p.loopStart, duration);
    end = std::min(p.loopEnd, duration);
  }
}

double rateOf(const ProcessorParams& p) {
  return static_cast<double>(std::max(0.0f, p.playbackRate)) * std::exp2(p.detune / 1200.0);
}

}  // namespace

void placeBuffer(const ProcessorParams& p, BufferState& s, double seconds) {
  if (!p.sound || p.sound->frames() == 0) return;
  const double duration = static_cast<double>(p.sound->frames()) / p.sound->sampleRate;
  double at = p.position - seconds * rateOf(p);
  double start = 0.0, end = duration;
  loopBounds(p, duration, start, end);
  if (p.loop && end > start && at >= end) at = start + std::fmod(at - start, end - start);
  at = std::max(at, 0.0);
  if (s.cursor < 0.0 || std::fabs(at - s.cursor) > 0.1) s.cursor = at;
}

void renderBuffer(const ProcessorParams& p, BufferState& s, SignalBlock& out) {
  const SampledSound* sound = p.sound.get();
  if (!sound || sound->frames() == 0 || sound->channels < 1) {
    silence(out, 1);
    return;
  }
  const int channels = std::min(sound->channels, kGraphMaxChannels);
  silence(out, channels);
  const std::size_t frames = sound->frames();
  const double duration = static_cast<double>(frames) / sound->sampleRate;
  double loopStart = 0.0, loopEnd = duration;
  loopBounds(p, duration, loopStart, loopEnd);
  const double step = rateOf(p) / kGraphSampleRate;
  if (s.cursor < 0.0) s.cursor = 0.0;
  for (std::size_t i = 0; i < kGraphBlock; ++i) {
    if (p.loop && loopEnd > loopStart && s.cursor >= loopEnd)
      s.cursor = loopStart + std::fmod(s.cursor - loopStart, loopEnd - loopStart);
    const double at = s.cursor * sound->sampleRate;
    if (at < static_cast<double>(frames)) {
      const auto k = static_cast<std::size_t>(at);
      const float f = static_cast<float>(at - static_cast<double>(k));
      const std::size_t next = k + 1 < frames ? k + 1 : (p.loop ? 0 : k);
      for (int c = 0; c < channels; ++c) {
        const float a = sound->samples[k * sound->channels + c];
        const float b = sound->samples[next * sound->channels + c];
        out.channel[c][i] = a + (b - a) * f;
      }
    }
    s.cursor += step;
  }
}

}  // namespace gs::audio::detail
