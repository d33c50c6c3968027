// MovieTexture (ISO/IEC 14772-1:1997 6.28): a formats::MoviePlayer per node, shared with its
// GL texture through render::MoviePlayers by the renderers of the same world, decodes on
// its own thread (rows bottom first, as GL wants them); each draw picks the frame for the
// node's media time (the execution model's MediaClock) and, when the texture holds another
// frame, copies it there (the first viewport of a world to draw a frame does). The drawing thread
// never decodes, never flips rows and, in the window, never waits (docs/media.md).
#include "base/url.hpp"
#include "gpu_resources.hpp"
#include "scene/node_access.hpp"

#include <memory>
#include <utility>

namespace gs::render::detail {

namespace {

/// The movie's bytes: the first url the fetcher reads (pending while it arrives); failed
/// with every url's reason in `failures` when none can be read.
base::FetchState readMovie(const vrml::Node& node, const std::string& baseUrl,
                           base::Fetcher* fetcher, std::string& url, std::string& bytes,
                           std::string& failures) {
  for (const std::string& reference : scene::mfString(node, "url")) {
    if (reference.empty()) continue;
    url = base::resolveUrl(baseUrl, reference);
    base::Fetched got = base::fetcherOr(fetcher).fetch(url, baseUrl, base::FetchMode::background);
    if (got.ready()) bytes = std::move(got.bytes);
    if (got.ready() || got.pending()) return got.state;
    failures += (failures.empty() ? "" : "; ") + got.error;
  }
  return base::FetchState::failed;
}

/// The url field resolved against `baseUrl`, one line each: with the node, the key of its
/// player in MoviePlayers.
std::string playerKey(const vrml::Node& node, const std::string& baseUrl) {
  std::string key;
  for (const std::string& reference : scene::mfString(node, "url"))
    if (!reference.empty()) key += base::resolveUrl(baseUrl, reference) + '\n';
  return key;
}

}  // namespace

void MovieTextures::setPlayers(std::shared_ptr<MoviePlayers> players) {
  players_ = std::move(players);
}

MovieGlTexture::~MovieGlTexture() {
  if (texture.id != 0 && glad_glDeleteTextures != nullptr) glDeleteTextures(1, &texture.id);
}

const GpuTexture& MovieTextures::get(const vrml::Node& node, const std::string& baseUrl,
                                     scene::SceneTraversal& traversal, base::Fetcher* fetcher) {
  static const GpuTexture kNone;  // untextured
  Movie& m = movies_[&node];
  if (m.failed) return kNone;
  if (!m.player) {
    if (!players_) players_ = std::make_shared<MoviePlayers>();
    // Another renderer of this world may play the movie already: no second read or decoder.
    m.player = players_->find(node, playerKey(node, baseUrl));
  }
  if (!m.player) {
    std::string url, bytes, failures;
    const base::FetchState status = readMovie(node, baseUrl, fetcher, url, bytes, failures);
    if (status == base::FetchState::pending) return kNone;  // untextured until they arrive
    if (status != base::FetchState::ready) {
      m.failed = true;
      durations_.emplace_back(&node, -1.0);
      traversal.report(vrml::Severity::warning, node.location,
                       failures.empty()
                           ? std::string("MovieTexture has no url: drawn untextured")
                           : "cannot load MovieTexture (" + failures + "): drawn untextured");
      return kNone;
    }
    m.player = players_->open(node, playerKey(node, baseUrl), std::move(bytes), url);
  }
  formats::MoviePlayer& player = *m.player;
  // --snapshot waits for the movie to open, so its duration is known at once.
  const formats::MoviePlayer::Status status = wait_ ? player.waitOpened() : player.status();
  if (status == formats::MoviePlayer::Status::failed) {
    m.failed = true;
    const std::string error = player.error();
    m.player.reset();  // `player` is gone from here on
    m.gl.reset();
    if (!m.durationTaken) durations_.emplace_back(&node, -1.0);
    traversal.report(vrml::Severity::warning, node.location,
                     "cannot play MovieTexture (" + error + "): drawn untextured");
    return kNone;
  }
  if (status != formats::MoviePlayer::Status::ready) return kNone;
  if (!m.durationTaken) {
    m.durationTaken = true;
    durations_.emplace_back(&node, player.duration());
  }
  if (!m.gl)
    m.gl = players_->texture(node, playerKey(node, baseUrl),
                             [] { return std::make_shared<MovieGlTexture>(); });
  MovieGlTexture& gl = *m.gl;
  std::optional<double> t = clock_ ? clock_(node) : std::nullopt;
  const double at = t.value_or(0.0);
  const std::shared_ptr<const formats::VideoFrame> frame =
      wait_ ? player.waitFrameFor(at) : player.frameFor(at);
  if (!frame) return gl.texture;
  if (frame->index != m.seen) {
    m.seen = frame->index;
    ++shown_;
  }
  // Another renderer of the world (the same clock) may have copied this frame already.
  if (frame->index == gl.frame) return gl.texture;
  // The player decodes rows bottom first (MoviePlayers): VRML's (0, 0) is the image's
  // lower-left corner, GL's first row the bottom one.
  const std::uint8_t* pixels = frame->rgba.data();
  if (gl.texture.id == 0 || gl.width != frame->width || gl.height != frame->height) {
    if (gl.texture.id == 0) glGenTextures(1, &gl.texture.id);
    glBindTexture(GL_TEXTURE_2D, gl.texture.id);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, frame->width, frame->height, 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, pixels);
    const bool repeatS = scene::sfBool(node, "repeatS", true),
               repeatT = scene::sfBool(node, "repeatT", true);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, repeatS ? GL_REPEAT : GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, repeatT ? GL_REPEAT : GL_CLAMP_TO_EDGE);
    gl.width = frame->width;
    gl.height = frame->height;
  } else {
    glBindTexture(GL_TEXTURE_2D, gl.texture.id);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, frame->width, frame->height, GL_RGBA, GL_UNSIGNED_BYTE,
                    pixels);
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  // VRML97 6.28's movies are RGB; a frame with transparent pixels (an animated GIF's
  // transparent colour, a video with alpha) is RGBA, as X3D 4 browsers draw it.
  gl.texture.components = frame->translucent ? 4 : 3;
  gl.texture.hasAlpha = frame->translucent;
  gl.frame = frame->index;
  ++uploads_;
  return gl.texture;
}

void MovieTextures::setClock(MediaClock clock, bool waitForFrames) {
  clock_ = std::move(clock);
  wait_ = waitForFrames;
  if (!wait_) return;
  for (auto& [node, m] : movies_)
    if (m.player && !m.durationTaken &&
        m.player->waitOpened() == formats::MoviePlayer::Status::ready) {
      m.durationTaken = true;
      durations_.emplace_back(node.node, m.player->duration());
    }
}

std::vector<std::pair<const vrml::Node*, double>> MovieTextures::takeDurations() {
  std::vector<std::pair<const vrml::Node*, double>> out;
  out.swap(durations_);
  return out;
}

void MovieTextures::release() {
  movies_.clear();  // the last renderer holding a movie's texture deletes it
}

}  // namespace gs::render::detail
