// URLs and local paths: one RFC 3986 resolver for the parser (EXTERNPROTO, Inline
// self-reference), the renderer (Inline, textures, QNV urls) and the session, and the
// one rule of what content from a URL may reference (docs/progressive-loading.md,
// "Safety"). A "URL" here is also a plain local path ("dir/world.wrl", "/tmp/a.wrl"),
// as VRML97 url fields (clause 4.5) and the command line allow.
#pragma once

#include <string>
#include <string_view>

namespace gs::base {

/// Length of the scheme of `url` ("http" in "http://h/a": 4), 0 when it has none. A
/// scheme is a letter followed by letters, digits, '+', '-' or '.' and then ':'
/// (RFC 3986 3.1); one-letter schemes are taken as drive letters ("C:"), not schemes.
std::size_t schemeLength(std::string_view url);

/// Whether `url` has a scheme (schemeLength(url) > 0).
bool hasScheme(std::string_view url);

/// The scheme of `url` in lower case ("http"), "" when it has none.
std::string schemeOf(std::string_view url);

/// Whether `url` starts with http:// or https:// (case-insensitive scheme).
bool isHttpUrl(std::string_view url);

/// `url` without its query and fragment ("?..." and "#..."), e.g. to read its extension.
std::string_view withoutQueryOrFragment(std::string_view url);

/// `reference` resolved against `base` as RFC 3986 section 5.2 says (the examples of
/// section 5.4 hold): a reference with a scheme stays as it is (dot segments removed),
/// "//host/p" takes base's scheme, "/p" base's scheme and authority (an absolute path
/// in an http world names a file on that host), a relative path joins base's
/// directory; "." and ".." segments are removed; an empty reference gives base
/// without its fragment. A base without scheme is a local path: relative references
/// join its directory the same way, and a relative base keeps the ".." that climb above
/// it ("dir/w.wrl" + "../../x" = "../x").
std::string resolveUrl(std::string_view base, std::string_view reference);

/// The local file path named by `url`: a plain path as it is; a file: URL
/// ("file:///a/my%20b.wrl", "file://localhost/a", "file:/a") with its host dropped and
/// %-escapes decoded; "" for any other scheme.
std::string localPathOfUrl(std::string_view url);

/// `s` with each %XX escape (two hex digits) decoded; other '%' kept.
std::string percentDecode(std::string_view s);

/// `path` (a relative path as a file is named, already decoded) written as a URL's path
/// (RFC 3986 section 2.1): every byte but the unreserved ones, '/', ':' and '@' and the
/// sub-delimiters as %XX (a space as %20, '%' as %25, '?' and '#' too; a ':' before the
/// first '/' too, which would read as a scheme). percentDecode gives `path` back. A path
/// that starts with '/' stays one (resolveUrl reads it from the root; "//" as a host).
std::string percentEncodePath(std::string_view path);

/// Whether content read from `baseUrl` may reference `resolvedUrl`: always for local
/// content; for content from http(s) only http(s) and data: URLs (docs/progressive-loading.md,
/// "Safety"). Content of a data: URL is treated as content from the network (it carries no
/// trace of who named it, and a remote world may name one): it too may name only http(s)
/// and data: URLs. False sets `error` to "<base> may not reference '<url>': content from
/// the network may only reference http(s) URLs" (a data: base shown by its first 48
/// characters, "content of a data: URL, as from the network, may only reference http(s)
/// URLs").
bool mayReference(std::string_view baseUrl, std::string_view resolvedUrl, std::string& error);

}  // namespace gs::base
