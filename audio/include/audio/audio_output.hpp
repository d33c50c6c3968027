// Where sound goes: OpenAL Soft's default device, or the null output when there is none
// (headless machines, CI): a missing device is a note, never an error (docs/media.md).
#pragma once

#include "formats/audio.hpp"

#include <glm/vec3.hpp>

#include <memory>
#include <string>
#include <vector>

namespace gs::audio {

/// One sound to play now (SoundScene::update makes them each frame).
struct Voice {
  const void* key = nullptr;  // identity of the Sound node: the same voice across frames
  std::shared_ptr<const formats::AudioData> clip;
  double offset = 0.0;  // seconds into the clip that should be heard now
  float gain = 1.0f;    // linear amplitude factor, 0..1 (audio/sound_model.hpp)
  float pitch = 1.0f;   // AudioClip.pitch, > 0
  bool loop = false;    // AudioClip.loop
  bool spatialize = true;
  /// Where the sound is, in the listener's coordinates (x right, y up, -z ahead; metres).
  glm::vec3 position{0.0f};
};

class AudioOutput {
 public:
  virtual ~AudioOutput() = default;
  /// True for the null output (nothing is heard).
  virtual bool isNull() const = 0;
  /// "OpenAL Soft: <device>" or "null".
  virtual std::string name() const = 0;
  /// From now on exactly `voices` play (called once a frame): new keys start at their
  /// offset, known ones follow their gain, pitch and position (and are moved when their
  /// offset drifted by more than a tenth of a second), missing ones stop.
  virtual void update(const std::vector<Voice>& voices) = 0;
  /// How many voices can play at once.
  virtual std::size_t maxVoices() const = 0;
  /// Queues `stereo` (interleaved left, right; kGraphSampleRate frames per second, -1..1,
  /// clipped beyond) after what was queued before: the X3D 4 audio graph's output
  /// (audio/audio_graph.hpp), rendered as simulated time passes. Sound queued more than a
  /// quarter of a second ahead of the device is dropped (the graph's clock leads).
  virtual void stream(const std::vector<float>& stereo) = 0;
  /// Appends to `mono` what the capture device (the default microphone) recorded since the
  /// last call, at most `maxFrames` frames (mono, -1..1, kGraphSampleRate frames per second),
  /// opening the device on the first call: MicrophoneSource's sound. Returns the frames
  /// appended; 0 when there is no capture device (then `note` says why, once).
  virtual std::size_t capture(std::vector<float>& mono, std::size_t maxFrames,
                              std::string& note) = 0;
};

/// The null output: plays nothing, remembers what it was asked to play.
class NullAudioOutput final : public AudioOutput {
 public:
  bool isNull() const override { return true; }
  std::string name() const override { return "null"; }
  void update(const std::vector<Voice>& voices) override { playing_ = voices; }
  std::size_t maxVoices() const override { return 32; }
  void stream(const std::vector<float>& stereo) override {
    streamed_.insert(streamed_.end(), stereo.begin(), stereo.end());
  }
  std::size_t capture(std::vector<float>&, std::size_t, std::string& note) override {
    if (!noted_) note = "no capture device (null audio output): MicrophoneSource is silent";
    noted_ = true;
    return 0;
  }
  /// The voices of the last update.
  const std::vector<Voice>& playing() const { return playing_; }
  /// Every frame streamed so far (interleaved stereo).
  const std::vector<float>& streamed() const { return streamed_; }
  /// Forgets the frames streamed so far (a test's window on the stream).
  void clearStreamed() { streamed_.clear(); }

 private:
  std::vector<Voice> playing_;
  std::vector<float> streamed_;
  bool noted_ = false;
};

/// OpenAL Soft's default device; the null output when `wanted` is false or no device
/// opens (then `note` says why). Never throws.
std::unique_ptr<AudioOutput> openAudioOutput(bool wanted, std::string& note);

}  // namespace gs::audio
