// The parser over real files from ../shared/corpus (see its README): KiCad models, the
// castle-engine demo worlds and the OpenVRML conformance cases. Each test skips with a
// warning when its corpus folder is absent.
#include "test_parser_support.hpp"

#include "encodings/parser.hpp"
#include "geometry/geometry.hpp"

#include <catch2/catch.hpp>

#include <functional>
#include <set>
#include <string>

using namespace gs::vrml;
namespace fs = std::filesystem;

namespace {

std::string describe(const Scene& s) {
  std::string out;
  for (const Diagnostic& d : s.diagnostics.items) out += d.format() + "\n";
  return out;
}

// The 15 castle worlds that use castle-engine extensions, name missing files on purpose or
// are deliberately wrong (corpus README).
const std::set<std::string> kCastleNotPlain = {
    "lights_materials/headlight_custom.wrl",
    "lights_materials/raytracer/alien_mirror.wrl",
    "prototypes/extern_proto_built_in_kings_head.wrl",
    "prototypes/proto_nodes_by_external.wrl",
    "prototypes/proto_ultra_simple.wrl",
    "prototypes/warnings/errors/proto_invalid_field.wrl",
    "prototypes/warnings/errors/proto_separate_namespace.wrl",
    "vrml_2/castle_extensions/inline_load_control_test_1.wrl",
    "vrml_2/castle_extensions/logger_nodes.wrl",
    "vrml_2/collisions.wrl",
    "vrml_2/collisions_final.wrl",
    "vrml_2/inline_test.wrl",
    "vrml_2/kings_head.wrl",
    "vrml_2/kings_head_gif.wrl",
    "vrml_2/warnings/errors/recurse_inline.wrl",
};

// What a browser reports when it loads and draws the world: the parser's diagnostics plus
// those of tessellating every Shape's geometry.
std::size_t loadDiagnostics(const Scene& s) {
  Diagnostics geometry;
  std::set<const Node*> seen;
  std::function<void(const NodePtr&)> walk = [&](const NodePtr& n) {
    if (!n || !seen.insert(n.get()).second) return;
    if (n->typeName() == "Shape")
      if (NodePtr g = n->sfnode("geometry")) tessellate(*g, &geometry);
    for (std::size_t i = 0; i < n->fieldCount(); ++i) {
      const FieldValue& v = n->fieldAt(i);
      if (v.type() == FieldType::SFNode) walk(v.get<FieldType::SFNode>());
      if (v.type() == FieldType::MFNode)
        for (const NodePtr& c : v.get<FieldType::MFNode>()) walk(c);
    }
  };
  for (const NodePtr& r : s.rootNodes) walk(r);
  return s.diagnostics.items.size() + geometry.items.size();
}

}  // namespace

TEST_CASE("corpus: every KiCad model parses without errors", "[corpus]") {
  if (!gs::test::haveCorpus("vrml/kicad")) return;
  const auto files = gs::test::filesWithSuffix(gs::test::corpusDir() / "vrml/kicad", ".wrl");
  CHECK(files.size() == 138);
  std::size_t shapes = 0;
  for (const fs::path& f : files) {
    const Scene s = loadVrmlFile(f.string());
    INFO(f.filename().string() << "\n" << describe(s));
    CHECK(s.diagnostics.errorCount() == 0);
    CHECK(!s.rootNodes.empty());
    shapes += s.rootNodes.size();
  }
  CHECK(shapes > 1000);
}

TEST_CASE("corpus: castle worlds, plain ones without any diagnostic", "[corpus]") {
  if (!gs::test::haveCorpus("vrml/castle")) return;
  const fs::path root = gs::test::corpusDir() / "vrml/castle";
  const auto files = gs::test::filesWithSuffix(root, ".wrl");
  CHECK(files.size() == 77);
  std::size_t plain = 0, errorsFolder = 0, warningsFolder = 0, extensions = 0;
  for (const fs::path& f : files) {
    const std::string rel = fs::relative(f, root).generic_string();
    const Scene s = loadVrmlFile(f.string());
    INFO(rel << "\n" << describe(s));
    if (rel.find("warnings/errors/") != std::string::npos) {
      ++errorsFolder;
      CHECK(s.diagnostics.errorCount() >= 1);
    } else if (rel.find("warnings/") != std::string::npos) {
      // At least one warning (or error) when the world is loaded and drawn.
      ++warningsFolder;
      CHECK(loadDiagnostics(s) >= 1);
    } else if (kCastleNotPlain.count(rel) != 0) {
      ++extensions;
      CHECK(!s.rootNodes.empty());
    } else {
      ++plain;
      CHECK(s.diagnostics.items.empty());
    }
    for (const Diagnostic& d : s.diagnostics.items) {
      CHECK(!d.location.file.empty());
      CHECK(d.location.line > 0);
    }
  }
  // The README counts the 7 files under warnings/ among its 62 plain worlds; they are
  // deliberately faulty, so the warnings/ rule above is what they must meet.
  CHECK(plain + warningsFolder == 62);
  CHECK(errorsFolder == 3);
  CHECK(warningsFolder == 7);
  CHECK(extensions == 12);
}

TEST_CASE("corpus: OpenVRML good cases load without errors", "[corpus]") {
  if (!gs::test::haveCorpus("vrml/openvrml/good")) return;
  const auto files =
      gs::test::filesWithSuffix(gs::test::corpusDir() / "vrml/openvrml/good", ".wrl");
  CHECK(files.size() == 13);
  for (const fs::path& f : files) {
    const Scene s = loadVrmlFile(f.string());
    INFO(f.filename().string() << "\n" << describe(s));
    CHECK(s.diagnostics.errorCount() == 0);
  }
}

TEST_CASE("corpus: OpenVRML bad cases give an error with its place", "[corpus]") {
  if (!gs::test::haveCorpus("vrml/openvrml/bad")) return;
  const auto files = gs::test::filesWithSuffix(gs::test::corpusDir() / "vrml/openvrml/bad", ".wrl");
  CHECK(files.size() == 12);
  for (const fs::path& f : files) {
    const Scene s = loadVrmlFile(f.string());
    INFO(f.filename().string() << "\n" << describe(s));
    bool placed = false;
    for (const Diagnostic& d : s.diagnostics.items)
      placed = placed || (d.severity == Severity::error && d.location.line > 0 &&
                          d.location.column > 0 && d.location.file == f.string());
    CHECK(placed);
  }
}

TEST_CASE("corpus: the OpenVRML bad cases name the right problem", "[corpus]") {
  if (!gs::test::haveCorpus("vrml/openvrml/bad")) return;
  const fs::path dir = gs::test::corpusDir() / "vrml/openvrml/bad";
  auto first = [&](const char* name) {
    const Scene s = loadVrmlFile((dir / name).string());
    return gs::test::firstError(s);
  };
  CHECK(first("unrecognized-node.wrl") == "unknown node type 'UnrecognizedNode'");
  CHECK(first("unrecognized-field.wrl") == "unknown field 'wrong' in Node");
  CHECK(first("exposedfield-in-script.wrl") ==
        "exposedField is not allowed in a Script node (clause 6.40)");
  CHECK(first("value-for-eventin-in-proto.wrl") ==
        "cannot give a value to eventIn 'set_children' of Group");
  CHECK(first("use-def-in-different-proto-default-value.wrl") == "USE of unknown DEF name 'G'");
  CHECK(first("route-sfint32-to-sfbool.wrl").find("ROUTE type mismatch") == 0);
  CHECK(first("route-from-field.wrl").find("ROUTE source 'val'") == 0);
  CHECK(first("route-to-field.wrl").find("ROUTE destination 'val'") == 0);
  CHECK(first("is-outside-proto.wrl").find("IS statement outside a PROTO body") == 0);
  CHECK(first("is-value-type-mismatch.wrl").find("IS type mismatch") == 0);
  CHECK(first("proto-eventin-conflict.wrl").find("conflicts with") != std::string::npos);
  CHECK(first("proto-eventout-conflict.wrl").find("conflicts with") != std::string::npos);
}
