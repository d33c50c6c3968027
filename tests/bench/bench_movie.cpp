// MovieTexture decoding throughput (docs/media.md): decodes every frame of a movie with
// formats::MovieDecoder (RGBA conversion included) on one thread and prints frames per
// second against the movie's own rate, and the time readMovieAudio takes to decode its
// whole audio stream (a Sound whose source is the MovieTexture). Usage: bench_movie MOVIE
#include "base/file.hpp"
#include "formats/movie.hpp"
#include "formats/movie_audio.hpp"

#include <chrono>
#include <cstdio>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_movie MOVIE\n");
    return 2;
  }
  std::string bytes, error;
  if (!gs::base::readFile(argv[1], bytes, error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const std::string file = bytes;
  auto movie = gs::formats::MovieDecoder::open(std::move(bytes), argv[1], error);
  if (!movie) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  const auto t1 = std::chrono::steady_clock::now();
  gs::formats::VideoFrame frame;
  for (std::int64_t i = 0; i < movie->frameCount(); ++i)
    if (!movie->decodeFrame(i, frame, error)) {
      std::fprintf(stderr, "%s\n", error.c_str());
      return 1;
    }
  const auto t2 = std::chrono::steady_clock::now();
  const double open = std::chrono::duration<double>(t1 - t0).count();
  const double decode = std::chrono::duration<double>(t2 - t1).count();
  std::printf("%s: %d x %d, %lld frames, %.3f s at %.2f fps\n", argv[1], movie->width(),
              movie->height(), static_cast<long long>(movie->frameCount()), movie->duration(),
              1.0 / movie->frameDuration());
  std::printf("open (frame count) %.1f ms; decode + RGBA %.0f frames/s (%.1fx real time)\n",
              open * 1e3, static_cast<double>(movie->frameCount()) / decode,
              movie->duration() / decode);
  gs::formats::MovieAudio sound;
  const auto t3 = std::chrono::steady_clock::now();
  if (gs::formats::readMovieAudio(file, argv[1], sound, error)) {
    const double audio =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t3).count();
    std::printf(
        "audio: %.3f s, %d Hz, %d channel(s), decoded whole in %.1f ms (frame count included)\n",
        sound.audio.duration(), sound.audio.sampleRate, sound.audio.channels, audio * 1e3);
  } else {
    std::printf("audio: %s\n", error.c_str());
  }
  return 0;
}
