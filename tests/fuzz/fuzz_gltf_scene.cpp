// glTF assets built into worlds (gltf/src/import*.cpp: the hierarchy, every primitive mode,
// accessors dense and sparse, materials and embedded images, cameras, punctual lights,
// animation samplers, skins, morph targets, Draco) on any bytes, then run for two instants
// of the execution model (animations, morph interpolators, CPU skinning); external buffers
// are refused (the loader answers nothing), so only data: URIs and the GLB BIN chunk count.
#include "encodings/node_types.hpp"
#include "fuzz_no_files.hpp"
#include "fuzz_support.hpp"
#include "gltf/import.hpp"
#include "runtime/execution_model.hpp"

#include <memory>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gs::gltf::ImportOptions options;
  options.fetcher = gs::fuzz::noFiles();
  options.maxNodes = 100000;
  options.nodeType = [](std::string_view name) { return gs::vrml::x3dNodeType(name); };
  auto scene = std::make_shared<gs::vrml::Scene>();
  gs::gltf::importGltf(gs::fuzz::view(data, size), "fuzz.gltf", options, *scene);
  gs::runtime::ExecutionModel model(scene, 0.0);
  model.advanceTo(0.37);
  model.advanceTo(1.61);
  return 0;
}
