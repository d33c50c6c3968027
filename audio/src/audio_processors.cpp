// The audio graph's processors (audio_processors.hpp): filters, delay, compressor, wave
// shaper, convolver and the SpatialSound panner, as the Web Audio API 1.0 defines them.
#include "audio_processors.hpp"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gs::audio::detail {

void silence(SignalBlock& block, int channels) {
  block.channel.resize(static_cast<std::size_t>(std::clamp(channels, 0, kGraphMaxChannels)));
  for (auto& c : block.channel) c.assign(kGraphBlock, 0.0f);
}

void mixInto(SignalBlock& sum, const SignalBlock& in) {
  if (in.channels() == 0) return;
  if (sum.channels() < in.channels()) {
    const std::size_t old = sum.channel.size();
    sum.channel.resize(in.channel.size());
    for (std::size_t c = old; c < sum.channel.size(); ++c)
      sum.channel[c] = old == 1 ? sum.channel[0] : std::vector<float>(kGraphBlock, 0.0f);
  }
  for (int c = 0; c < sum.channels(); ++c) {
    if (in.channels() != 1 && c >= in.channels()) break;
    const std::vector<float>& from = in.channel[in.channels() == 1 ? 0 : c];
    for (std::size_t i = 0; i < kGraphBlock; ++i) sum.channel[c][i] += from[i];
  }
}

void fft(std::vector<std::complex<float>>& x, bool inverse) {
  const std::size_t n = x.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(x[i], x[j]);
  }
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const double angle = 2.0 * std::numbers::pi / static_cast<double>(len) * (inverse ? 1 : -1);
    const std::complex<double> w(std::cos(angle), std::sin(angle));
    for (std::size_t i = 0; i < n; i += len) {
      std::complex<double> wk(1.0, 0.0);
      for (std::size_t k = 0; k < len / 2; ++k) {
        const std::complex<float> u = x[i + k];
        const std::complex<float> v = x[i + k + len / 2] * std::complex<float>(wk);
        x[i + k] = u + v;
        x[i + k + len / 2] = u - v;
        wk *= w;
      }
    }
  }
}

namespace {

struct Coefficients {
  double b0 = 1, b1 = 0, b2 = 0, a1 = 0, a2 = 0;  // normalized by a0
};

Coefficients biquadCoefficients(const ProcessorParams& p) {
  const double nyquist = kGraphSampleRate / 2.0;
  const double f0 = std::clamp(static_cast<double>(p.frequency) * std::exp2(p.detune / 1200.0),
                               1e-3, nyquist - 1e-3);
  const double w0 = 2.0 * std::numbers::pi * f0 / kGraphSampleRate;
  const double cw = std::cos(w0), sw = std::sin(w0);
  const double q = std::max(1e-4, static_cast<double>(p.qualityFactor));
  const double a = std::pow(10.0, p.filterGain / 40.0);
  const double alphaQ = sw / (2.0 * q);
  const double alphaQdB = sw / (2.0 * std::pow(10.0, q / 20.0));  // lowpass, highpass
  const double alphaS = sw / 2.0 * std::sqrt(2.0);                // shelves, S = 1
  const double sa = 2.0 * alphaS * std::sqrt(a);
  double b0 = 1, b1 = 0, b2 = 0, a0 = 1, a1 = 0, a2 = 0;
  switch (p.biquad) {
    case BiquadType::lowpass:
      b0 = (1 - cw) / 2, b1 = 1 - cw, b2 = (1 - cw) / 2;
      a0 = 1 + alphaQdB, a1 = -2 * cw, a2 = 1 - alphaQdB;
      break;
    case BiquadType::highpass:
      b0 = (1 + cw) / 2, b1 = -(1 + cw), b2 = (1 + cw) / 2;
      a0 = 1 + alphaQdB, a1 = -2 * cw, a2 = 1 - alphaQdB;
      break;
    case BiquadType::bandpass:
      b0 = alphaQ, b1 = 0, b2 = -alphaQ;
      a0 = 1 + alphaQ, a1 = -2 * cw, a2 = 1 - alphaQ;
      break;
    case BiquadType::notch:
      b0 = 1, b1 = -2 * cw, b2 = 1;
      a0 = 1 + alphaQ, a1 = -2 * cw, a2 = 1 - alphaQ;
      break;
    case BiquadType::allpass:
      b0 = 1 - alphaQ, b1 = -2 * cw, b2 = 1 + alphaQ;
      a0 = 1 + alphaQ, a1 = -2 * cw, a2 = 1 - alphaQ;
      break;
    case BiquadType::peaking:
      b0 = 1 + alphaQ * a, b1 = -2 * cw, b2 = 1 - alphaQ * a;
      a0 = 1 + alphaQ / a, a1 = -2 * cw, a2 = 1 - alphaQ / a;
      break;
    case BiquadType::lowshelf:
      b0 = a * ((a + 1) - (a - 1) * cw + sa), b1 = 2 * a * ((a - 1) - (a + 1) * cw);
      b2 = a * ((a + 1) - (a - 1) * cw - sa);
      a0 = (a + 1) + (a - 1) * cw + sa, a1 = -2 * ((a - 1) + (a + 1) * cw);
      a2 = (a + 1) + (a - 1) * cw - sa;
      break;
    case BiquadType::highshelf:
      b0 = a * ((a + 1) + (a - 1) * cw + sa), b1 = -2 * a * ((a - 1) + (a + 1) * cw);
      b2 = a * ((a + 1) + (a - 1) * cw - sa);
      a0 = (a + 1) - (a - 1) * cw + sa, a1 = 2 * ((a - 1) - (a + 1) * cw);
      a2 = (a + 1) - (a - 1) * cw - sa;
      break;
  }
  return {b0 / a0, b1 / a0, b2 / a0, a1 / a0, a2 / a0};
}

}  // namespace

void renderBiquad(const ProcessorParams& p, BiquadState& s, const SignalBlock& in,
                  SignalBlock& out) {
  const Coefficients k = biquadCoefficients(p);
  silence(out, in.channels());
  for (int c = 0; c < in.channels(); ++c) {
    double& z1 = s.z[c][0];
    double& z2 = s.z[c][1];
    for (std::size_t i = 0; i < kGraphBlock; ++i) {
      const double x = in.channel[c][i];
      const double y = k.b0 * x + z1;
      z1 = k.b1 * x - k.a1 * y + z2;
      z2 = k.b2 * x - k.a2 * y;
      out.channel[c][i] = static_cast<float>(y);
    }
  }
}

void renderDelay(const ProcessorParams& p, DelayState& s, const SignalBlock& in, SignalBlock& out) {
  const double maxDelay = std::clamp(p.maxDelayTime, 0.0, 180.0);  // Web Audio: < 3 minutes
  const std::size_t size =
      static_cast<std::size_t>(std::ceil(maxDelay * kGraphSampleRate)) + kGraphBlock + 2;
  const int channels = std::max(in.channels(), static_cast<int>(s.ring.size()));
  if (s.ring.empty() || s.ring.front().size() != size) {
    s.ring.assign(static_cast<std::size_t>(channels), std::vector<float>(size, 0.0f));
    s.write = 0;
  }
  while (static_cast<int>(s.ring.size()) < channels) s.ring.emplace_back(size, 0.0f);
  silence(out, channels);
  const double delay = std::clamp(p.delayTime, 0.0, maxDelay) * kGraphSampleRate;
  for (std::size_t i = 0; i < kGraphBlock; ++i) {
    const std::size_t w = (s.write + i) % size;
    for (int c = 0; c < channels; ++c) {
      const int from = in.channels() == 1 ? 0 : c;
      s.ring[c][w] = from < in.channels() ? in.channel[from][i] : 0.0f;
      const double r = static_cast<double>(w + size) - delay;
      const auto k = static_cast<std::size_t>(std::floor(r));
      const float f = static_cast<float>(r - std::floor(r));
      const float a = s.ring[c][k % size], b = s.ring[c][(k + 1) % size];
      out.channel[c][i] = a + (b - a) * f;
    }
  }
  s.write = (s.write + kGraphBlock) % size;
}

void renderCompressor(const ProcessorParams& p, CompressorState& s, const SignalBlock& in,
                      SignalBlock& out) {
  // Web Audio's ranges (X_ITE clamps the fields to them).
  const float threshold = std::clamp(p.threshold, -100.0f, 0.0f);
  const float knee = std::clamp(p.knee, 0.0f, 40.0f);
  const float ratio = std::clamp(p.ratio, 1.0f, 20.0f);
  const double attack = std::clamp(p.attack, 0.0, 1.0), release = std::clamp(p.release, 0.0, 1.0);
  const double attackK = attack > 0.0 ? std::exp(-1.0 / (attack * kGraphSampleRate)) : 0.0;
  const double releaseK = release > 0.0 ? std::exp(-1.0 / (release * kGraphSampleRate)) : 0.0;
  silence(out, in.channels());
  for (std::size_t i = 0; i < kGraphBlock; ++i) {
    float peak = 0.0f;
    for (int c = 0; c < in.channels(); ++c) peak = std::max(peak, std::fabs(in.channel[c][i]));
    const float level = peak > 1e-9f ? 20.0f * std::log10(peak) : -200.0f;
    // The static curve: unity below the knee, slope 1 / ratio above, a quadratic between.
    float over = level - threshold;
    float compressed = level;
    if (2.0f * over >= knee) {
      compressed = threshold + over / ratio;
    } else if (knee > 0.0f && 2.0f * over > -knee) {
      const float x = over + knee / 2.0f;
      compressed = level + (1.0f / ratio - 1.0f) * x * x / (2.0f * knee);
    }
    const float target = std::min(0.0f, compressed - level);
    const double k = target < s.reductionDb ? attackK : releaseK;
    s.reductionDb = static_cast<float>(target + (s.reductionDb - target) * k);
    const float g = std::pow(10.0f, s.reductionDb / 20.0f);
    for (int c = 0; c < in.channels(); ++c) out.channel[c][i] = in.channel[c][i] * g;
  }
}

void renderWaveShaper(const ProcessorParams& p, const SignalBlock& in, SignalBlock& out) {
  silence(out, in.channels());
  const std::vector<float>& curve = p.curve;
  for (int c = 0; c < in.channels(); ++c)
    for (std::size_t i = 0; i < kGraphBlock; ++i) {
      const float x = in.channel[c][i];
      if (curve.size() < 2) {
        out.channel[c][i] = x;
        continue;
      }
      const float v = static_cast<float>(curve.size() - 1) / 2.0f * (x + 1.0f);
      if (!(v > 0.0f)) {
        out.channel[c][i] = curve.front();
      } else if (v >= static_cast<float>(curve.size() - 1)) {
        out.channel[c][i] = curve.back();
      } else {
        const auto k = static_cast<std::size_t>(v);
        const float f = v - static_cast<float>(k);
        out.channel[c][i] = curve[k] * (1.0f - f) + curve[k + 1] * f;
      }
    }
}

PartitionedConvolution::PartitionedConvolution(const std::vector<float>& impulse)
    : overlap_(kGraphBlock, 0.0f) {
  const std::size_t n = 2 * kGraphBlock;
  for (std::size_t at = 0; at < impulse.size(); at += kGraphBlock) {
    Spectrum s(n);
    for (std::size_t i = 0; i < kGraphBlock && at + i < impulse.size(); ++i) s[i] = impulse[at + i];
    fft(s, false);
    partitions_.push_back(std::move(s));
  }
  history_.assign(partitions_.size(), Spectrum(n));
}

void PartitionedConvolution::process(const float* in, float* out) {
  const std::size_t n = 2 * kGraphBlock;
  if (partitions_.empty()) {
    std::fill(out, out + kGraphBlock, 0.0f);
    return;
  }
  head_ = (head_ + history_.size() - 1) % history_.size();
  Spectrum& x = history_[head_];
  std::fill(x.begin(), x.end(), std::complex<float>());
  for (std::size_t i = 0; i < kGraphBlock; ++i) x[i] = in[i];
  fft(x, false);
  Spectrum y(n);
  for (std::size_t p = 0; p < partitions_.size(); ++p) {
    const Spectrum& h = partitions_[p];
    const Spectrum& past = history_[(head_ + p) % history_.size()];
    for (std::size_t k = 0; k < n; ++k) y[k] += past[k] * h[k];
  }
  fft(y, true);
  const float scale = 1.0f / static_cast<float>(n);
  for (std::size_t i = 0; i < kGraphBlock; ++i) {
    out[i] = y[i].real() * scale + overlap_[i];
    overlap_[i] = y[i + kGraphBlock].real() * scale;
  }
}

}  // namespace gs::audio::detail

namespace gs::audio {

float convolverNormalization(const SampledSound& sound) {
  // Web Audio 1.0 1.15.3, calculateNormalizationScale.
  constexpr double kGainCalibration = 0.00125, kCalibrationRate = 44100.0, kMinPower = 0.000125;
  const std::size_t frames = sound.frames();
  double power = 0.0;
  for (float v : sound.samples) power += static_cast<double>(v) * v;
  power = frames > 0 ? std::sqrt(power / (static_cast<double>(sound.channels) * frames)) : 0.0;
  if (!std::isfinite(power) || power < kMinPower) power = kMinPower;
  double scale = 1.0 / power * kGainCalibration;
  if (sound.sampleRate > 0) scale *= kCalibrationRate / sound.sampleRate;
  if (sound.channels == 4) scale *= 0.5;
  return static_cast<float>(scale);
}

}  // namespace gs::audio

namespace gs::audio::detail {

void renderConvolver(const ProcessorParams& p, ConvolverState& s, const SignalBlock& in,
                     SignalBlock& out) {
  const SampledSound* impulse = p.sound.get();
  if (!impulse || impulse->frames() == 0 || impulse->channels < 1) {
    silence(out, in.channels());
    return;
  }
  const int outChannels =
      std::min(2, std::max(std::max(in.channels(), 1), std::min(impulse->channels, 2)));
  if (s.impulse != impulse || s.normalize != p.normalize ||
      static_cast<int>(s.channels.size()) != outChannels) {
    s.impulse = impulse;
    s.normalize = p.normalize;
    s.channels.clear();
    const float scale = p.normalize ? convolverNormalization(*impulse) : 1.0f;
    for (int c = 0; c < outChannels; ++c) {
      const int from = impulse->channels == 1 ? 0 : std::min(c, impulse->channels - 1);
      std::vector<float> response(impulse->frames());
      for (std::size_t i = 0; i < response.size(); ++i)
        response[i] = impulse->samples[i * impulse->channels + from] * scale;
      s.channels.emplace_back(response);
    }
  }
  silence(out, outChannels);
  const std::vector<float> zeros(kGraphBlock, 0.0f);
  for (int c = 0; c < outChannels; ++c) {
    const float* x = in.channels() == 0   ? zeros.data()
                     : in.channels() == 1 ? in.channel[0].data()
                                          : in.channel[std::min(c, in.channels() - 1)].data();
    s.channels[c].process(x, out.channel[c].data());
  }
}

}  // namespace gs::audio::detail

namespace gs::audio {

float distanceGain(DistanceModel model, float distance, float ref, float maxDistance,
                   float rolloff) {
  ref = std::max(ref, 0.0f);
  rolloff = std::max(rolloff, 0.0f);
  switch (model) {
    case DistanceModel::linear: {
      rolloff = std::min(rolloff, 1.0f);
      if (!(maxDistance > ref)) return distance < ref ? 1.0f : 1.0f - rolloff;
      const float d = std::clamp(distance, ref, maxDistance);
      return 1.0f - rolloff * (d - ref) / (maxDistance - ref);
    }
    case DistanceModel::inverse: {
      if (ref <= 0.0f) return distance > 0.0f ? 0.0f : 1.0f;
      return ref / (ref + rolloff * (std::max(distance, ref) - ref));
    }
    case DistanceModel::exponential:
      if (ref <= 0.0f) return distance > 0.0f ? 0.0f : 1.0f;
      return std::pow(std::max(distance, ref) / ref, -rolloff);
  }
  return 1.0f;
}

float coneGain(const glm::vec3& direction, const glm::vec3& toListener, float inner, float outer,
               float outerGain) {
  constexpr float kFull = 2.0f * std::numbers::pi_v<float>;
  if (inner >= kFull - 1e-4f && outer >= kFull - 1e-4f) return 1.0f;
  if (glm::length(direction) <= 0.0f || glm::length(toListener) <= 0.0f) return 1.0f;
  const float cosAngle =
      std::clamp(glm::dot(glm::normalize(direction), glm::normalize(toListener)), -1.0f, 1.0f);
  const float angle = std::acos(cosAngle);  // 0..pi
  const float halfInner = std::clamp(inner, 0.0f, kFull) / 2.0f;
  const float halfOuter = std::clamp(outer, 0.0f, kFull) / 2.0f;
  outerGain = std::clamp(outerGain, 0.0f, 1.0f);
  if (angle <= halfInner) return 1.0f;
  if (angle >= halfOuter) return outerGain;
  const float x = (angle - halfInner) / (halfOuter - halfInner);
  return 1.0f + (outerGain - 1.0f) * x;
}

}  // namespace gs::audio

namespace gs::audio::detail {

void renderSpatialSound(const ProcessorParams& p, const glm::mat4& worldToListener,
                        const SignalBlock& in, SignalBlock& out) {
  // The input as two channels ("explicit" 2, speakers), times gain and intensity.
  silence(out, 2);
  if (in.channels() == 0) return;
  const float g = std::clamp(p.intensity, 0.0f, 1.0f) * p.gain;
  const bool mono = in.channels() == 1;
  const std::vector<float>& left = in.channel[0];
  const std::vector<float>& right = mono ? in.channel[0] : in.channel[1];
  if (!p.spatialize) {
    for (std::size_t i = 0; i < kGraphBlock; ++i) {
      out.channel[0][i] = left[i] * g;
      out.channel[1][i] = right[i] * g;
    }
    return;
  }
  const glm::vec3 source(worldToListener * glm::vec4(p.location, 1.0f));
  const glm::vec3 direction(worldToListener * glm::vec4(p.direction, 0.0f));
  const float distance = glm::length(source);
  const float gain =
      g *
      distanceGain(p.distanceModel, distance, p.referenceDistance, p.maxDistance, p.rolloffFactor) *
      coneGain(direction, -source, p.coneInnerAngle, p.coneOuterAngle, p.coneOuterGain);
  // Azimuth in degrees: 0 ahead (-z), +90 to the right (+x), folded to the front half.
  float azimuth = 0.0f;
  if (source.x != 0.0f || source.z != 0.0f) azimuth = glm::degrees(std::atan2(source.x, -source.z));
  if (azimuth < -90.0f) azimuth = -180.0f - azimuth;
  if (azimuth > 90.0f) azimuth = 180.0f - azimuth;
  const float halfPi = std::numbers::pi_v<float> / 2.0f;
  if (mono) {
    const float x = (azimuth + 90.0f) / 180.0f;
    const float gl = std::cos(x * halfPi) * gain, gr = std::sin(x * halfPi) * gain;
    for (std::size_t i = 0; i < kGraphBlock; ++i) {
      out.channel[0][i] = left[i] * gl;
      out.channel[1][i] = left[i] * gr;
    }
    return;
  }
  // Stereo input (Web Audio 1.0 1.27.5.2): the far channel is moved into the near one.
  const float x = azimuth <= 0.0f ? (azimuth + 90.0f) / 90.0f : azimuth / 90.0f;
  const float gl = std::cos(x * halfPi), gr = std::sin(x * halfPi);
  for (std::size_t i = 0; i < kGraphBlock; ++i) {
    if (azimuth <= 0.0f) {
      out.channel[0][i] = (left[i] + right[i] * gl) * gain;
      out.channel[1][i] = right[i] * gr * gain;
    } else {
      out.channel[0][i] = left[i] * gl * gain;
      out.channel[1][i] = (right[i] + left[i] * gr) * gain;
    }
  }
}

}  // namespace gs::audio::detail
