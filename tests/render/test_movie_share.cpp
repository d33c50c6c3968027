// MovieTexture players shared by the renderers of one world (docs/media.md, "Threading"):
// two renderers, as two viewports of the window, draw the same world at the same world
// time through one render::MoviePlayers; the movie is opened and decoded once, copied
// into one texture once per frame, and both show the frame of that time. colours.mpg: 16 x 16, 24
// frames at 24 fps, red, green, blue and white for 6 frames each.
#include "encodings/parser.hpp"
#include "render/context.hpp"
#include "render/image.hpp"
#include "render/movie_players.hpp"
#include "render/scene_renderer.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <memory>
#include <optional>
#include <string>

namespace {

constexpr int kSize = 32;

const char* const kWorld = R"(#VRML V2.0 utf8
Viewpoint { position 0 0 2 fieldOfView 1.5 }
Shape {
  appearance Appearance { texture MovieTexture { url "colours.mpg" loop TRUE } }
  geometry IndexedFaceSet {
    coord Coordinate { point [ -1 -1 0, 1 -1 0, 1 1 0, -1 1 0 ] }
    coordIndex [ 0 1 2 3 ]
    texCoord TextureCoordinate { point [ 0 0, 1 0, 1 1, 0 1 ] }
  }
}
)";

bool near(const std::uint8_t* p, int r, int g, int b) {
  INFO("pixel " << int(p[0]) << " " << int(p[1]) << " " << int(p[2]) << ", expected " << r << " "
                << g << " " << b);
  const auto ok = [](int a, int e) { return std::abs(a - e) <= 40; };
  return ok(p[0], r) && ok(p[1], g) && ok(p[2], b);
}

}  // namespace

TEST_CASE("MovieTexture: two viewports of one world decode its movie once",
          "[render][offscreen][media]") {
  auto context = gs::render::createOffscreenContext(2 * kSize, kSize);
  context->makeCurrent();
  // The world as if read from assets/media/, where colours.mpg lies.
  auto scene = std::make_shared<const gs::vrml::Scene>(
      gs::vrml::parseVrml(kWorld, std::string(GS_SOURCE_DIR) + "/assets/media/share.wrl"));
  auto players = std::make_shared<gs::render::MoviePlayers>();
  gs::render::SceneRendererOptions options;
  options.movies = players;
  gs::render::SceneRenderer left(scene, options), right(scene, options);
  double worldTime = 0.0;  // one world: one clock for both viewports
  const gs::render::MediaClock clock = [&](const gs::vrml::Node&) {
    return std::optional<double>(worldTime);
  };
  // Waiting for the frame of the time (as --snapshot does) makes the pixels certain.
  left.setMediaClock(clock, true);
  right.setMediaClock(clock, true);
  const auto drawBoth = [&] {
    left.draw(left.boundViewpointCamera(), 0, 0, kSize, kSize);
    right.draw(right.boundViewpointCamera(), kSize, 0, kSize, kSize);
    return gs::render::readPixels(0, 0, 2 * kSize, kSize);
  };

  worldTime = 0.3;  // frame 7 of 24: green
  gs::render::Image image = drawBoth();
  CHECK(players->playersOpened() == 1);
  CHECK(players->playing() == 1);
  CHECK(near(image.pixel(kSize / 2, kSize / 2), 0, 255, 0));
  CHECK(near(image.pixel(kSize + kSize / 2, kSize / 2), 0, 255, 0));
  // Frames 0..7 decoded once, plus at most the player's queue of 4 ahead; two decoders
  // would have decoded at least 16.
  CHECK(players->framesDecoded() >= 8);
  CHECK(players->framesDecoded() <= 12);
  // Both drew the new frame; one texture, so the first copied it and the second not.
  CHECK(left.statistics().movieFrames == 1);
  CHECK(right.statistics().movieFrames == 1);
  CHECK(left.statistics().movieUploads == 1);
  CHECK(right.statistics().movieUploads == 0);

  worldTime = 0.6;  // frame 14: blue
  image = drawBoth();
  CHECK(near(image.pixel(kSize / 2, kSize / 2), 0, 0, 255));
  CHECK(near(image.pixel(kSize + kSize / 2, kSize / 2), 0, 0, 255));
  CHECK(players->playersOpened() == 1);
  CHECK(players->framesDecoded() <= 19);
  CHECK(left.statistics().movieFrames == 2);
  CHECK(right.statistics().movieFrames == 2);
  CHECK(left.statistics().movieUploads == 2);
  CHECK(right.statistics().movieUploads == 0);
  // Both report the duration the execution model needs.
  const auto durations = left.takeMediaDurations();
  REQUIRE(durations.size() == 1);
  CHECK(durations[0].second == Approx(1.0));
}

TEST_CASE("MovieTexture: renderers without a shared registry each play their own",
          "[render][offscreen][media]") {
  auto context = gs::render::createOffscreenContext(kSize, kSize);
  context->makeCurrent();
  auto scene = std::make_shared<const gs::vrml::Scene>(
      gs::vrml::parseVrml(kWorld, std::string(GS_SOURCE_DIR) + "/assets/media/share.wrl"));
  auto a = std::make_shared<gs::render::MoviePlayers>();
  auto b = std::make_shared<gs::render::MoviePlayers>();
  gs::render::SceneRendererOptions oa, ob;
  oa.movies = a;
  ob.movies = b;
  gs::render::SceneRenderer first(scene, oa), second(scene, ob);
  const gs::render::MediaClock clock = [](const gs::vrml::Node&) {
    return std::optional<double>(0.9);  // frame 21: white
  };
  first.setMediaClock(clock, true);
  second.setMediaClock(clock, true);
  first.draw(first.boundViewpointCamera(), 0, 0, kSize, kSize);
  CHECK(
      near(gs::render::readPixels(0, 0, kSize, kSize).pixel(kSize / 2, kSize / 2), 255, 255, 255));
  second.draw(second.boundViewpointCamera(), 0, 0, kSize, kSize);
  CHECK(
      near(gs::render::readPixels(0, 0, kSize, kSize).pixel(kSize / 2, kSize / 2), 255, 255, 255));
  CHECK(a->playersOpened() == 1);
  CHECK(b->playersOpened() == 1);
  CHECK(a->framesDecoded() >= 22);
  CHECK(b->framesDecoded() >= 22);
  // Separate registries: separate textures, each copied by its renderer.
  CHECK(first.statistics().movieUploads == 1);
  CHECK(second.statistics().movieUploads == 1);
}
