// Hostile and broken input: truncation at every length, random bytes, deep nesting, counts
// that claim more data than there is, unterminated strings, and the regression files in
// tests/data/vrml/bad/ (each named after what it tests). None may crash, hang, throw or
// allocate from a count in the file; every problem is an error diagnostic with its place.
#include "test_parser_support.hpp"

#include "encodings/parser.hpp"

#include <catch2/catch.hpp>

#include <chrono>
#include <cstring>
#include <memory>
#include <random>
#include <string>

using namespace gs::vrml;
using gs::test::parse;

namespace {

// A small world touching most of the grammar.
const std::string kWorld = R"(#VRML V2.0 utf8
# comment
PROTO Ball [ field SFFloat r 1 exposedField SFColor c 1 0 0 eventIn SFBool go ] {
  Transform { children Shape {
    appearance Appearance { material Material { diffuseColor IS c } }
    geometry Sphere { radius IS r } } }
  DEF T TimeSensor { loop TRUE }
}
EXTERNPROTO Ext [ field SFBool on ] [ "urn:nothing" ]
DEF B Ball { r 2.5 }
Ext { on TRUE }
DEF G Transform { children [
  Shape { geometry IndexedFaceSet {
    coord Coordinate { point [ 0 0 0, 1 0 0, 1 1 0, 0 1 0 ] }
    coordIndex [ 0 1 2 -1, 0 2 3 -1 ] texCoord TextureCoordinate { point [ 0 0 1 1 ] } } }
  USE B
  DEF S Script { field SFNode me USE S eventIn SFTime t field MFString u [ "a\"b" "c" ] }
  Shape { appearance Appearance { texture PixelTexture { image 2 2 1 0x00 0xFF 0x80 0x7F } } }
] }
DEF TS TimeSensor { cycleInterval 2 }
DEF PI PositionInterpolator { key [ 0, 1 ] keyValue [ 0 0 0 1 1 1 ] }
ROUTE TS.fraction_changed TO PI.set_fraction
ROUTE PI.value_changed TO G.set_translation
WorldInfo { title "done" info [ "x", "y" ] }
)";

// Parses a copy of `bytes` in a heap block of exactly that size, so AddressSanitizer
// sees any read past the end.
Scene parseExact(std::string_view bytes, const ParseOptions& o = {}) {
  std::unique_ptr<char[]> copy(new char[bytes.size() + 1]);
  if (!bytes.empty()) std::memcpy(copy.get(), bytes.data(), bytes.size());
  return parseVrml(std::string_view(copy.get(), bytes.size()), "bad.wrl", o);
}

void checkPlaced(const Scene& s) {
  for (const Diagnostic& d : s.diagnostics.items) {
    CHECK(!d.message.empty());
    CHECK(d.location.file == "bad.wrl");
  }
}

}  // namespace

TEST_CASE("bad input: the sample world itself is clean", "[bad_input]") {
  Scene s = parseExact(kWorld);
  INFO((s.diagnostics.items.empty() ? std::string() : s.diagnostics.items[0].format()));
  CHECK(s.diagnostics.errorCount() == 0);
  CHECK(s.diagnostics.warningCount() == 1);  // the unresolvable EXTERNPROTO
  CHECK(s.rootNodes.size() == 6);
  CHECK(s.routes.size() == 2);
}

TEST_CASE("bad input: every truncation of a world parses or fails cleanly", "[bad_input]") {
  std::size_t failed = 0;
  for (std::size_t n = 0; n <= kWorld.size(); ++n) {
    Scene s;
    REQUIRE_NOTHROW(s = parseExact(std::string_view(kWorld).substr(0, n)));
    checkPlaced(s);
    if (s.diagnostics.hasErrors()) ++failed;
  }
  // Every cut inside a node or statement is an error; a few cuts between statements are not.
  CHECK(failed > kWorld.size() * 3 / 4);
}

TEST_CASE("bad input: random bytes and random mutations", "[bad_input]") {
  std::mt19937 rng(20240611);
  std::uniform_int_distribution<int> byte(0, 255);
  const std::string alphabet = "{}[]\"#,.-+0123456789eExX \n\tDEFUSEPROTOISTO\\";
  std::uniform_int_distribution<std::size_t> pick(0, alphabet.size() - 1);
  for (int round = 0; round < 300; ++round) {
    std::string junk = round % 2 == 0 ? std::string("#VRML V2.0 utf8\n") : std::string();
    const std::size_t len = static_cast<std::size_t>(rng() % 400);
    for (std::size_t i = 0; i < len; ++i)
      junk += round % 3 == 0 ? alphabet[pick(rng)] : static_cast<char>(byte(rng));
    Scene s;
    REQUIRE_NOTHROW(s = parseExact(junk));
    checkPlaced(s);
  }
  for (int round = 0; round < 400; ++round) {
    std::string w = kWorld;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = 16 + rng() % (w.size() - 16);
      switch (rng() % 3) {
        case 0:
          w[at] = alphabet[pick(rng)];
          break;
        case 1:
          w.erase(at, 1 + rng() % 8);
          break;
        default:
          w.insert(at, 1, alphabet[pick(rng)]);
          break;
      }
    }
    Scene s;
    REQUIRE_NOTHROW(s = parseExact(w));
    checkPlaced(s);
  }
}

TEST_CASE("bad input: 100,000 nested nodes give a nesting error, no stack overflow",
          "[bad_input]") {
  const int n = 100000;
  auto nested = [&](const std::string& open, const std::string& close) {
    std::string t = "#VRML V2.0 utf8\n";
    t.reserve(t.size() + static_cast<std::size_t>(n) * (open.size() + close.size()));
    for (int i = 0; i < n; ++i) t += open;
    for (int i = 0; i < n; ++i) t += close;
    return t;
  };
  for (const auto& [open, close] :
       {std::pair<std::string, std::string>{"Group { children [ ", "] } "},
        {"Transform { children ", "} "},
        {"Shape { appearance Appearance { material ", "} } "},
        {"PROTO P [] { ", "} "},
        {"Group { PROTO P [ field SFNode f ", "] { Group {} } } "},
        {"DEF S Script { field SFNode n ", "} "}}) {
    INFO(open);
    Scene s;
    REQUIRE_NOTHROW(s = parseExact(nested(open, close)));
    REQUIRE(s.diagnostics.errorCount() >= 1);
    CHECK(gs::test::firstError(s).find("nested deeper than 256 levels") != std::string::npos);
  }
  // Skipping does not recurse: unknown nodes and unknown fields nested 100,000 deep.
  Scene skip = parseExact(nested("Foo { ", "} "));
  CHECK(skip.diagnostics.errorCount() == 1);
  Scene brackets = parseExact("#VRML V2.0 utf8\nGroup { junk " + std::string(100000, '[') +
                              std::string(100000, ']') + " }");
  CHECK(brackets.diagnostics.errorCount() == 1);
  CHECK(brackets.rootNodes.size() == 1);

  ParseOptions o;
  o.limits.maxNesting = 3;
  Scene three = parse("Group { children Group { children Group { } } }", o);
  CHECK(three.diagnostics.items.empty());
  Scene four = parse("Group { children Group { children Group { children Group {} } } }", o);
  CHECK(four.diagnostics.errorCount() == 1);
}

TEST_CASE("bad input: counts larger than the data are refused before allocating", "[bad_input]") {
  Scene img = parse("PixelTexture { image 100000 100000 4 0xFF 0xFF }");
  REQUIRE(img.diagnostics.errorCount() == 1);
  CHECK(gs::test::firstError(img).find(
            "SFImage of 100000 x 100000 needs 10000000000 pixels but only") == 0);
  Scene neg = parse("PixelTexture { image -1 2 3 }");
  CHECK(gs::test::firstError(neg) == "invalid SFImage size -1 x 2 with 3 components");
  Scene comps = parse("PixelTexture { image 1 1 5 0 }");
  CHECK(gs::test::firstError(comps) == "invalid SFImage size 1 x 1 with 5 components");
  Scene wrap = parse("PixelTexture { image 65536 65536 1 0 }");
  CHECK(wrap.diagnostics.errorCount() == 1);
  Scene ok = parse("PixelTexture { image 0 0 0 }");
  CHECK(ok.diagnostics.errorCount() == 0);

  // An MF list never reserves from a count, and one cut off is an error at the end.
  Scene list = parseExact("#VRML V2.0 utf8\nIndexedFaceSet { coordIndex [ 2147483647 1 2 ");
  REQUIRE(list.diagnostics.errorCount() == 1);

  ParseOptions small;
  small.limits.maxInputBytes = 64;
  Scene big = parse(std::string(100, ' ') + "Group {}", small);
  CHECK(gs::test::firstError(big).find("maxInputBytes") != std::string::npos);
}

TEST_CASE("bad input: unterminated strings and comments at the end", "[bad_input]") {
  Scene s = parseExact("#VRML V2.0 utf8\nWorldInfo { title \"never ends }\nGroup {}\n");
  REQUIRE(s.diagnostics.errorCount() == 1);
  CHECK(s.diagnostics.items[0].message == "unterminated string");
  CHECK(s.diagnostics.items[0].location.line == 2);
  CHECK(s.diagnostics.items[0].location.column == 19);
  Scene esc = parseExact("#VRML V2.0 utf8\nWorldInfo { title \"ends in a backslash\\");
  CHECK(esc.diagnostics.errorCount() == 1);
  Scene unknown = parseExact("#VRML V2.0 utf8\nFoo { x \"open }");
  CHECK(unknown.diagnostics.errorCount() == 2);
  Scene comment = parseExact("#VRML V2.0 utf8\nGroup {} # no newline");
  CHECK(comment.diagnostics.items.empty());
}

TEST_CASE("bad input: large interfaces and many lookups stay linear", "[bad_input]") {
  // A PROTO with 20,000 members, an instance giving each, ROUTEs to them, a Script with
  // 4,000 declarations, and many instances whose location is taken after their body:
  // quadratic algorithms would take minutes here.
  const auto t0 = std::chrono::steady_clock::now();
  std::string t = "PROTO Big [\n";
  for (int i = 0; i < 20000; ++i) t += "exposedField SFInt32 m" + std::to_string(i) + " 0\n";
  t += "] { Group {} }\nDEF B Big {\n";
  for (int i = 0; i < 20000; ++i) t += " m" + std::to_string(i) + " " + std::to_string(i);
  t += " }\nDEF S Script {\n";
  for (int i = 0; i < 4000; ++i) t += " eventOut SFInt32 o" + std::to_string(i) + "\n";
  t += "}\n";
  for (int i = 0; i < 4000; ++i)
    t += "ROUTE S.o" + std::to_string(i) + " TO B.set_m" + std::to_string(i * 5) + "\n";
  t += "PROTO Ball [ field SFNode m NULL ] { Shape { appearance Appearance { material IS m } } }\n";
  for (int i = 0; i < 20000; ++i) t += "Material {} Ball { m Material { } }\n";
  ParseOptions o;
  Scene s = parse(t, o);
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK(s.diagnostics.errorCount() == 0);
  CHECK(s.diagnostics.warningCount() == 1001);  // the root Materials, capped, and a summary
  CHECK(s.rootNodes.size() == 40002);
  CHECK(sec < 30.0);
  Scene script = parse("DEF S Script {\n" + std::string(5000 * 0, ' ') + [] {
    std::string d;
    for (int i = 0; i < 5000; ++i) d += " field SFInt32 f" + std::to_string(i) + " 1\n";
    return d;
  }() + "}");
  CHECK(gs::test::firstError(script) == "more than 4096 fields and events in one Script node");
}

TEST_CASE("bad input: too many errors stop the parse", "[bad_input]") {
  std::string t;
  for (int i = 0; i < 5000; ++i) t += "Group { nope 1 }\n";
  Scene s = parse(t);
  CHECK(s.diagnostics.items.size() == 1001);
  CHECK(s.diagnostics.items.back().message == "too many errors (1000): giving up on this file");
  CHECK(s.rootNodes.size() < 1001);
}

TEST_CASE("bad input: the regression files in tests/data/vrml/bad", "[bad_input]") {
  const auto files =
      gs::test::filesWithSuffix(gs::test::sourceDir() / "tests/data/vrml/bad", ".wrl");
  REQUIRE(files.size() >= 9);
  for (const auto& f : files) {
    Scene s;
    REQUIRE_NOTHROW(s = loadVrmlFile(f.string()));
    INFO(f.filename().string());
    bool placed = false;
    for (const Diagnostic& d : s.diagnostics.items)
      placed = placed || (d.severity == Severity::error && d.location.line > 0 &&
                          d.location.column > 0 && d.location.file == f.string());
    CHECK(placed);
  }
}
