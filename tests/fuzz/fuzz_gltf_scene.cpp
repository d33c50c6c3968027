// glTF assets built into worlds (vrml/src/gltf_*.cpp: the hierarchy, every primitive mode,
// accessors dense and sparse, materials and embedded images, cameras, punctual lights,
// animation samplers) on any bytes; external buffers are refused (the loader answers
// nothing), so only data: URIs and the GLB BIN chunk count.
#include "fuzz_support.hpp"
#include "gltf_import.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gs::vrml::ParseOptions options;
  options.loader = [](const std::string&, std::string&, std::string& error) {
    error = "no external files while fuzzing";
    return false;
  };
  options.limits.maxNodes = 100000;
  gs::vrml::Scene scene;
  gs::vrml::parsing::importGltf(gs::fuzz::view(data, size), "fuzz.gltf", options, scene);
  return 0;
}
