// The audio graph (audio/audio_graph.hpp): processors keyed by their nodes, rendered block
// by block from the destinations and SpatialSounds down to the sources, each processor's
// output computed once per block however many processors take it in.
#include "audio/audio_graph.hpp"

#include "audio_processors.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace gs::audio {

using detail::mixInto;
using detail::silence;

struct AudioGraph::State {
  struct Processor {
    ProcessorParams params;
    bool set = false;  // set since the last render
    detail::OscillatorState oscillator;
    detail::BufferState buffer;
    detail::BiquadState biquad;
    detail::DelayState delay;
    detail::CompressorState compressor;
    detail::ConvolverState convolver;
    SignalBlock out;
    SignalBlock in;              // the sum of the inputs, for process()
    std::uint64_t outBlock = 0;  // the block `out` was computed for
    bool visiting = false;       // on the path being computed: a cycle
  };
  std::unordered_map<const void*, Processor> processors;
  std::vector<const void*> order;  // the processors in the order they were set
  glm::mat4 worldToListener{1.0f};
  std::uint64_t block = 0;
  /// Channel i of a ChannelSplitter goes to each node of its outputs[i].
  std::unordered_map<const void*, std::vector<std::pair<const void*, int>>> splitterFeeds;
  std::vector<float> pending;  // rendered stereo frames not yet handed out

  const SignalBlock& output(const void* key);
  void input(const void* key, Processor& p, SignalBlock& sum);
  void process(const void* key, Processor& p);
};

namespace {

const SignalBlock& silentBlock() {
  static const SignalBlock none;
  return none;
}

bool isSource(ProcessorType t) {
  return t == ProcessorType::oscillator || t == ProcessorType::buffer ||
         t == ProcessorType::captured || t == ProcessorType::silence;
}

void scaleBlock(SignalBlock& b, float g) {
  if (g == 1.0f) return;
  for (auto& c : b.channel)
    for (float& v : c) v *= g;
}

}  // namespace

void AudioGraph::State::input(const void* key, Processor& p, SignalBlock& sum) {
  silence(sum, 0);
  for (const void* in : p.params.inputs) mixInto(sum, output(in));
  if (const auto f = splitterFeeds.find(key); f != splitterFeeds.end())
    for (const auto& [splitter, channel] : f->second) {
      const SignalBlock& all = output(splitter);
      const auto it = processors.find(splitter);
      const bool split = it != processors.end() && it->second.params.enabled;
      if (!split) {
        mixInto(sum, all);
      } else if (channel < all.channels()) {
        SignalBlock one;
        one.channel.push_back(all.channel[static_cast<std::size_t>(channel)]);
        mixInto(sum, one);
      }
    }
}

const SignalBlock& AudioGraph::State::output(const void* key) {
  const auto it = processors.find(key);
  if (it == processors.end()) return silentBlock();
  Processor& p = it->second;
  if (p.outBlock == block) return p.out;
  if (p.visiting) return silentBlock();  // the input that closes a cycle
  p.visiting = true;
  process(key, p);
  p.visiting = false;
  p.outBlock = block;
  return p.out;
}

void AudioGraph::State::process(const void* key, Processor& p) {
  const ProcessorParams& q = p.params;
  if (isSource(q.type)) {
    if (!q.enabled || !q.running || q.type == ProcessorType::silence) {
      silence(p.out, 0);
      return;
    }
    if (q.type == ProcessorType::oscillator) detail::renderOscillator(q, p.oscillator, p.out);
    if (q.type == ProcessorType::buffer) detail::renderBuffer(q, p.buffer, p.out);
    if (q.type == ProcessorType::captured) {
      silence(p.out, 1);
      std::deque<float>* fifo = q.captured.get();
      for (std::size_t i = 0; fifo != nullptr && i < kGraphBlock && !fifo->empty(); ++i) {
        p.out.channel[0][i] = fifo->front();
        fifo->pop_front();
      }
    }
    scaleBlock(p.out, q.gain);
    return;
  }
  SignalBlock& in = p.in;  // kept with the processor: its buffers are reused block to block
  input(key, p, in);
  if (q.type == ProcessorType::destination) {
    if (!q.enabled) {
      silence(p.out, 0);
      return;
    }
    scaleBlock(in, q.gain);
    in.channel.resize(static_cast<std::size_t>(
        std::min(in.channels(), std::clamp(q.maxChannelCount, 1, kGraphMaxChannels))));
    std::swap(p.out, in);
    return;
  }
  if (q.type == ProcessorType::spatialSound) {
    detail::renderSpatialSound(q, worldToListener, in, p.out);
    return;
  }
  // Processing and channel nodes: a disabled one passes its input on unchanged (X_ITE 15);
  // `gain` scales the input before the processing (X_ITE's input GainNode).
  if (!q.enabled) {
    std::swap(p.out, in);
    return;
  }
  scaleBlock(in, q.gain);
  switch (q.type) {
    case ProcessorType::biquadFilter:
      detail::renderBiquad(q, p.biquad, in, p.out);
      break;
    case ProcessorType::delay:
      detail::renderDelay(q, p.delay, in, p.out);
      break;
    case ProcessorType::dynamicsCompressor:
      detail::renderCompressor(q, p.compressor, in, p.out);
      break;
    case ProcessorType::waveShaper:
      detail::renderWaveShaper(q, in, p.out);
      break;
    case ProcessorType::convolver:
      detail::renderConvolver(q, p.convolver, in, p.out);
      break;
    case ProcessorType::channelSelector: {
      const int c = std::clamp(q.channelSelection, 0, kGraphMaxChannels - 1);
      silence(p.out, 1);
      if (c < in.channels()) p.out.channel[0] = in.channel[static_cast<std::size_t>(c)];
      break;
    }
    case ProcessorType::channelMerger: {
      // Input i, down-mixed to mono, is channel i (its gain applied after: linear).
      const std::size_t n = std::min<std::size_t>(q.inputs.size(), kGraphMaxChannels);
      silence(p.out, static_cast<int>(std::max<std::size_t>(n, 1)));
      for (std::size_t i = 0; i < n; ++i) {
        const SignalBlock& one = output(q.inputs[i]);
        if (one.channels() == 0) continue;
        for (std::size_t k = 0; k < kGraphBlock; ++k) {
          float v = 0.0f;
          for (const auto& c : one.channel) v += c[k];
          p.out.channel[i][k] = v / static_cast<float>(one.channels()) * q.gain;
        }
      }
      break;
    }
    default:  // gain, analyser, channelSplitter: the (scaled) input
      std::swap(p.out, in);
      break;
  }
}

AudioGraph::AudioGraph() : state_(std::make_unique<State>()) {}
AudioGraph::~AudioGraph() = default;

void AudioGraph::set(const void* key, ProcessorParams params) {
  auto [it, added] = state_->processors.try_emplace(key);
  if (added) state_->order.push_back(key);
  it->second.params = std::move(params);
  it->second.set = true;
}

void AudioGraph::setListener(const glm::mat4& worldToListener) {
  state_->worldToListener = worldToListener;
}

std::size_t AudioGraph::size() const {
  return state_->processors.size();
}

float AudioGraph::reduction(const void* key) const {
  const auto it = state_->processors.find(key);
  return it == state_->processors.end() ? 0.0f : it->second.compressor.reductionDb;
}

void AudioGraph::render(std::size_t frames, std::vector<float>& stereo) {
  State& s = *state_;
  // Forget what was not set since the last render.
  std::erase_if(s.processors, [](const auto& e) { return !e.second.set; });
  std::erase_if(s.order, [&s](const void* k) { return !s.processors.contains(k); });
  s.splitterFeeds.clear();
  std::vector<const void*> roots;
  for (const void* key : s.order) {
    State::Processor& p = s.processors.at(key);
    p.set = false;
    const ProcessorParams& q = p.params;
    if (q.type == ProcessorType::destination || q.type == ProcessorType::spatialSound)
      roots.push_back(key);
    if (q.type == ProcessorType::channelSplitter)
      for (std::size_t i = 0; i < q.outputs.size() && i < kGraphMaxChannels; ++i)
        s.splitterFeeds[q.outputs[i]].emplace_back(key, static_cast<int>(i));
    if (q.type == ProcessorType::buffer)
      detail::placeBuffer(q, p.buffer, static_cast<double>(frames) / kGraphSampleRate);
  }
  std::array<float, kGraphBlock> left{}, right{};
  while (s.pending.size() < 2 * frames) {
    ++s.block;
    left.fill(0.0f);
    right.fill(0.0f);
    for (const void* root : roots) {
      const SignalBlock& out = s.output(root);
      if (out.channels() == 0) continue;
      const std::vector<float>& l = out.channel[0];
      const std::vector<float>& r = out.channels() > 1 ? out.channel[1] : out.channel[0];
      for (std::size_t i = 0; i < kGraphBlock; ++i) {
        left[i] += l[i];
        right[i] += r[i];
      }
    }
    for (std::size_t i = 0; i < kGraphBlock; ++i) {
      s.pending.push_back(left[i]);
      s.pending.push_back(right[i]);
    }
  }
  stereo.insert(stereo.end(), s.pending.begin(),
                s.pending.begin() + static_cast<std::ptrdiff_t>(2 * frames));
  s.pending.erase(s.pending.begin(), s.pending.begin() + static_cast<std::ptrdiff_t>(2 * frames));
}

}  // namespace gs::audio
