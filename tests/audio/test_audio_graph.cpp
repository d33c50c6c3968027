// The X3D 4 audio graph's signal processing (audio/audio_graph.hpp), without nodes: each
// processor's output checked against what the Web Audio API's formulas give.
#include "audio/audio_graph.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace gs::audio;

namespace {

// Keys: any distinct addresses.
int keys[16];
const void* k(int i) {
  return &keys[i];
}

ProcessorParams destination(std::vector<const void*> inputs) {
  ProcessorParams p;
  p.type = ProcessorType::destination;
  p.inputs = std::move(inputs);
  return p;
}

ProcessorParams sine(float frequency, float gain = 1.0f) {
  ProcessorParams p;
  p.type = ProcessorType::oscillator;
  p.wave = WaveForm::sine;
  p.frequency = frequency;
  p.gain = gain;
  return p;
}

/// A sampled sound of `channels` channels, `frames` long, from f(frame, channel).
template <class F>
std::shared_ptr<const SampledSound> sampled(int channels, std::size_t frames, F f) {
  auto s = std::make_shared<SampledSound>();
  s->channels = channels;
  for (std::size_t i = 0; i < frames; ++i)
    for (int c = 0; c < channels; ++c) s->samples.push_back(f(i, c));
  return s;
}

ProcessorParams buffer(std::shared_ptr<const SampledSound> sound) {
  ProcessorParams p;
  p.type = ProcessorType::buffer;
  p.sound = std::move(sound);
  return p;
}

/// Left (channel 0) or right (1) of an interleaved stereo stream.
std::vector<float> side(const std::vector<float>& stereo, int c) {
  std::vector<float> out;
  for (std::size_t i = static_cast<std::size_t>(c); i < stereo.size(); i += 2)
    out.push_back(stereo[i]);
  return out;
}

float peak(const std::vector<float>& v, std::size_t from = 0) {
  float m = 0.0f;
  for (std::size_t i = from; i < v.size(); ++i) m = std::max(m, std::fabs(v[i]));
  return m;
}

int zeroCrossings(const std::vector<float>& v) {
  int n = 0;
  for (std::size_t i = 1; i < v.size(); ++i)
    if ((v[i - 1] < 0.0f) != (v[i] < 0.0f)) ++n;
  return n;
}

}  // namespace

TEST_CASE("Audio graph: an oscillator's frequency, gain and waves", "[audio][graph]") {
  AudioGraph g;
  g.set(k(0), destination({k(1)}));
  g.set(k(1), sine(441.0f, 0.5f));
  std::vector<float> out;
  g.render(4410, out);  // 0.1 s: 44.1 cycles
  REQUIRE(out.size() == 2 * 4410);
  const std::vector<float> left = side(out, 0);
  CHECK(left == side(out, 1));  // a mono destination input is heard in both ears
  CHECK(zeroCrossings(left) == Approx(88).margin(1));
  CHECK(peak(left) == Approx(0.5f).margin(0.002));
  CHECK(left[25] ==
        Approx(0.5f * std::sin(2.0 * std::numbers::pi * 441.0 * 25 / 44100)).margin(1e-3));

  for (WaveForm w : {WaveForm::square, WaveForm::sawtooth, WaveForm::triangle}) {
    AudioGraph h;
    ProcessorParams o = sine(441.0f);
    o.wave = w;
    h.set(k(0), destination({k(1)}));
    h.set(k(1), o);
    std::vector<float> s;
    h.render(4410, s);
    CHECK(peak(side(s, 0)) == Approx(1.0f).margin(0.01));  // normalized to peak 1
    CHECK(zeroCrossings(side(s, 0)) == Approx(88).margin(2));
  }
  // A custom wave of the second harmonic alone sounds an octave up.
  AudioGraph h;
  ProcessorParams o = sine(441.0f);
  o.wave = WaveForm::custom;
  o.real = {0.0f, 0.0f, 0.0f};
  o.imag = {0.0f, 0.0f, 1.0f};
  h.set(k(0), destination({k(1)}));
  h.set(k(1), o);
  std::vector<float> s;
  h.render(4410, s);
  CHECK(zeroCrossings(side(s, 0)) == Approx(176).margin(2));
}

TEST_CASE("Audio graph: silent sources, disabled destinations and cycles", "[audio][graph]") {
  AudioGraph g;
  ProcessorParams o = sine(441.0f);
  o.running = false;
  g.set(k(0), destination({k(1)}));
  g.set(k(1), o);
  std::vector<float> out;
  g.render(1000, out);
  CHECK(peak(out) == 0.0f);

  ProcessorParams d = destination({k(1)});
  d.enabled = false;
  g.set(k(0), d);
  g.set(k(1), sine(441.0f));
  out.clear();
  g.render(1000, out);
  CHECK(peak(out) == 0.0f);

  // Gain 2 takes Gain 3 and the oscillator; Gain 3 takes Gain 2: the cycle is cut.
  ProcessorParams a, b;
  a.inputs = {k(3), k(1)};
  b.inputs = {k(2)};
  g.set(k(0), destination({k(2)}));
  g.set(k(1), sine(441.0f));
  g.set(k(2), a);
  g.set(k(3), b);
  out.clear();
  g.render(4410, out);
  CHECK(std::all_of(out.begin(), out.end(), [](float v) { return std::isfinite(v); }));
  CHECK(peak(out) == Approx(1.0f).margin(0.01));  // the input closing the cycle is silent
  // What is not set again is forgotten.
  g.set(k(0), destination({}));
  out.clear();
  g.render(128, out);
  CHECK(g.size() == 1);
}

TEST_CASE("Audio graph: filters, delay, wave shaper and compressor", "[audio][graph]") {
  auto through = [](ProcessorParams processor, float frequency, std::size_t frames) {
    AudioGraph g;
    processor.inputs = {k(2)};
    g.set(k(0), destination({k(1)}));
    g.set(k(1), processor);
    g.set(k(2), sine(frequency));
    std::vector<float> out;
    g.render(frames, out);
    return side(out, 0);
  };
  ProcessorParams lowpass;
  lowpass.type = ProcessorType::biquadFilter;
  lowpass.frequency = 500.0f;
  CHECK(peak(through(lowpass, 5000.0f, 8820), 4410) < 0.02f);  // -40 dB a decade
  CHECK(peak(through(lowpass, 100.0f, 8820), 4410) == Approx(1.0f).margin(0.05));
  ProcessorParams highpass = lowpass;
  highpass.biquad = BiquadType::highpass;
  CHECK(peak(through(highpass, 5000.0f, 8820), 4410) == Approx(1.0f).margin(0.05));
  CHECK(peak(through(highpass, 50.0f, 8820), 4410) < 0.02f);
  ProcessorParams notch = lowpass;
  notch.biquad = BiquadType::notch;
  notch.frequency = 1000.0f;
  CHECK(peak(through(notch, 1000.0f, 44100), 22050) < 0.02f);

  // Delay: an impulse comes out delayTime later.
  {
    AudioGraph g;
    ProcessorParams delay;
    delay.type = ProcessorType::delay;
    delay.delayTime = 0.01;
    delay.inputs = {k(2)};
    g.set(k(0), destination({k(1)}));
    g.set(k(1), delay);
    g.set(k(2), buffer(sampled(1, 1, [](std::size_t, int) { return 1.0f; })));
    std::vector<float> out;
    g.render(1024, out);
    const std::vector<float> left = side(out, 0);
    CHECK(left[441] == Approx(1.0f));
    CHECK(peak(left) == Approx(1.0f));
    CHECK(std::count_if(left.begin(), left.end(), [](float v) { return v != 0.0f; }) == 1);
  }

  // WaveShaper [0 0 1]: negative half-waves cut, positive ones kept.
  ProcessorParams shaper;
  shaper.type = ProcessorType::waveShaper;
  shaper.curve = {0.0f, 0.0f, 1.0f};
  const std::vector<float> shaped = through(shaper, 441.0f, 4410);
  CHECK(*std::min_element(shaped.begin(), shaped.end()) >= 0.0f);
  CHECK(peak(shaped) == Approx(1.0f).margin(0.01));

  // DynamicsCompressor: a full-scale tone is pulled down, ratio 12 over -24 dB.
  AudioGraph g;
  ProcessorParams compressor;
  compressor.type = ProcessorType::dynamicsCompressor;
  compressor.inputs = {k(2)};
  g.set(k(0), destination({k(1)}));
  g.set(k(1), compressor);
  g.set(k(2), sine(441.0f));
  std::vector<float> out;
  g.render(44100, out);
  CHECK(peak(side(out, 0), 22050) < 0.2f);
  CHECK(g.reduction(k(1)) < -15.0f);
  CHECK(g.reduction(k(0)) == 0.0f);
}

TEST_CASE("Audio graph: the convolver equals direct convolution", "[audio][graph]") {
  // A decaying noise response of 700 frames (6 partitions) and a noise input.
  std::uint32_t seed = 1;
  auto noise = [&seed]() {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<float>(seed >> 8) / 8388608.0f - 1.0f;
  };
  std::vector<float> response(700), input(2000);
  for (std::size_t i = 0; i < response.size(); ++i) response[i] = noise() * std::exp(-0.005f * i);
  for (float& v : input) v = noise() * 0.5f;
  AudioGraph g;
  ProcessorParams conv;
  conv.type = ProcessorType::convolver;
  conv.sound = sampled(1, response.size(), [&](std::size_t i, int) { return response[i]; });
  conv.inputs = {k(2)};
  g.set(k(0), destination({k(1)}));
  g.set(k(1), conv);
  g.set(k(2), buffer(sampled(1, input.size(), [&](std::size_t i, int) { return input[i]; })));
  std::vector<float> out;
  g.render(2048, out);
  const std::vector<float> left = side(out, 0);
  for (std::size_t n : {0u, 1u, 127u, 128u, 699u, 700u, 1500u, 1999u}) {
    double expected = 0.0;
    for (std::size_t j = 0; j < response.size() && j <= n; ++j)
      expected += static_cast<double>(response[j]) * input[n - j];
    CHECK(left[n] == Approx(expected).margin(1e-3));
  }
  // Normalization (Web Audio 1.0 1.15.3): 1 / RMS x 0.00125 at 44.1 kHz.
  SampledSound one;
  one.samples = {1.0f, 1.0f, 1.0f, 1.0f};
  CHECK(convolverNormalization(one) == Approx(0.00125f));
}

TEST_CASE("Audio graph: channel splitter, selector and merger", "[audio][graph]") {
  // Stereo: left 1, right 0.5.
  auto stereo = sampled(2, 4000, [](std::size_t, int c) { return c == 0 ? 1.0f : 0.5f; });
  {
    AudioGraph g;
    ProcessorParams select;
    select.type = ProcessorType::channelSelector;
    select.channelSelection = 1;
    select.inputs = {k(2)};
    g.set(k(0), destination({k(1)}));
    g.set(k(1), select);
    g.set(k(2), buffer(stereo));
    std::vector<float> out;
    g.render(256, out);
    CHECK(out[0] == Approx(0.5f));  // the right channel, heard in both ears
    CHECK(out[1] == Approx(0.5f));
  }
  // The splitter sends left to Gain 4 and right to Gain 3; the merger takes them in the
  // order Gain 3, Gain 4: the channels are swapped.
  AudioGraph g;
  ProcessorParams split, merge, right, left;
  split.type = ProcessorType::channelSplitter;
  split.inputs = {k(2)};
  split.outputs = {k(4), k(3)};
  merge.type = ProcessorType::channelMerger;
  merge.inputs = {k(3), k(4)};
  g.set(k(0), destination({k(1)}));
  g.set(k(1), merge);
  g.set(k(2), buffer(stereo));
  g.set(k(3), right);
  g.set(k(4), left);
  g.set(k(5), split);
  std::vector<float> out;
  g.render(256, out);
  CHECK(out[0] == Approx(0.5f));
  CHECK(out[1] == Approx(1.0f));
}

TEST_CASE("Audio graph: SpatialSound's distance, cone and panning", "[audio][graph]") {
  CHECK(distanceGain(DistanceModel::inverse, 2.0f, 1.0f, 10000.0f, 1.0f) == Approx(0.5f));
  CHECK(distanceGain(DistanceModel::inverse, 0.5f, 1.0f, 10000.0f, 1.0f) == Approx(1.0f));
  CHECK(distanceGain(DistanceModel::linear, 5.5f, 1.0f, 10.0f, 1.0f) == Approx(0.5f));
  CHECK(distanceGain(DistanceModel::exponential, 4.0f, 1.0f, 10.0f, 2.0f) == Approx(1.0f / 16));
  const float pi = std::numbers::pi_v<float>;
  CHECK(coneGain({0, 0, 1}, {0, 0, -1}, pi / 2, pi, 0.25f) == Approx(0.25f));  // behind
  CHECK(coneGain({0, 0, 1}, {0, 0, 1}, pi / 2, pi, 0.25f) == Approx(1.0f));    // ahead
  CHECK(coneGain({0, 0, 1}, {1, 0, 1}, 0.0f, pi, 0.0f) == Approx(0.5f));       // 45 of 90
  CHECK(coneGain({0, 0, 1}, {0, 0, -1}, 2 * pi, 2 * pi, 0.0f) == 1.0f);

  // A tone 2 m to the listener's right: inverse model 0.5, all in the right ear.
  AudioGraph g;
  ProcessorParams spatial;
  spatial.type = ProcessorType::spatialSound;
  spatial.location = {2.0f, 0.0f, 0.0f};
  spatial.inputs = {k(1)};
  g.set(k(0), spatial);
  g.set(k(1), sine(441.0f));
  std::vector<float> out;
  g.render(4410, out);
  CHECK(peak(side(out, 0)) < 1e-4f);
  CHECK(peak(side(out, 1)) == Approx(0.5f).margin(0.005));
  // Ahead: equal power, cos 45 degrees in each ear.
  spatial.location = {0.0f, 0.0f, -1.0f};
  g.set(k(0), spatial);
  g.set(k(1), sine(441.0f));
  out.clear();
  g.render(4410, out);
  CHECK(peak(side(out, 0)) == Approx(std::sqrt(0.5f)).margin(0.005));
  CHECK(peak(side(out, 1)) == Approx(std::sqrt(0.5f)).margin(0.005));
  // The listener turned to face the sound (+x): ahead now.
  spatial.location = {2.0f, 0.0f, 0.0f};
  g.set(k(0), spatial);
  g.set(k(1), sine(441.0f));
  g.setListener(glm::mat4(glm::vec4(0, 0, -1, 0), glm::vec4(0, 1, 0, 0), glm::vec4(1, 0, 0, 0),
                          glm::vec4(0, 0, 0, 1)));  // world +x to eye -z
  out.clear();
  g.render(4410, out);
  // (The first block is the last render's: the graph renders whole blocks.)
  CHECK(peak(side(out, 0), kGraphBlock) == Approx(0.5f * std::sqrt(0.5f)).margin(0.005));
  CHECK(peak(side(out, 1), kGraphBlock) == Approx(0.5f * std::sqrt(0.5f)).margin(0.005));
}
