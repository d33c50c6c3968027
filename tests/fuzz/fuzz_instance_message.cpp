// The single-instance socket's message (app::parseInstanceMessage): what another local
// process sends the running window.
#include "app/single_instance.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  for (const auto& input : gs::app::parseInstanceMessage(gs::fuzz::view(data, size)))
    if (input.empty() || input.find('\n') != std::string::npos) __builtin_trap();
  return 0;
}
