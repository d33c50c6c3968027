// The OpenAL Soft output: one source per voice (up to 32), one buffer per clip. The
// ellipsoid model of 6.42 sets each source's gain, so OpenAL's own distance model is off.
#include "audio/audio_output.hpp"

#include "audio/audio_graph.hpp"

#include <AL/al.h>
#include <AL/alc.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <unordered_map>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

namespace gs::audio {

namespace {

class OpenAlOutput final : public AudioOutput {
 public:
  OpenAlOutput(ALCdevice* device, ALCcontext* context) : device_(device), context_(context) {
    alcMakeContextCurrent(context_);
    alDistanceModel(AL_NONE);
    const ALCchar* name = alcGetString(device_, ALC_DEVICE_SPECIFIER);
    name_ = std::string("OpenAL Soft: ") + (name != nullptr ? name : "default device");
  }
  ~OpenAlOutput() override {
    if (capture_ != nullptr) {
      alcCaptureStop(capture_);
      alcCaptureCloseDevice(capture_);
    }
    alcMakeContextCurrent(context_);
    for (auto& [key, s] : sources_) alDeleteSources(1, &s.id);
    if (stream_ != 0) {
      alSourceStop(stream_);
      ALint queued = 0;
      alGetSourcei(stream_, AL_BUFFERS_QUEUED, &queued);
      std::vector<ALuint> ids(static_cast<std::size_t>(queued));
      if (queued > 0) alSourceUnqueueBuffers(stream_, queued, ids.data());
      alDeleteBuffers(queued, ids.data());
      alDeleteSources(1, &stream_);
    }
    for (auto& [clip, b] : buffers_) alDeleteBuffers(1, &b);
    alcMakeContextCurrent(nullptr);
    alcDestroyContext(context_);
    alcCloseDevice(device_);
  }
  bool isNull() const override { return false; }
  std::string name() const override { return name_; }
  std::size_t maxVoices() const override { return 32; }

  void update(const std::vector<Voice>& voices) override {
    alcMakeContextCurrent(context_);
    std::unordered_map<const void*, bool> keep;
    for (const Voice& v : voices) {
      if (!v.clip || v.clip->samples.empty()) continue;
      keep[v.key] = true;
      Source& s = sources_[v.key];
      if (s.id == 0) alGenSources(1, &s.id);
      const ALuint buffer = bufferOf(*v.clip);
      if (s.clip != v.clip.get()) {
        alSourceStop(s.id);
        alSourcei(s.id, AL_BUFFER, static_cast<ALint>(buffer));
        s.clip = v.clip.get();
      }
      alSourcef(s.id, AL_GAIN, v.gain);
      alSourcef(s.id, AL_PITCH, v.pitch);
      alSourcei(s.id, AL_LOOPING, v.loop ? AL_TRUE : AL_FALSE);
      alSourcei(s.id, AL_SOURCE_RELATIVE, AL_TRUE);
      const glm::vec3 p = v.spatialize ? v.position : glm::vec3(0.0f);
      alSource3f(s.id, AL_POSITION, p.x, p.y, p.z);
      ALint state = AL_STOPPED;
      alGetSourcei(s.id, AL_SOURCE_STATE, &state);
      float at = 0.0f;
      alGetSourcef(s.id, AL_SEC_OFFSET, &at);
      if (state != AL_PLAYING || std::fabs(at - static_cast<float>(v.offset)) > 0.1f) {
        alSourcef(s.id, AL_SEC_OFFSET, static_cast<float>(v.offset));
        if (state != AL_PLAYING) alSourcePlay(s.id);
      }
    }
    for (auto it = sources_.begin(); it != sources_.end();) {
      if (keep.count(it->first) == 0) {
        alSourceStop(it->second.id);
        alDeleteSources(1, &it->second.id);
        it = sources_.erase(it);
      } else {
        ++it;
      }
    }
  }

  void stream(const std::vector<float>& stereo) override {
    if (stereo.size() < 2) return;
    alcMakeContextCurrent(context_);
    if (stream_ == 0) {
      alGenSources(1, &stream_);
      alSourcei(stream_, AL_SOURCE_RELATIVE, AL_TRUE);
    }
    // Buffers the device has played are deleted; what is still queued bounds the latency.
    ALint processed = 0, queued = 0;
    alGetSourcei(stream_, AL_BUFFERS_PROCESSED, &processed);
    if (processed > 0) {
      std::vector<ALuint> done(static_cast<std::size_t>(processed));
      alSourceUnqueueBuffers(stream_, processed, done.data());
      alDeleteBuffers(processed, done.data());
      for (ALuint b : done) queuedFrames_.erase(b);
    }
    std::size_t ahead = 0;
    for (const auto& [b, frames] : queuedFrames_) ahead += frames;
    const std::size_t frames = stereo.size() / 2;
    if (ahead + frames > kGraphSampleRate / 4) return;  // the clock ran ahead: dropped
    std::vector<std::int16_t> pcm(2 * frames);
    for (std::size_t i = 0; i < pcm.size(); ++i)
      pcm[i] =
          static_cast<std::int16_t>(std::lround(std::clamp(stereo[i], -1.0f, 1.0f) * 32767.0f));
    ALuint b = 0;
    alGenBuffers(1, &b);
    alBufferData(b, AL_FORMAT_STEREO16, pcm.data(),
                 static_cast<ALsizei>(pcm.size() * sizeof(std::int16_t)), kGraphSampleRate);
    alSourceQueueBuffers(stream_, 1, &b);
    queuedFrames_[b] = frames;
    ALint state = AL_STOPPED;
    alGetSourcei(stream_, AL_SOURCE_STATE, &state);
    alGetSourcei(stream_, AL_BUFFERS_QUEUED, &queued);
    if (state != AL_PLAYING && queued > 0) alSourcePlay(stream_);
  }

  std::size_t capture(std::vector<float>& mono, std::size_t maxFrames, std::string& note) override {
    if (capture_ == nullptr && !captureTried_) {
      captureTried_ = true;
      // Half a second of ring buffer, mono 16-bit at the graph's rate.
      capture_ =
          alcCaptureOpenDevice(nullptr, kGraphSampleRate, AL_FORMAT_MONO16, kGraphSampleRate / 2);
      if (capture_ == nullptr)
        note = "no capture device (OpenAL Soft opened none): MicrophoneSource is silent";
      else
        alcCaptureStart(capture_);
    }
    if (capture_ == nullptr) return 0;
    ALCint available = 0;
    alcGetIntegerv(capture_, ALC_CAPTURE_SAMPLES, 1, &available);
    const auto frames =
        std::min<std::size_t>(static_cast<std::size_t>(std::max(available, 0)), maxFrames);
    if (frames == 0) return 0;
    std::vector<std::int16_t> pcm(frames);
    alcCaptureSamples(capture_, pcm.data(), static_cast<ALCsizei>(frames));
    for (std::int16_t v : pcm) mono.push_back(static_cast<float>(v) / 32768.0f);
    return frames;
  }

 private:
  struct Source {
    ALuint id = 0;
    const formats::AudioData* clip = nullptr;
  };
  ALuint bufferOf(const formats::AudioData& clip) {
    ALuint& b = buffers_[&clip];
    if (b == 0) {
      alGenBuffers(1, &b);
      alBufferData(
          b, clip.channels == 2 ? AL_FORMAT_STEREO16 : AL_FORMAT_MONO16, clip.samples.data(),
          static_cast<ALsizei>(clip.samples.size() * sizeof(std::int16_t)), clip.sampleRate);
    }
    return b;
  }

  ALCdevice* device_;
  ALCcontext* context_;
  std::string name_;
  std::unordered_map<const void*, Source> sources_;
  std::unordered_map<const formats::AudioData*, ALuint> buffers_;
  ALuint stream_ = 0;             // the audio graph's streaming source
  ALCdevice* capture_ = nullptr;  // the microphone, opened by the first capture()
  bool captureTried_ = false;
  std::unordered_map<ALuint, std::size_t> queuedFrames_;
};

// While the device opens, stderr points at /dev/null: OpenAL Soft and ALSA print every
// backend they try (about ten lines on a machine without a sound card), and the caller's
// one-line note already says what matters (issue 42, friction 5).
class QuietStderr {
 public:
  QuietStderr() {
    std::fflush(stderr);
    saved_ = ::dup(2);
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (saved_ >= 0 && null >= 0) ::dup2(null, 2);
    if (null >= 0) ::close(null);
  }
  ~QuietStderr() {
    std::fflush(stderr);
    if (saved_ >= 0) {
      ::dup2(saved_, 2);
      ::close(saved_);
    }
  }
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;

 private:
  int saved_ = -1;
};

}  // namespace

std::unique_ptr<AudioOutput> openAudioOutput(bool wanted, std::string& note) {
  if (!wanted) {
    note = "sound is off";
    return std::make_unique<NullAudioOutput>();
  }
  ALCdevice* device = nullptr;
  ALCcontext* context = nullptr;
  {
    const QuietStderr quiet;
    device = alcOpenDevice(nullptr);
    if (device != nullptr) context = alcCreateContext(device, nullptr);
  }
  if (device == nullptr) {
    note = "no audio device: sound is not played";
    return std::make_unique<NullAudioOutput>();
  }
  if (context == nullptr) {
    alcCloseDevice(device);
    note = "the audio device has no context: sound is not played";
    return std::make_unique<NullAudioOutput>();
  }
  return std::make_unique<OpenAlOutput>(device, context);
}

}  // namespace gs::audio
