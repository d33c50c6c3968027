// Test helpers for the execution model: a world from VRML text and a recorded trace.
#pragma once

#include "encodings/parser.hpp"
#include "runtime/execution_model.hpp"
#include "runtime/trace.hpp"

#include <memory>
#include <string>
#include <vector>

namespace gs::test {

/// The whole text of a world and its url.
struct WorldText {
  std::string text;
  std::string url;
};

/// An X3D world (Classic VRML encoding, X3D 4.0) of `body`.
inline WorldText x3dWorld(const std::string& body) {
  return {"#X3D V4.0 utf8\n" + body, "test.x3dv"};
}

/// A world parsed from `body` (the header is added) and run from `loadTime`, recording
/// every event as "NODE.field=value" (trace names, runtime/trace.hpp).
struct RunningWorld {
  std::shared_ptr<vrml::Scene> scene;
  std::vector<std::string> events;
  std::unique_ptr<runtime::ExecutionModel> model;

  explicit RunningWorld(const std::string& body, double loadTime = 0.0,
                        runtime::ExecutionOptions options = {})
      : RunningWorld(WorldText{"#VRML V2.0 utf8\n" + body, "test.wrl"}, loadTime,
                     std::move(options)) {}
  /// A world from the whole text of a file (header included), e.g. x3dWorld(body).
  explicit RunningWorld(const WorldText& world, double loadTime = 0.0,
                        runtime::ExecutionOptions options = {}) {
    scene = std::make_shared<vrml::Scene>(vrml::parseVrml(world.text, world.url));
    options.trace = [this](const runtime::TraceEvent& e) {
      const auto& spec = e.node->type().fields[static_cast<std::size_t>(e.field)];
      std::string name = spec.name;
      if (spec.access == vrml::AccessType::exposedField) name += "_changed";
      events.push_back(runtime::traceNodeName(*e.node) + "." + name + "=" +
                       runtime::fieldValueText(*e.value));
    };
    model = std::make_unique<runtime::ExecutionModel>(scene, loadTime, std::move(options));
  }
  /// The node DEFed as `name` among the roots and their descendants.
  vrml::Node& node(const std::string& name) const;
  /// Field index of `field` in `n` (aliases accepted); fails the test when missing.
  static int field(const vrml::Node& n, const std::string& field);
  /// Posts `value` to `name.field` and processes it as one timestamp.
  void send(const std::string& name, const std::string& fieldName, vrml::FieldValue value);
  /// Events recorded since the last call, then forgotten.
  std::vector<std::string> take() {
    std::vector<std::string> out;
    out.swap(events);
    return out;
  }
};

}  // namespace gs::test
