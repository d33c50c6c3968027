// MoviePlayers: one formats::MoviePlayer per MovieTexture node and url, shared by the
// renderers of a world (docs/media.md, "Threading").
#include "render/movie_players.hpp"

namespace gs::render {

std::shared_ptr<formats::MoviePlayer> MoviePlayers::find(const vrml::Node& node,
                                                         const std::string& key) {
  std::lock_guard lock(mutex_);
  const auto it = players_.find(Key(&node, key));
  return it == players_.end() ? nullptr : it->second.player.lock();
}

std::shared_ptr<formats::MoviePlayer> MoviePlayers::open(const vrml::Node& node,
                                                         const std::string& key, std::string bytes,
                                                         const std::string& url) {
  std::lock_guard lock(mutex_);
  std::weak_ptr<formats::MoviePlayer>& slot = players_[Key(&node, key)].player;
  if (auto player = slot.lock()) return player;
  // Players no renderer holds any more go (their nodes may be gone, and their addresses
  // reused).
  std::erase_if(players_, [&](const auto& entry) {
    return &entry.second.player != &slot && entry.second.player.expired() &&
           entry.second.texture.expired();
  });
  auto player = std::make_shared<formats::MoviePlayer>(
      [bytes = std::move(bytes), url](std::string& error) mutable {
        auto decoder = formats::MovieDecoder::open(std::move(bytes), url, error);
        if (decoder) decoder->setBottomRowFirst(true);
        return decoder;
      });
  slot = player;
  ++opened_;
  return player;
}

std::shared_ptr<detail::MovieGlTexture> MoviePlayers::texture(
    const vrml::Node& node, const std::string& key,
    const std::function<std::shared_ptr<detail::MovieGlTexture>()>& make) {
  std::lock_guard lock(mutex_);
  std::weak_ptr<detail::MovieGlTexture>& slot = players_[Key(&node, key)].texture;
  if (auto texture = slot.lock()) return texture;
  auto texture = make();
  slot = texture;
  return texture;
}

std::uint64_t MoviePlayers::playersOpened() const {
  std::lock_guard lock(mutex_);
  return opened_;
}

std::size_t MoviePlayers::playing() const {
  std::lock_guard lock(mutex_);
  std::size_t n = 0;
  for (const auto& [key, entry] : players_) n += entry.player.expired() ? 0 : 1;
  return n;
}

std::uint64_t MoviePlayers::framesDecoded() const {
  std::lock_guard lock(mutex_);
  std::uint64_t n = 0;
  for (const auto& [key, entry] : players_)
    if (const auto player = entry.player.lock()) n += player->framesDecoded();
  return n;
}

}  // namespace gs::render
