// MovieTexture players shared by the renderers that show one world (ISO/IEC 14772-1:1997
// 6.28; docs/media.md, "Threading"): one formats::MoviePlayer, so one decoder thread, per
// MovieTexture node and url, however many viewports draw the node. Each renderer keeps its
// own GL texture and copies a frame into it only when the player has a newer one for the
// node's media time; viewports of one world share that world's clock, so they ask for the
// same frame. Thread-safe.
#pragma once

#include "formats/movie.hpp"

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

namespace gs::vrml {
class Node;
}

namespace gs::render {

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

  /// Players made since this registry was made (each one decoder thread).
  std::uint64_t playersOpened() const;
  /// Players alive now.
  std::size_t playing() const;
  /// Pictures decoded so far by the players alive now (formats::MoviePlayer::framesDecoded).
  std::uint64_t framesDecoded() const;

 private:
  using Key = std::pair<const vrml::Node*, std::string>;
  mutable std::mutex mutex_;
  std::map<Key, std::weak_ptr<formats::MoviePlayer>> players_;
  std::uint64_t opened_ = 0;
};

}  // namespace gs::render
