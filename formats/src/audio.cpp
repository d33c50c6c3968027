// readAudio over libsndfile's virtual I/O (the bytes stay in memory). 6.3.
#include "formats/audio.hpp"

#include <sndfile.h>

#include <algorithm>
#include <cstring>

namespace gs::formats {

namespace {

struct Memory {
  const std::string* bytes;
  sf_count_t position = 0;
};

sf_count_t length(void* user) {
  return static_cast<sf_count_t>(static_cast<Memory*>(user)->bytes->size());
}

sf_count_t seek(sf_count_t offset, int whence, void* user) {
  auto* m = static_cast<Memory*>(user);
  const auto size = static_cast<sf_count_t>(m->bytes->size());
  sf_count_t to = offset;
  if (whence == SEEK_CUR) to += m->position;
  if (whence == SEEK_END) to += size;
  m->position = std::clamp<sf_count_t>(to, 0, size);
  return m->position;
}

sf_count_t read(void* buffer, sf_count_t count, void* user) {
  auto* m = static_cast<Memory*>(user);
  const auto size = static_cast<sf_count_t>(m->bytes->size());
  const sf_count_t n = std::clamp<sf_count_t>(count, 0, size - m->position);
  std::memcpy(buffer, m->bytes->data() + m->position, static_cast<std::size_t>(n));
  m->position += n;
  return n;
}

sf_count_t write(const void*, sf_count_t, void*) {
  return 0;
}

sf_count_t tell(void* user) {
  return static_cast<Memory*>(user)->position;
}

}  // namespace

bool readAudio(const std::string& bytes, const std::string& name, AudioData& out,
               std::string& error) {
  SF_VIRTUAL_IO io{length, seek, read, write, tell};
  Memory memory{&bytes};
  SF_INFO info{};
  SNDFILE* file = sf_open_virtual(&io, SFM_READ, &info, &memory);
  if (file == nullptr) {
    error = name + ": not a sound libsndfile reads (" + sf_strerror(nullptr) + ")";
    return false;
  }
  const auto fail = [&](const std::string& why) {
    sf_close(file);
    error = name + ": " + why;
    return false;
  };
  if (info.channels < 1 || info.channels > 2)
    return fail(std::to_string(info.channels) + " channels (1 or 2 are played)");
  if (info.samplerate <= 0 || info.samplerate > 384000) return fail("bad sample rate");
  if (info.frames <= 0) return fail("no sound in the file");
  if (static_cast<double>(info.frames) / info.samplerate > kMaxAudioSeconds)
    return fail("longer than " + std::to_string(static_cast<int>(kMaxAudioSeconds)) + " s");
  out.sampleRate = info.samplerate;
  out.channels = info.channels;
  out.samples.assign(
      static_cast<std::size_t>(info.frames) * static_cast<std::size_t>(info.channels), 0);
  const sf_count_t got = sf_readf_short(file, out.samples.data(), info.frames);
  sf_close(file);
  if (got <= 0) {
    error = name + ": the sound data cannot be decoded";
    return false;
  }
  // A truncated file gives fewer frames than its header says: keep those.
  out.samples.resize(static_cast<std::size_t>(got) * static_cast<std::size_t>(info.channels));
  return true;
}

}  // namespace gs::formats
