// data: URLs (RFC 2397), as X3D 4.0 (clause 9.2.1) and glTF 2.0 (clause 3.6.1.1) allow
// for embedded resources: "data:[<mediatype>][;base64],<data>".
#pragma once

#include <string>
#include <string_view>

namespace gs::base {

/// True when `url` starts with "data:" (any case).
bool isDataUrl(std::string_view url);

/// The bytes a data: URL holds: base64 decoded when it says ";base64" (white space
/// skipped), else %-decoded. `mediaType` receives the media type ("" when none). False
/// with `error` set for a URL without ',' or with characters outside base64.
bool decodeDataUrl(std::string_view url, std::string& bytes, std::string& mediaType,
                   std::string& error);

/// "data:<mediaType>;base64,<bytes in base64>".
std::string makeDataUrl(std::string_view mediaType, std::string_view bytes);

}  // namespace gs::base
