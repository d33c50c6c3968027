// The Script bridge (runtime/script_ecmascript.hpp): the input is the ECMAScript source
// of a Script node ("javascript:" url) with an eventIn, eventOuts of several types and a
// field holding a node; the world is loaded (initialize()), then time advances a few
// frames so that a TimeSensor's events reach the Script. Small limits: 50 ms per call,
// 16 MiB of heap.
#include "encodings/parser.hpp"
#include "fuzz_no_files.hpp"
#include "fuzz_support.hpp"
#include "runtime/execution_model.hpp"
#include "runtime/script_ecmascript.hpp"

#include <memory>

namespace {

std::string vrmlString(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string world =
      "#VRML V2.0 utf8\n"
      "DEF T TimeSensor { loop TRUE cycleInterval 0.5 }\n"
      "DEF X Transform { children Shape { geometry Box {} } }\n"
      "DEF S Script {\n"
      "  eventIn SFTime tick eventIn SFFloat fraction\n"
      "  eventOut SFFloat f eventOut SFVec3f v eventOut MFString s eventOut SFNode n\n"
      "  field SFNode node USE X field MFInt32 ints [1 2 3]\n"
      "  directOutput TRUE mustEvaluate TRUE\n"
      "  url " +
      vrmlString("javascript:" + std::string(gs::fuzz::view(data, size))) +
      "\n}\n"
      "ROUTE T.time TO S.tick\nROUTE T.fraction_changed TO S.fraction\n"
      "ROUTE S.v TO X.set_translation\n";
  gs::vrml::ParseOptions parse;
  parse.fetcher = gs::fuzz::noFiles();
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(world, "fuzz.wrl", parse));
  gs::runtime::ExecutionOptions options;
  options.scripts = gs::runtime::ecmascriptFactory();
  options.scriptLimits.callSeconds = 0.05;
  options.scriptLimits.heapBytes = 16u << 20;
  options.maxEventsPerCascade = 10'000;
  options.fetcher = gs::fuzz::noFiles();
  gs::runtime::ExecutionModel model(scene, 0.0, options);
  for (int frame = 1; frame <= 3; ++frame) model.advanceTo(frame * 0.1);
  return 0;
}
