#include "base/fetch.hpp"

#include "base/data_url.hpp"
#include "base/file.hpp"
#include "base/url.hpp"

namespace gs::base {

std::string localFileFor(const std::string& url, const std::string& referrer, std::string& error) {
  if (!referrer.empty() && !mayReference(referrer, url, error)) return {};
  return isDataUrl(url) ? std::string() : localPathOfUrl(url);
}

std::optional<Fetched> fetchLocally(const std::string& url, const std::string& referrer) {
  Fetched out;
  std::string error;
  const std::string path = localFileFor(url, referrer, error);
  if (!error.empty()) {
    out.state = FetchState::refused;
    out.error = error;
    return out;
  }
  if (isDataUrl(url)) {
    std::string mediaType;
    if (decodeDataUrl(url, out.bytes, mediaType, error)) {
      out.state = FetchState::ready;
    } else {
      out.error = (url.size() > 48 ? url.substr(0, 48) + "..." : url) + ": " + error;
    }
    return out;
  }
  if (path.empty()) return std::nullopt;
  if (readFile(path, out.bytes, error)) {
    out.state = FetchState::ready;
  } else {
    out.error = error;  // readFile names the path and the reason
  }
  return out;
}

Fetched LocalFetcher::fetch(const std::string& url, const std::string& referrer, FetchMode) {
  if (std::optional<Fetched> local = fetchLocally(url, referrer)) return std::move(*local);
  Fetched out;
  out.error = url + ": only local files can be read without a network loader";
  return out;
}

Fetcher& fetcherOr(Fetcher* fetcher) {
  static LocalFetcher local;
  return fetcher != nullptr ? *fetcher : local;
}

}  // namespace gs::base
