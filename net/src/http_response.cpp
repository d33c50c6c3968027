#include "http_response.hpp"

#include "base/text.hpp"

#include <cstdio>
#include <cstdlib>
#include <limits>

namespace gs::net::detail {
namespace {

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string_view::npos) return {};
  return std::string(s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1));
}

}  // namespace

void readHeaderLine(std::string_view raw, ResponseHead& head) {
  const std::string line = trim(raw);
  if (line.rfind("HTTP/", 0) == 0) {
    head = ResponseHead{};
    const auto sp = line.find(' ');
    if (sp != std::string::npos) {
      const long code = std::strtol(line.c_str() + sp + 1, nullptr, 10);
      head.code = code >= 0 && code <= 999 ? code : 0;
      const auto sp2 = line.find(' ', sp + 1);
      if (sp2 != std::string::npos) head.reason = trim(std::string_view(line).substr(sp2 + 1));
    }
    return;
  }
  const auto colon = line.find(':');
  if (colon == std::string::npos) return;
  const std::string name = base::toLower(trim(std::string_view(line).substr(0, colon)));
  const std::string value = trim(std::string_view(line).substr(colon + 1));
  if (name == "content-length") {
    char* end = nullptr;
    const long long v = std::strtoll(value.c_str(), &end, 10);
    if (end != value.c_str() && v >= 0) head.contentLength = v;
  } else if (name == "content-encoding") {
    const std::string v = base::toLower(value);
    head.encoded = !v.empty() && v != "identity";
  } else if (name == "content-range") {
    // "bytes 100-1099/5000" or "bytes 100-1099/*".
    long long first = -1, last = -1;
    char totalText[32] = {};
    if (std::sscanf(value.c_str(), "bytes %lld-%lld/%31s", &first, &last, totalText) == 3 &&
        first >= 0 && last >= 0) {
      head.rangeStart = first;
      head.rangeEnd = last;
      head.rangeTotal = -1;
      if (totalText[0] != '*') {
        const long long total = std::strtoll(totalText, nullptr, 10);
        if (total >= 0) head.rangeTotal = total;
      }
    }
  }
}

BodyPlan planBody(const ResponseHead& head, long code, bool ranged, std::uint64_t from) {
  BodyPlan p;
  p.resourceSize = head.encoded ? -1 : head.contentLength;
  if (ranged && code == 206) {
    if (head.rangeStart >= 0 && static_cast<std::uint64_t>(head.rangeStart) != from) {
      p.error = "asked for bytes from " + std::to_string(from) +
                " but the server sent bytes from " + std::to_string(head.rangeStart);
      return p;
    }
    p.resourceSize = head.rangeTotal;
    // The end is inclusive; an end of INT64_MAX would overflow the length.
    if (head.rangeEnd >= head.rangeStart && head.rangeStart >= 0 &&
        head.rangeEnd < std::numeric_limits<std::int64_t>::max())
      p.left = head.rangeEnd - head.rangeStart + 1;
    else if (!head.encoded)
      p.left = head.contentLength;
  } else {
    if (ranged) {
      p.rangeIgnored = true;
      p.drop = from;
    }
    if (p.resourceSize >= 0) {
      const auto size = static_cast<std::uint64_t>(p.resourceSize);
      p.left = p.drop >= size ? 0 : static_cast<std::int64_t>(size - p.drop);
    }
  }
  return p;
}

}  // namespace gs::net::detail
