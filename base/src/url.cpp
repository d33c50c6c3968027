#include "base/url.hpp"

#include "base/data_url.hpp"

#include <vector>

#include "base/text.hpp"

namespace gs::base {

namespace {

bool isAlpha(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}
bool isDigit(char c) {
  return c >= '0' && c <= '9';
}
int hexValue(char c) {
  if (isDigit(c)) return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

/// The five components of RFC 3986 section 3 (appendix B); "has" flags tell an empty
/// component from an absent one.
struct UrlParts {
  std::string_view scheme, authority, path, query, fragment;
  bool hasScheme = false, hasAuthority = false, hasQuery = false, hasFragment = false;
};

UrlParts split(std::string_view url) {
  UrlParts p;
  if (const std::size_t n = schemeLength(url); n > 0) {
    p.hasScheme = true;
    p.scheme = url.substr(0, n);
    url.remove_prefix(n + 1);
  }
  if (url.starts_with("//")) {
    p.hasAuthority = true;
    const std::size_t end = url.find_first_of("/?#", 2);
    p.authority = url.substr(2, end == std::string_view::npos ? url.npos : end - 2);
    url.remove_prefix(end == std::string_view::npos ? url.size() : end);
  }
  if (const std::size_t hash = url.find('#'); hash != std::string_view::npos) {
    p.hasFragment = true;
    p.fragment = url.substr(hash + 1);
    url = url.substr(0, hash);
  }
  if (const std::size_t q = url.find('?'); q != std::string_view::npos) {
    p.hasQuery = true;
    p.query = url.substr(q + 1);
    url = url.substr(0, q);
  }
  p.path = url;
  return p;
}

/// RFC 3986 5.2.4 on segments: "." and ".." removed. An absolute path never climbs
/// above its root; a relative one keeps the ".." that climb above its start.
std::string removeDotSegments(std::string_view path) {
  const bool absolute = path.starts_with('/');
  if (absolute) path.remove_prefix(1);
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t slash = path.find('/', start);
    const bool last = slash == std::string_view::npos;
    const std::string_view segment = path.substr(start, last ? path.npos : slash - start);
    if (segment == ".") {
      if (last) out.emplace_back();
    } else if (segment == "..") {
      if (!out.empty() && out.back() != "..")
        out.pop_back();
      else if (!absolute)
        out.emplace_back("..");
      if (last) out.emplace_back();
    } else {
      out.push_back(segment);
    }
    if (last) break;
    start = slash + 1;
  }
  std::string result = absolute ? "/" : "";
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (i > 0) result += '/';
    result += out[i];
  }
  return result;
}

/// RFC 3986 5.2.3: `reference` joined to the directory of the base path.
std::string merge(const UrlParts& base, std::string_view reference) {
  // Built with append (not operator+ of temporaries, which trips GCC 12's -Wrestrict
  // false positive at -O3).
  std::string out;
  if (base.hasAuthority && base.path.empty()) {
    out.reserve(reference.size() + 1);
    out.push_back('/');
  } else if (const std::size_t slash = base.path.rfind('/'); slash != std::string_view::npos) {
    out.reserve(slash + 1 + reference.size());
    out.append(base.path.substr(0, slash + 1));
  }
  out.append(reference);
  return out;
}

/// RFC 3986 5.3: the components put back together.
std::string recompose(std::string_view scheme, bool hasAuthority, std::string_view authority,
                      std::string_view path, bool hasQuery, std::string_view query,
                      bool hasFragment, std::string_view fragment) {
  std::string out;
  if (!scheme.empty()) out.append(scheme).push_back(':');
  if (hasAuthority) out.append("//").append(authority);
  out.append(path);
  if (hasQuery) out.append("?").append(query);
  if (hasFragment) out.append("#").append(fragment);
  return out;
}

}  // namespace

std::size_t schemeLength(std::string_view url) {
  if (url.empty() || !isAlpha(url[0])) return 0;
  for (std::size_t i = 1; i < url.size(); ++i) {
    const char c = url[i];
    if (c == ':') return i >= 2 ? i : 0;
    if (!isAlpha(c) && !isDigit(c) && c != '+' && c != '-' && c != '.') return 0;
  }
  return 0;
}

bool hasScheme(std::string_view url) {
  return schemeLength(url) > 0;
}

std::string schemeOf(std::string_view url) {
  return toLower(url.substr(0, schemeLength(url)));
}

bool isHttpUrl(std::string_view url) {
  return startsWithNoCase(url, "http://") || startsWithNoCase(url, "https://");
}

std::string_view withoutQueryOrFragment(std::string_view url) {
  return url.substr(0, url.find_first_of("?#"));
}

std::string resolveUrl(std::string_view base, std::string_view reference) {
  const UrlParts r = split(reference);
  if (r.hasScheme)
    return recompose(r.scheme, r.hasAuthority, r.authority, removeDotSegments(r.path), r.hasQuery,
                     r.query, r.hasFragment, r.fragment);
  const UrlParts b = split(base);
  if (r.hasAuthority)
    return recompose(b.scheme, true, r.authority, removeDotSegments(r.path), r.hasQuery, r.query,
                     r.hasFragment, r.fragment);
  if (r.path.empty())
    return recompose(b.scheme, b.hasAuthority, b.authority, b.path, r.hasQuery || b.hasQuery,
                     r.hasQuery ? r.query : b.query, r.hasFragment, r.fragment);
  const std::string path =
      removeDotSegments(r.path.starts_with('/') ? std::string(r.path) : merge(b, r.path));
  return recompose(b.scheme, b.hasAuthority, b.authority, path, r.hasQuery, r.query, r.hasFragment,
                   r.fragment);
}

std::string percentDecode(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && hexValue(s[i + 1]) >= 0 && hexValue(s[i + 2]) >= 0) {
      out += static_cast<char>(hexValue(s[i + 1]) * 16 + hexValue(s[i + 2]));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

std::string percentEncodePath(std::string_view path) {
  static constexpr std::string_view kKept = "-._~/!$&'()*+,;=:@";
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out;
  out.reserve(path.size());
  bool firstSegment = true;  // a ':' there would read as a scheme (RFC 3986 section 4.2)
  for (const char c : path) {
    const auto b = static_cast<unsigned char>(c);
    firstSegment &= c != '/';
    if ((b >= 'a' && b <= 'z') || (b >= 'A' && b <= 'Z') || (b >= '0' && b <= '9') ||
        (kKept.find(c) != std::string_view::npos && !(c == ':' && firstSegment))) {
      out += c;
    } else {
      out += '%';
      out += kHex[b >> 4];
      out += kHex[b & 15];
    }
  }
  return out;
}

std::string localPathOfUrl(std::string_view url) {
  const std::size_t scheme = schemeLength(url);
  if (scheme == 0) return std::string(url);
  if (!equalsNoCase(url.substr(0, scheme), "file")) return {};
  std::string_view path = url.substr(scheme + 1);
  if (path.starts_with("//")) {
    path.remove_prefix(2);
    const std::size_t slash = path.find('/');
    path = slash == std::string_view::npos ? std::string_view() : path.substr(slash);  // host
  }
  return percentDecode(path);
}

bool mayReference(std::string_view baseUrl, std::string_view resolvedUrl, std::string& error) {
  // A data: URL's content came from whoever named it, which may be the network (a data:
  // Inline in a remote world): it takes the network's rules, whoever that was.
  const bool data = isDataUrl(baseUrl);
  if ((!isHttpUrl(baseUrl) && !data) || isHttpUrl(resolvedUrl)) return true;
  if (isDataUrl(resolvedUrl)) return true;  // holds its bytes: reads nothing
  const std::string base = data && baseUrl.size() > 48 ? std::string(baseUrl.substr(0, 48)) + "..."
                                                       : std::string(baseUrl);
  error = base + " may not reference '" + std::string(resolvedUrl) +
          (data ? "': content of a data: URL, as from the network, may only reference http(s) URLs"
                : "': content from the network may only reference http(s) URLs");
  return false;
}

}  // namespace gs::base
