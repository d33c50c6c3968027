// MovieTexture decoding throughput (docs/media.md): decodes every frame of a movie with
// formats::MovieDecoder (RGBA conversion included) on one thread and prints frames per
// second against the movie's own rate. Usage: bench_movie MOVIE
#include "base/file.hpp"
#include "formats/movie.hpp"

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
  return 0;
}
