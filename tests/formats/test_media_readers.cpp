// formats/movie.hpp and formats/audio.hpp on the clips under assets/media (docs/media.md):
// colours.mpg is MPEG-1, 16 x 16, 24 frames at 24 fps: red, green, blue, white for 6
// frames each; tone.wav is 0.5 s of 440 Hz, 8 kHz mono 16-bit.
#include "base/file.hpp"
#include "formats/audio.hpp"
#include "formats/movie.hpp"

#include <catch2/catch.hpp>

#include <array>

using namespace gs::formats;

namespace {

std::string asset(const std::string& name) {
  std::string bytes, error;
  REQUIRE(gs::base::readFile(std::string(GS_SOURCE_DIR) + "/assets/media/" + name, bytes, error));
  return bytes;
}

/// The colour of a frame's centre pixel, each channel rounded to 0 or 255.
std::array<int, 3> colourOf(const VideoFrame& f) {
  const std::size_t i = (static_cast<std::size_t>(f.height / 2) * f.width + f.width / 2) * 4;
  return {f.rgba[i] > 127 ? 255 : 0, f.rgba[i + 1] > 127 ? 255 : 0, f.rgba[i + 2] > 127 ? 255 : 0};
}

constexpr std::array<int, 3> kRed{255, 0, 0}, kGreen{0, 255, 0}, kBlue{0, 0, 255},
    kWhite{255, 255, 255};

}  // namespace

TEST_CASE("MovieDecoder: the MPEG-1 clip's size, frame count and duration", "[formats][movie]") {
  std::string error;
  auto movie = MovieDecoder::open(asset("colours.mpg"), "colours.mpg", error);
  REQUIRE(movie);
  CHECK(movie->width() == 16);
  CHECK(movie->height() == 16);
  CHECK(movie->frameCount() == 24);
  CHECK(movie->frameDuration() == Approx(1.0 / 24.0));
  CHECK(movie->duration() == Approx(1.0));
  CHECK(movie->frameIndexAt(0.0) == 0);
  CHECK(movie->frameIndexAt(0.26) == 6);
  CHECK(movie->frameIndexAt(5.0) == 23);  // clamped to the last frame
}

TEST_CASE("MovieDecoder: a GIF's transparent colour comes as alpha 0, an MPEG's frames opaque",
          "[formats][movie]") {
  // stripes.gif (assets/worlds/media/make_images.py): 32 x 32, columns x with (x / 4) odd
  // are palette index 0, the transparent one; the others magenta (top) or black.
  std::string bytes, error;
  REQUIRE(gs::base::readFile(std::string(GS_SOURCE_DIR) + "/assets/worlds/media/stripes.gif", bytes,
                             error));
  auto gif = MovieDecoder::open(std::move(bytes), "stripes.gif", error);
  REQUIRE(gif);
  VideoFrame f;
  REQUIRE(gif->decodeFrame(0, f, error));
  REQUIRE(f.width == 32);
  CHECK(f.translucent);
  const auto alphaAt = [&](int x, int y) {
    const int row = f.bottomRowFirst ? f.height - 1 - y : y;
    return int(f.rgba[(static_cast<std::size_t>(row) * 32 + static_cast<std::size_t>(x)) * 4 + 3]);
  };
  CHECK(alphaAt(5, 4) == 0);     // a transparent column
  CHECK(alphaAt(1, 4) == 255);   // magenta
  CHECK(alphaAt(1, 28) == 255);  // black
  auto mpeg = MovieDecoder::open(asset("colours.mpg"), "colours.mpg", error);
  REQUIRE(mpeg);
  REQUIRE(mpeg->decodeFrame(0, f, error));
  CHECK_FALSE(f.translucent);
}

TEST_CASE("MovieDecoder: the frame at time t, forwards and after a rewind", "[formats][movie]") {
  std::string error;
  auto movie = MovieDecoder::open(asset("colours.mpg"), "colours.mpg", error);
  REQUIRE(movie);
  VideoFrame f;
  const std::pair<double, std::array<int, 3>> expected[] = {
      {0.1, kRed}, {0.3, kGreen},  {0.6, kBlue}, {0.9, kWhite},
      {0.2, kRed}, {0.99, kWhite}, {0.5, kBlue}};
  for (const auto& [t, colour] : expected) {
    INFO("t = " << t);
    REQUIRE(movie->decodeFrame(movie->frameIndexAt(t), f, error));
    CHECK(f.index == movie->frameIndexAt(t));
    CHECK(f.width == 16);
    CHECK(f.rgba.size() == 16u * 16u * 4u);
    CHECK(colourOf(f) == colour);
  }
}

TEST_CASE("MovieDecoder: bad movies are errors naming the file", "[formats][movie]") {
  std::string error;
  CHECK_FALSE(MovieDecoder::open("this is not a movie", "bad.mpg", error));
  CHECK(error.find("bad.mpg") != std::string::npos);
  // Truncated inside the first picture: no frame, or fewer frames, never a crash.
  const std::string clip = asset("colours.mpg");
  for (std::size_t n : {std::size_t{0}, std::size_t{20}, std::size_t{100}, clip.size() / 2}) {
    error.clear();
    auto movie = MovieDecoder::open(clip.substr(0, n), "cut.mpg", error);
    if (!movie) {
      CHECK(error.find("cut.mpg") != std::string::npos);
      continue;
    }
    VideoFrame f;
    if (!movie->decodeFrame(movie->frameCount() - 1, f, error))
      CHECK(error.find("cut.mpg") != std::string::npos);
  }
  // Over the size limit.
  MovieLimits tiny;
  tiny.maxSide = 8;
  CHECK_FALSE(MovieDecoder::open(clip, "big.mpg", error, tiny));
  CHECK(error.find("16 x 16") != std::string::npos);
}

TEST_CASE("MoviePlayer: frames come from the worker thread", "[formats][movie]") {
  MoviePlayer player([clip = asset("colours.mpg")](std::string& error) {
    return MovieDecoder::open(clip, "colours.mpg", error);
  });
  auto f = player.waitFrameFor(0.6);
  REQUIRE(f);
  CHECK(player.status() == MoviePlayer::Status::ready);
  CHECK(player.duration() == Approx(1.0));
  CHECK(f->index == 14);
  CHECK(colourOf(*f) == kBlue);
  f = player.waitFrameFor(0.05);  // backwards: a rewind
  REQUIRE(f);
  CHECK(colourOf(*f) == kRed);
  // frameFor never waits: it gives a frame at or before the one asked for.
  const auto now = player.frameFor(0.95);
  REQUIRE(now);
  CHECK(now->index <= 22);
  MoviePlayer bad([](std::string& error) { return MovieDecoder::open("junk", "junk.mpg", error); });
  CHECK_FALSE(bad.waitFrameFor(0.0));
  CHECK(bad.status() == MoviePlayer::Status::failed);
  CHECK(bad.error().find("junk.mpg") != std::string::npos);
}

TEST_CASE("readAudio: a WAV clip and bad sound files", "[formats][audio]") {
  AudioData a;
  std::string error;
  REQUIRE(readAudio(asset("tone.wav"), "tone.wav", a, error));
  CHECK(a.sampleRate == 8000);
  CHECK(a.channels == 1);
  CHECK(a.duration() == Approx(0.5));
  int peak = 0;
  for (std::int16_t s : a.samples) peak = std::max(peak, static_cast<int>(s < 0 ? -s : s));
  CHECK(peak > 3000);  // a real tone (ffmpeg's sine source peaks at 1/8 of full scale)
  CHECK_FALSE(readAudio("RIFF0000WAVEjunk", "bad.wav", a, error));
  CHECK(error.find("bad.wav") != std::string::npos);
  const std::string wav = asset("tone.wav");
  AudioData cut;
  // A WAV cut short keeps the samples it has (or is an error): never a crash.
  if (readAudio(wav.substr(0, 1000), "cut.wav", cut, error)) {
    CHECK(cut.duration() < 0.5);
  } else {
    CHECK(error.find("cut.wav") != std::string::npos);
  }
}
