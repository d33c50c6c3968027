#include "app/pointer_input.hpp"
#include "base/url.hpp"
#include "formats/input_kind.hpp"

#include "scene/traversal.hpp"

#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <thread>

extern char** environ;

namespace gs::app {

runtime::PickResult toPickResult(const scene::PickHit& hit) {
  runtime::PickResult r;
  r.path.reserve(hit.path.size());
  for (const scene::PathStep& step : hit.path)
    r.path.push_back({const_cast<vrml::Node*>(step.node), step.localToWorld, step.children});
  r.point = hit.point;
  r.normal = hit.normal;
  r.texCoord = hit.texCoord;
  return r;
}

runtime::PointerEvent pointerEventAt(scene::SceneTraversal& traversal, const scene::Camera& camera,
                                     int width, int height, float x, float y, bool buttonDown) {
  runtime::PointerEvent e;
  const scene::Ray ray = scene::rayThroughPixel(camera, width, height, x, y);
  e.rayOrigin = ray.origin;
  e.rayDirection = ray.direction;
  e.buttonDown = buttonDown;
  if (x >= 0.0f && y >= 0.0f && x < static_cast<float>(width) && y < static_cast<float>(height))
    if (auto hit = scene::pick(
            traversal, camera, ray,
            glm::vec2(x / static_cast<float>(width), 1.0f - y / static_cast<float>(height))))
      e.hit = toPickResult(*hit);
  return e;
}

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// The scheme of `url` in lower case ("http"), empty for a path (a drive letter "C:" is
/// a path too).
std::string schemeOf(const std::string& url) {
  const std::size_t colon = url.find(':');
  if (colon == std::string::npos || colon < 2) return {};
  for (std::size_t i = 0; i < colon; ++i) {
    const char c = url[i];
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.') return {};
  }
  return lower(url.substr(0, colon));
}

/// The path part of `url` in lower case, without query and fragment.
std::string pathOf(const std::string& url) {
  return lower(url.substr(0, url.find_first_of("?#")));
}

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// A world (VRML97 or X3D in any encoding, formats::kindFromName) or a QNV stream.
bool isWorld(const std::string& path) {
  const formats::InputKind k = formats::kindFromName(path);
  return k == formats::InputKind::world || k == formats::InputKind::qnv ||
         endsWith(path, ".vrml") || endsWith(path, ".vrml.gz");
}

bool isPassiveDocument(const std::string& path) {
  for (const char* ext : {".pdf", ".html", ".htm", ".txt", ".png", ".jpg", ".jpeg", ".gif", ".svg"})
    if (endsWith(path, ext)) return true;
  return false;
}

}  // namespace

LinkDecision decideLink(const std::string& worldUrl, const std::vector<std::string>& url,
                        const std::vector<std::string>& parameter) {
  const std::string worldScheme = schemeOf(worldUrl);
  const bool remote = worldScheme == "http" || worldScheme == "https";
  bool newViewport = false;
  for (const std::string& p : parameter)
    if (p.starts_with("target=") && p.size() > 7 && p != "target=_self") newViewport = true;
  LinkDecision first;
  first.reason = "the link has no url";
  bool haveReason = false;
  for (const std::string& u : url) {
    if (u.empty() || u.starts_with("#")) continue;
    LinkDecision d;
    const std::string scheme = schemeOf(u);
    // Only web and file references are resolved; anything else stays as written.
    d.url = (scheme.empty() || scheme == "http" || scheme == "https" || scheme == "file")
                ? base::resolveUrl(worldUrl, u)
                : u;
    const std::string resolvedScheme = schemeOf(d.url);
    const std::string path = pathOf(d.url);
    const bool web = resolvedScheme == "http" || resolvedScheme == "https";
    const bool local = resolvedScheme.empty() || resolvedScheme == "file";
    if (web) {
      d.action = isWorld(path)
                     ? (newViewport ? LinkAction::openWorldInNewViewport : LinkAction::openWorld)
                     : LinkAction::external;
    } else if (local && remote) {
      d.reason = "a world from the network may not open local files (" + d.url + ")";
    } else if (local && isWorld(path)) {
      d.action = newViewport ? LinkAction::openWorldInNewViewport : LinkAction::openWorld;
    } else if (local && isPassiveDocument(path)) {
      d.action = LinkAction::external;
    } else if (local) {
      d.reason = "a link to a local file of this type is not opened (" + d.url + ")";
    } else {
      d.reason = "links of scheme '" + resolvedScheme + ":' are not followed (" + d.url + ")";
    }
    if (d.action != LinkAction::refused) return d;
    if (!haveReason) {
      first = d;
      haveReason = true;
    }
  }
  first.action = LinkAction::refused;
  return first;
}

bool openExternally(const std::string& url, std::string& error) {
  if (url.empty() || url.starts_with("-")) {
    error = "refused to open '" + url + "'";
    return false;
  }
  std::vector<char> program{'x', 'd', 'g', '-', 'o', 'p', 'e', 'n', '\0'};
  std::vector<char> argument(url.begin(), url.end());
  argument.push_back('\0');
  char* argv[] = {program.data(), argument.data(), nullptr};
  pid_t pid = 0;
  const int rc = ::posix_spawnp(&pid, "xdg-open", nullptr, nullptr, argv, environ);
  if (rc != 0) {
    error = std::string("cannot start xdg-open: ") + std::strerror(rc);
    return false;
  }
  std::thread([pid] { ::waitpid(pid, nullptr, 0); }).detach();  // no zombie left
  return true;
}

}  // namespace gs::app
