#include "base/data_url.hpp"

#include "base/url.hpp"

#include <array>
#include <cstdint>

namespace gs::base {
namespace {

constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

int sextet(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+' || c == '-') return 62;
  if (c == '/' || c == '_') return 63;
  return -1;
}

bool startsNoCase(std::string_view s, std::string_view prefix) {
  if (s.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i) {
    char c = s[i];
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    if (c != prefix[i]) return false;
  }
  return true;
}

}  // namespace

bool isDataUrl(std::string_view url) {
  return startsNoCase(url, "data:");
}

bool decodeDataUrl(std::string_view url, std::string& bytes, std::string& mediaType,
                   std::string& error) {
  bytes.clear();
  mediaType.clear();
  if (!isDataUrl(url)) {
    error = "not a data: URL";
    return false;
  }
  const std::size_t comma = url.find(',');
  if (comma == std::string_view::npos) {
    error = "a data: URL needs a ',' before its data";
    return false;
  }
  std::string_view header = url.substr(5, comma - 5);
  const std::string_view data = url.substr(comma + 1);
  bool base64 = false;
  if (header.size() >= 7 && startsNoCase(header.substr(header.size() - 7), ";base64")) {
    base64 = true;
    header.remove_suffix(7);
  }
  mediaType = std::string(header.substr(0, header.find(';')));
  if (!base64) {
    bytes = percentDecode(data);
    return true;
  }
  bytes.reserve(data.size() / 4 * 3);
  std::uint32_t acc = 0;
  int bits = 0;
  for (const char c : data) {
    if (c == '=' || c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
    const int v = sextet(c);
    if (v < 0) {
      error = "a base64 data: URL holds a character outside base64";
      bytes.clear();
      return false;
    }
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes.push_back(static_cast<char>((acc >> bits) & 0xFF));
    }
  }
  return true;
}

std::string makeDataUrl(std::string_view mediaType, std::string_view bytes) {
  std::string out = "data:" + std::string(mediaType) + ";base64,";
  out.reserve(out.size() + (bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16 |
                            static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1]))
                                << 8 |
                            static_cast<unsigned char>(bytes[i + 2]);
    for (int k = 3; k >= 0; --k) out.push_back(kAlphabet[(v >> (6 * k)) & 63]);
  }
  if (i < bytes.size()) {
    std::uint32_t v = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16;
    if (i + 1 < bytes.size())
      v |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8;
    out.push_back(kAlphabet[(v >> 18) & 63]);
    out.push_back(kAlphabet[(v >> 12) & 63]);
    out.push_back(i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=');
    out.push_back('=');
  }
  return out;
}

}  // namespace gs::base
