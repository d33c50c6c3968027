// Private to net/: what an HTTP response's head says, read from bytes a server chose
// (RFC 9110 sections 8.6 Content-Length, 8.4 Content-Encoding, 14.4 Content-Range), and
// what the transfer then expects of the body. Pure functions of their arguments, so that
// tests/fuzz/fuzz_http_response.cpp can feed them any bytes.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace gs::net::detail {

/// The fields of the last response head seen (a redirect or a 1xx starts a new one).
/// -1 means "not given" (or not parseable).
struct ResponseHead {
  long code = 0;       // from the status line "HTTP/x y reason"
  std::string reason;  // its reason phrase
  std::int64_t contentLength = -1;
  bool encoded = false;  // Content-Encoding other than identity
  std::int64_t rangeStart = -1, rangeEnd = -1, rangeTotal = -1;  // "bytes S-E/T"
};

/// Reads one header line as libcurl hands it over (CRLF included or not): a status line
/// resets `head`; Content-Length, Content-Encoding and Content-Range (names in any case)
/// set their fields; other lines are ignored. Negative or malformed numbers are ignored.
void readHeaderLine(std::string_view line, ResponseHead& head);

/// What the body of a 2xx response will hold, decided once its head arrived.
struct BodyPlan {
  std::string error;               // non-empty: refuse the response (the message's tail)
  std::int64_t resourceSize = -1;  // bytes of the whole resource, -1 unknown
  std::int64_t left = -1;          // bytes of this response's body, -1 unknown
  bool rangeIgnored = false;       // asked for a range, got the whole resource
  std::uint64_t drop = 0;          // leading body bytes to drop (range ignored)
};

/// The plan for a response with status `code` (2xx) to a request that asked for bytes
/// from `from` (`ranged`: a Range header was sent). A 206 that starts elsewhere is an
/// error; a range end below its start, or a length that overflows, leaves `left` unknown.
BodyPlan planBody(const ResponseHead& head, long code, bool ranged, std::uint64_t from);

}  // namespace gs::net::detail
