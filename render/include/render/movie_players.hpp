// MovieTexture players shared by the renderers that show one world (ISO/IEC 14772-1:1997
// 6.28; docs/media.md, "Threading"): one formats::MoviePlayer, so one decoder thread, per
// MovieTexture node and url, however many viewports draw the node, and one GL texture of
// it, into which the first renderer that draws a new frame copies it; viewports of one
// world share that world's clock, so they ask for the same frame. The renderers given one
// registry must draw in one GL context (or contexts that share objects), as the window's
// viewports and --snapshot's do. Thread-safe.
#pragma once

#include "formats/movie.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

namespace gs::vrml {
class Node;
}

namespace gs::render {

namespace detail {
struct MovieGlTexture;  // render/src/gpu_resources.hpp
}

class MoviePlayers {
 public:
  MoviePlayers() = default;
  MoviePlayers(const MoviePlayers&) = delete;
  MoviePlayers& operator=(const MoviePlayers&) = delete;

  /// The player of MovieTexture `node` for the url list `key` (its url field resolved, as
  /// one string) while some renderer still holds it; null otherwise.
  std::shared_ptr<formats::MoviePlayer> find(const vrml::Node& node, const std::string& key);
  /// The player of (`node`, `key`): the one playing already, else a new one that opens
  /// `bytes` (the movie file read from `url`, which names it in errors) on its worker
  /// thread with rows bottom first, as glTexImage2D wants them. A player lives as long as
  /// a renderer holds it.
  std::shared_ptr<formats::MoviePlayer> open(const vrml::Node& node, const std::string& key,
                                             std::string bytes, const std::string& url);
  /// The GL texture of (`node`, `key`) while some renderer holds it, else `make()`'s (kept
  /// as long as a renderer holds it). For render/ only: the renderers must share GL objects.
  std::shared_ptr<detail::MovieGlTexture> texture(
      const vrml::Node& node, const std::string& key,
      const std::function<std::shared_ptr<detail::MovieGlTexture>()>& make);

  /// Players made since this registry was made (each one decoder thread).
  std::uint64_t playersOpened() const;
  /// Players alive now.
  std::size_t playing() const;
  /// Pictures decoded so far by the players alive now (formats::MoviePlayer::framesDecoded).
  std::uint64_t framesDecoded() const;

 private:
  using Key = std::pair<const vrml::Node*, std::string>;
  mutable std::mutex mutex_;
  struct Entry {
    std::weak_ptr<formats::MoviePlayer> player;
    std::weak_ptr<detail::MovieGlTexture> texture;
  };
  std::map<Key, Entry> players_;
  std::uint64_t opened_ = 0;
};

}  // namespace gs::render
