// MovieTexture (ISO/IEC 14772-1:1997 6.28): a formats::MoviePlayer per node, shared through
// render::MoviePlayers by the renderers of the same world, decodes on its own thread (rows
// bottom first, as GL wants them); each draw picks the frame for the node's media time
// (the execution model's MediaClock) and, when it is newer than the one in this
// renderer's texture, copies it there. The drawing thread never decodes, never flips rows
// and, in the window, never waits (docs/media.md).
#include "base/file.hpp"
#include "base/url.hpp"
#include "gpu_resources.hpp"
#include "node_access.hpp"

#include <memory>
#include <utility>

namespace gs::render::detail {

namespace {

/// The movie's bytes: a local file, or the loader's (pending while they arrive).
LoadStatus readMovie(const vrml::Node& node, const std::string& baseUrl,
                     const ResourceLoader& loader, std::string& url, std::string& bytes,
                     std::string& failures) {
  for (const std::string& reference : mfString(node, "url")) {
    if (reference.empty()) continue;
    url = base::resolveUrl(baseUrl, reference);
    std::string error;
    if (!base::mayReference(baseUrl, url, error)) {
      failures += (failures.empty() ? "" : "; ") + url + ": " + error;
      continue;
    }
    const std::string path = base::localPathOfUrl(url);
    if (!path.empty() && base::readFile(path, bytes, error)) return LoadStatus::loaded;
    if (loader) {
      const LoadStatus status = loader(url, bytes, error);
      if (status != LoadStatus::failed) return status;
    } else if (path.empty()) {
      error = "only local files can be read without a network loader";
    }
    failures += (failures.empty() ? "" : "; ") + url + ": " + error;
  }
  return LoadStatus::failed;
}

/// The url field resolved against `baseUrl`, one line each: with the node, the key of its
/// player in MoviePlayers.
std::string playerKey(const vrml::Node& node, const std::string& baseUrl) {
  std::string key;
  for (const std::string& reference : mfString(node, "url"))
    if (!reference.empty()) key += base::resolveUrl(baseUrl, reference) + '\n';
  return key;
}

}  // namespace

void MovieTextures::setPlayers(std::shared_ptr<MoviePlayers> players) {
  players_ = std::move(players);
}

const GpuTexture& MovieTextures::get(const vrml::Node& node, const std::string& baseUrl,
                                     SceneTraversal& traversal, const ResourceLoader& loader) {
  Movie& m = movies_[&node];
  if (m.failed) return m.texture;
  if (!m.player) {
    if (!players_) players_ = std::make_shared<MoviePlayers>();
    // Another renderer of this world may play the movie already: no second read or decoder.
    const std::string key = playerKey(node, baseUrl);
    m.player = players_->find(node, key);
  }
  if (!m.player) {
    std::string url, bytes, failures;
    const LoadStatus status = readMovie(node, baseUrl, loader, url, bytes, failures);
    if (status == LoadStatus::pending) return m.texture;  // untextured until the bytes arrive
    if (status == LoadStatus::failed) {
      m.failed = true;
      durations_.emplace_back(&node, -1.0);
      traversal.report(vrml::Severity::warning, node.location,
                       failures.empty()
                           ? std::string("MovieTexture has no url: drawn untextured")
                           : "cannot load MovieTexture (" + failures + "): drawn untextured");
      return m.texture;
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
    if (!m.durationTaken) durations_.emplace_back(&node, -1.0);
    traversal.report(vrml::Severity::warning, node.location,
                     "cannot play MovieTexture (" + error + "): drawn untextured");
    return m.texture;
  }
  if (status != formats::MoviePlayer::Status::ready) return m.texture;
  if (!m.durationTaken) {
    m.durationTaken = true;
    durations_.emplace_back(&node, player.duration());
  }
  std::optional<double> t = clock_ ? clock_(node) : std::nullopt;
  const double at = t.value_or(0.0);
  const std::shared_ptr<const formats::VideoFrame> frame =
      wait_ ? player.waitFrameFor(at) : player.frameFor(at);
  if (!frame || frame->index == m.shown) return m.texture;
  // The player decodes rows bottom first (MoviePlayers): VRML's (0, 0) is the image's
  // lower-left corner, GL's first row the bottom one.
  const std::uint8_t* pixels = frame->rgba.data();
  if (m.texture.id == 0 || m.width != frame->width || m.height != frame->height) {
    if (m.texture.id == 0) glGenTextures(1, &m.texture.id);
    glBindTexture(GL_TEXTURE_2D, m.texture.id);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, frame->width, frame->height, 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, pixels);
    const bool repeatS = sfBool(node, "repeatS", true), repeatT = sfBool(node, "repeatT", true);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, repeatS ? GL_REPEAT : GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, repeatT ? GL_REPEAT : GL_CLAMP_TO_EDGE);
    m.width = frame->width;
    m.height = frame->height;
    m.texture.components = 3;  // 6.28: movies are RGB
    m.texture.hasAlpha = false;
  } else {
    glBindTexture(GL_TEXTURE_2D, m.texture.id);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, frame->width, frame->height, GL_RGBA, GL_UNSIGNED_BYTE,
                    pixels);
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  m.shown = frame->index;
  ++uploads_;
  return m.texture;
}

void MovieTextures::setClock(MediaClock clock, bool waitForFrames) {
  clock_ = std::move(clock);
  wait_ = waitForFrames;
  if (!wait_) return;
  for (auto& [node, m] : movies_)
    if (m.player && !m.durationTaken &&
        m.player->waitOpened() == formats::MoviePlayer::Status::ready) {
      m.durationTaken = true;
      durations_.emplace_back(node, m.player->duration());
    }
}

std::vector<std::pair<const vrml::Node*, double>> MovieTextures::takeDurations() {
  std::vector<std::pair<const vrml::Node*, double>> out;
  out.swap(durations_);
  return out;
}

void MovieTextures::release() {
  for (auto& [node, m] : movies_)
    if (m.texture.id != 0) glDeleteTextures(1, &m.texture.id);
  movies_.clear();
}

}  // namespace gs::render::detail
