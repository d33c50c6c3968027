// Case-insensitive text helpers (ASCII only: URL schemes, file extensions, header and
// field names). Locale-independent; bytes >= 0x80 compare as themselves.
#pragma once

#include <string>
#include <string_view>

namespace gs::base {

/// `s` with the ASCII letters A-Z turned into a-z.
std::string toLower(std::string_view s);

/// Whether `a` and `b` are equal ignoring ASCII case.
bool equalsNoCase(std::string_view a, std::string_view b);

/// Whether `s` starts with `prefix`, ignoring ASCII case.
bool startsWithNoCase(std::string_view s, std::string_view prefix);

/// Whether `s` ends with `suffix`, ignoring ASCII case.
bool endsWithNoCase(std::string_view s, std::string_view suffix);

}  // namespace gs::base
