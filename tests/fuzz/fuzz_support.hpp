// Shared by the libFuzzer targets (docs/fuzzing.md). Each target feeds one reader of
// untrusted bytes; the errors a reader documents (std::runtime_error and its kin:
// InputError, ParseError, GzipError) are expected answers, so they are caught; anything
// else (a crash, a sanitizer report, std::logic_error such as std::out_of_range, a leak,
// a time-out) is a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace gs::fuzz {

inline std::string_view view(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// Runs `f`, swallowing the documented error type of the readers.
template <class F>
void expectingErrors(F&& f) {
  try {
    f();
  } catch (const std::runtime_error&) {
  }
}

}  // namespace gs::fuzz
