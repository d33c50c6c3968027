// StreamingParser: bytes fed in any split (plain or gzip) give the Scene parseVrml gives
// for the whole text; completed top-level statements show at once; cut statements are
// undone and retried; truncated, corrupt and fatal inputs are reported as parseVrml does.
#include "test_parser_support.hpp"

#include "encodings/parser.hpp"
#include "encodings/streaming_parser.hpp"

#include <catch2/catch.hpp>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace gs::vrml;
using gs::test::gzip;
namespace fs = std::filesystem;

namespace {

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// ---- structural comparison -------------------------------------------------------------

std::string where(const SourceLocation& l) {
  return l.file + ":" + std::to_string(l.line) + ":" + std::to_string(l.column);
}

struct Comparer {
  std::set<std::pair<const Node*, const Node*>> seen;
  std::string diff;  // the first difference found

  bool fail(const std::string& what) {
    if (diff.empty()) diff = what;
    return false;
  }

  bool nodes(const NodePtr& a, const NodePtr& b, const std::string& path) {
    if (!a || !b) return (!a && !b) || fail(path + ": NULL on one side only");
    if ((a.use_count() == 0) != (b.use_count() == 0))
      return fail(path + ": owning on one side only");
    if (!seen.insert({a.get(), b.get()}).second) return true;
    if (a->typeName() != b->typeName())
      return fail(path + ": type " + a->typeName() + " vs " + b->typeName());
    if (a->defName != b->defName || a->protoName() != b->protoName() ||
        a->unresolved != b->unresolved)
      return fail(path + ": DEF/PROTO name or resolution differs");
    if (where(a->location) != where(b->location))
      return fail(path + ": location " + where(a->location) + " vs " + where(b->location));
    if (a->fieldCount() != b->fieldCount()) return fail(path + ": field count differs");
    for (std::size_t i = 0; i < a->fieldCount(); ++i)
      if (!values(a->fieldAt(i), b->fieldAt(i),
                  path + "/" + a->typeName() + "." + a->type().fields[i].name))
        return false;
    return true;
  }

  bool values(const FieldValue& a, const FieldValue& b, const std::string& path) {
    if (a.type() != b.type()) return fail(path + ": field type differs");
    if (a.type() == FieldType::SFNode)
      return nodes(a.get<FieldType::SFNode>(), b.get<FieldType::SFNode>(), path);
    if (a.type() == FieldType::MFNode) {
      const auto& x = a.get<FieldType::MFNode>();
      const auto& y = b.get<FieldType::MFNode>();
      if (x.size() != y.size()) return fail(path + ": MFNode sizes differ");
      for (std::size_t i = 0; i < x.size(); ++i)
        if (!nodes(x[i], y[i], path + "[" + std::to_string(i) + "]")) return false;
      return true;
    }
    // Every other alternative has == (glm vectors, std::vector of them, SFImage, ...).
    return a.storage() == b.storage() || fail(path + ": values differ");
  }

  bool scenes(const Scene& a, const Scene& b) {
    if (a.diagnostics.items.size() != b.diagnostics.items.size())
      return fail("diagnostic count " + std::to_string(a.diagnostics.items.size()) + " vs " +
                  std::to_string(b.diagnostics.items.size()));
    for (std::size_t i = 0; i < a.diagnostics.items.size(); ++i) {
      const Diagnostic& x = a.diagnostics.items[i];
      const Diagnostic& y = b.diagnostics.items[i];
      if (x.format() != y.format()) return fail("diagnostic " + x.format() + " vs " + y.format());
    }
    if (a.rootNodes.size() != b.rootNodes.size())
      return fail("root node count " + std::to_string(a.rootNodes.size()) + " vs " +
                  std::to_string(b.rootNodes.size()));
    for (std::size_t i = 0; i < a.rootNodes.size(); ++i)
      if (!nodes(a.rootNodes[i], b.rootNodes[i], "root[" + std::to_string(i) + "]")) return false;
    if (a.hiddenNodes.size() != b.hiddenNodes.size()) return fail("hidden node count differs");
    for (std::size_t i = 0; i < a.hiddenNodes.size(); ++i)
      if (!nodes(a.hiddenNodes[i], b.hiddenNodes[i], "hidden[" + std::to_string(i) + "]"))
        return false;
    if (a.routes.size() != b.routes.size())
      return fail("route count " + std::to_string(a.routes.size()) + " vs " +
                  std::to_string(b.routes.size()));
    for (std::size_t i = 0; i < a.routes.size(); ++i) {
      const Route& x = a.routes[i];
      const Route& y = b.routes[i];
      if (x.fromField != y.fromField || x.toField != y.toField ||
          where(x.location) != where(y.location) || !x.fromNode || !y.fromNode ||
          x.fromNode->typeName() != y.fromNode->typeName() ||
          x.toNode->typeName() != y.toNode->typeName())
        return fail("route " + std::to_string(i) + " differs");
    }
    if (a.protos.size() != b.protos.size()) return fail("PROTO count differs");
    for (std::size_t i = 0; i < a.protos.size(); ++i)
      if (a.protos[i]->name != b.protos[i]->name ||
          a.protos[i]->fields.size() != b.protos[i]->fields.size())
        return fail("PROTO " + a.protos[i]->name + " differs");
    return true;
  }
};

/// Empty when the scenes match; else the first difference.
std::string difference(const Scene& a, const Scene& b) {
  Comparer c;
  c.scenes(a, b);
  return c.diff;
}

// ---- feeding -----------------------------------------------------------------------------

/// Splits of `n` bytes: chunk sizes, in order.
using Splitter = std::function<std::vector<std::size_t>(std::size_t n)>;

Splitter fixed(std::size_t size) {
  return [size](std::size_t n) {
    std::vector<std::size_t> out;
    for (std::size_t at = 0; at < n; at += size) out.push_back(std::min(size, n - at));
    return out;
  };
}

Splitter randomSizes(unsigned seed, std::size_t maxChunk) {
  return [seed, maxChunk](std::size_t n) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<std::size_t> size(1, maxChunk);
    std::vector<std::size_t> out;
    for (std::size_t at = 0; at < n;) {
      const std::size_t k = std::min(size(rng), n - at);
      out.push_back(k);
      at += k;
    }
    return out;
  };
}

struct Streamed {
  Scene scene;
  std::size_t added = 0;      // what feed() and finish() returned, summed
  std::size_t callbacks = 0;  // onRootNode calls
};

Streamed stream(const std::string& bytes, const std::string& url, const Splitter& split,
                ParseOptions options = {}) {
  Streamed r;
  options.onRootNode = [&r](const NodePtr&) { ++r.callbacks; };
  StreamingParser p(url, options);
  std::size_t at = 0;
  for (std::size_t k : split(bytes.size())) {
    r.added += p.feed(std::string_view(bytes).substr(at, k));
    at += k;
  }
  r.added += p.finish();
  CHECK(p.done());
  r.scene = p.takeScene();
  return r;
}

struct NamedSplit {
  std::string name;
  Splitter split;
};

std::vector<NamedSplit> standardSplits(std::size_t size, std::size_t oneByteUpTo) {
  std::vector<NamedSplit> s = {
      {"whole", [](std::size_t n) { return std::vector<std::size_t>{n}; }},
      {"7-byte", fixed(7)},
      {"4096-byte", fixed(4096)},
      {"random 1..300", randomSizes(12345, 300)},
      {"random 1..9000", randomSizes(777, 9000)},
  };
  if (size <= oneByteUpTo) s.push_back({"1-byte", fixed(1)});
  return s;
}

/// Checks every split of `bytes` (gzip or not) against parseVrml of the same bytes.
void checkEquivalent(const std::string& bytes, const std::string& url,
                     const std::vector<NamedSplit>& splits, const ParseOptions& options = {}) {
  ParseOptions counting = options;
  std::size_t expectedCallbacks = 0;
  counting.onRootNode = [&](const NodePtr&) { ++expectedCallbacks; };
  const Scene expected = parseVrml(bytes, url, counting);
  for (const NamedSplit& s : splits) {
    INFO(url << " fed " << s.name);
    const Streamed got = stream(bytes, url, s.split, options);
    CHECK(difference(got.scene, expected) == "");
    CHECK(got.added == expected.rootNodes.size());
    CHECK(got.callbacks == expectedCallbacks);
  }
}

std::vector<fs::path> projectWorlds() {
  std::vector<fs::path> files =
      gs::test::filesWithSuffix(gs::test::sourceDir() / "tests/data/vrml", ".wrl");
  for (const fs::path& p : gs::test::filesWithSuffix(gs::test::sourceDir() / "assets", ".wrl"))
    files.push_back(p);
  return files;
}

}  // namespace

TEST_CASE("streaming: the comparison helper sees differences", "[streaming]") {
  const Scene a = gs::test::parse("Transform { translation 1 2 3 children Shape {} }\n");
  const Scene b = gs::test::parse("Transform { translation 1 2 4 children Shape {} }\n");
  const Scene c = gs::test::parse("Transform { translation 1 2 3 children Group {} }\n");
  const Scene d = gs::test::parse("Transform { translation 1 2 3 children Shape {} } Foo {}\n");
  CHECK(difference(a, a) == "");
  CHECK(difference(a, gs::test::parse("Transform { translation 1 2 3 children Shape {} }\n")) ==
        "");
  CHECK(difference(a, b) != "");
  CHECK(difference(a, c) != "");
  CHECK(difference(a, d) != "");  // a diagnostic more
}

TEST_CASE("streaming: project worlds in any split equal parseVrml", "[streaming]") {
  const std::vector<fs::path> files = projectWorlds();
  REQUIRE(files.size() >= 12);
  for (const fs::path& f : files) {
    const std::string bytes = readAll(f);
    REQUIRE(!bytes.empty());
    checkEquivalent(bytes, f.string(), standardSplits(bytes.size(), 1 << 20));
    checkEquivalent(gzip(bytes), f.string(), standardSplits(bytes.size(), 1 << 20));
  }
}

TEST_CASE("streaming: corpus worlds in any split equal parseVrml", "[heavy][streaming][corpus]") {
  if (!gs::test::haveCorpus("vrml/castle") || !gs::test::haveCorpus("vrml/openvrml")) return;
  std::vector<fs::path> files =
      gs::test::filesWithSuffix(gs::test::corpusDir() / "vrml/castle", ".wrl");
  for (const fs::path& p :
       gs::test::filesWithSuffix(gs::test::corpusDir() / "vrml/openvrml", ".wrl"))
    files.push_back(p);
  CHECK(files.size() > 50);
  std::size_t gz = 0;
  for (const fs::path& f : files) {
    const std::string bytes = readAll(f);
    checkEquivalent(bytes, f.string(), standardSplits(bytes.size(), 64 << 10));
    // Some of them gzip-compressed (as .wrz files are), byte by byte and in random sizes.
    if (bytes.size() < (32 << 10) && gz++ % 4 == 0)
      checkEquivalent(gzip(bytes), f.string(),
                      {{"gzip 1-byte", fixed(1)}, {"gzip random", randomSizes(99, 500)}});
  }
  CHECK(gz > 5);
}

TEST_CASE("streaming: gzip corpus files and a large world in 64 KiB chunks",
          "[streaming][corpus]") {
  if (!gs::test::haveCorpus("vrml/kicad")) return;
  const fs::path dir = gs::test::corpusDir() / "vrml/kicad";
  // Stored .wrz / .wrl.gz worlds when the corpus has any, else gzip made here.
  std::vector<fs::path> stored = gs::test::filesWithSuffix(gs::test::corpusDir() / "vrml", ".wrz");
  for (const fs::path& p : gs::test::filesWithSuffix(gs::test::corpusDir() / "vrml", ".wrl.gz"))
    stored.push_back(p);
  for (const fs::path& p : stored) {
    const std::string bytes = readAll(p);
    checkEquivalent(bytes, p.string(), {{"64 KiB", fixed(64 << 10)}, {"7-byte", fixed(7)}});
  }
  const std::vector<fs::path> files = gs::test::filesWithSuffix(dir, ".wrl");
  REQUIRE(files.size() > 10);
  fs::path largest = files.front();
  for (const fs::path& f : files)
    if (fs::file_size(f) > fs::file_size(largest)) largest = f;
  REQUIRE(fs::file_size(largest) > (1 << 20));
  const std::string big = readAll(largest);
  const std::vector<NamedSplit> chunks = {{"64 KiB", fixed(64 << 10)},
                                          {"random 1..64 KiB", randomSizes(5, 64 << 10)}};
  checkEquivalent(big, largest.string(), chunks);
  checkEquivalent(gzip(big), largest.string(), chunks);
  // A few smaller models in every split, compressed too.
  for (std::size_t i = 0; i < files.size(); i += files.size() / 4) {
    const std::string bytes = readAll(files[i]);
    checkEquivalent(bytes, files[i].string(), standardSplits(bytes.size(), 0));
    checkEquivalent(gzip(bytes), files[i].string(),
                    {{"gzip 4096", fixed(4096)}, {"gzip random", randomSizes(3, 2000)}});
  }
}

TEST_CASE("streaming: completed statements show at once, cut ones wait", "[streaming]") {
  const std::string s1 = "Shape { geometry Box { size 1 1 1 } }\n";
  const std::string s2 = "Shape { geometry Box { size 2 2 2 } }\n";
  const std::string s3 = "Shape { geometry Sphere { radius 3 } }\n";
  const std::string text = "#VRML V2.0 utf8\n" + s1 + s2 + s3;
  std::vector<NodePtr> seen;
  ParseOptions options;
  options.onRootNode = [&](const NodePtr& n) { seen.push_back(n); };
  StreamingParser p("w.wrl", options);
  // Up to the first Shape's '}': it shows at once.
  const std::size_t first = 16 + s1.size() - 1;
  CHECK(p.feed(std::string_view(text).substr(0, first)) == 1);
  CHECK(p.scene().rootNodes.size() == 1);
  CHECK(seen.size() == 1);
  // On to the middle of the second: it waits.
  const std::size_t cut = 16 + s1.size() + s2.size() / 2;
  CHECK(p.feed(std::string_view(text).substr(first, cut - first)) == 0);
  CHECK(p.scene().rootNodes.size() == 1);
  CHECK(seen.size() == 1);
  CHECK(p.scene().diagnostics.items.empty());
  CHECK(p.textBytes() == cut);
  CHECK(p.parsedBytes() == 16 + s1.size() - 1);  // up to the first Shape's '}'
  CHECK_FALSE(p.done());
  // The rest, ending in a newline: all three are complete before finish().
  CHECK(p.feed(std::string_view(text).substr(cut)) == 2);
  CHECK(p.scene().rootNodes.size() == 3);
  CHECK(seen.size() == 3);
  CHECK(p.finish() == 0);
  CHECK(p.done());
  REQUIRE(seen.size() == 3);
  for (std::size_t i = 0; i < 3; ++i) CHECK(seen[i] == p.scene().rootNodes[i]);
  CHECK(p.scene().rootNodes[2]->sfnode("geometry")->typeName() == "Sphere");
}

TEST_CASE("streaming: a number cut mid-token is never read short", "[streaming]") {
  const std::string head = "#VRML V2.0 utf8\nTransform { translation 1.2";
  const std::string tail = "5 0 0 }\nTransform { translation 7 0 0 }\n";
  StreamingParser p("n.wrl");
  CHECK(p.feed(head) == 0);
  CHECK(p.scene().rootNodes.empty());
  CHECK(p.parsedBytes() < p.textBytes());
  CHECK(p.feed(tail) == 2);
  CHECK(p.finish() == 0);
  const Scene& s = p.scene();
  REQUIRE(s.rootNodes.size() == 2);
  CHECK(s.diagnostics.items.empty());
  CHECK(s.rootNodes[0]->get<FieldType::SFVec3f>("translation", glm::vec3(0)).x == 1.25f);
  // The same cut inside an MF list and an integer, fed one byte at a time after the cut.
  const std::string list =
      "#VRML V2.0 utf8\nShape { geometry IndexedFaceSet { coord Coordinate { point [ 0 0 0, "
      "1.25 0 0, 0 1.5 0 ] } coordIndex [ 0 1 2 -1 ] } }\n";
  for (std::size_t cut = 17; cut < list.size(); cut += 3) {
    StreamingParser q("l.wrl");
    q.feed(std::string_view(list).substr(0, cut));
    for (std::size_t i = cut; i < list.size(); ++i) q.feed(std::string_view(list).substr(i, 1));
    q.finish();
    INFO("cut at " << cut);
    CHECK(difference(q.scene(), parseVrml(list, "l.wrl")) == "");
  }
}

TEST_CASE("streaming: a name cut mid-token is never read short", "[streaming]") {
  // A ROUTE or USE ends with a name: read short it would still make a whole statement.
  const std::string text =
      "#VRML V2.0 utf8\nDEF Thing Transform {}\nROUTE Thing.translation_changed TO "
      "Thing.set_translation\nUSE Thing\n";
  const Scene expected = parseVrml(text, "id.wrl");
  REQUIRE(expected.diagnostics.items.empty());
  REQUIRE(expected.routes.size() == 1);
  for (const char* cutAfter : {"Thing.set_tr", "USE Th"}) {
    INFO("cut after " << cutAfter);
    const std::size_t cut = text.find(cutAfter) + std::string_view(cutAfter).size();
    StreamingParser p("id.wrl");
    p.feed(std::string_view(text).substr(0, cut));
    CHECK(p.scene().diagnostics.items.empty());
    p.feed(std::string_view(text).substr(cut));
    p.finish();
    CHECK(difference(p.scene(), expected) == "");
  }
}

TEST_CASE("streaming: decisions on how much text is left wait for the rest", "[streaming]") {
  // The SFImage claims 16 pixels: with the whole text there is room for them (and the
  // error is the '}' where a pixel should be); the text up to the first statement's end
  // alone has too little room, which must not decide.
  std::string text =
      "#VRML V2.0 utf8\nShape { appearance Appearance { texture PixelTexture { image 4 4 1 0 0 "
      "} } }\n";
  const std::size_t cut = text.size();
  for (int i = 0; i < 5; ++i) text += "Shape { geometry Box { size 1 2 3 } }\n";
  const Scene expected = parseVrml(text, "img.wrl");
  REQUIRE(expected.diagnostics.items.size() == 1);
  CHECK(expected.diagnostics.items[0].message.find("expected an integer") != std::string::npos);
  const Streamed got = stream(text, "img.wrl", [cut](std::size_t n) {
    return std::vector<std::size_t>{cut, n - cut};
  });
  CHECK(difference(got.scene, expected) == "");
  // A string cut after a space, in a value that is skipped (unknown field) and read.
  const std::string strings =
      "#VRML V2.0 utf8\nWorldInfo { bogus \"a b c d\" title \"x y z\" }\nGroup {}\n";
  for (const char* cutAfter : {"\"a b ", "\"x y "}) {
    const std::size_t at = strings.find(cutAfter) + std::string_view(cutAfter).size();
    INFO("cut after " << cutAfter);
    CHECK(difference(stream(strings, "s.wrl",
                            [at](std::size_t n) {
                              return std::vector<std::size_t>{at, n - at};
                            })
                         .scene,
                     parseVrml(strings, "s.wrl")) == "");
  }
}

TEST_CASE("streaming: names persist across chunks; undone statements leave none", "[streaming]") {
  SECTION("DEF in one chunk, USE in a later one") {
    StreamingParser p("d.wrl");
    p.feed("#VRML V2.0 utf8\nDEF S Shape { geometry Box {} }\n");
    REQUIRE(p.scene().rootNodes.size() == 1);
    p.feed("Transform { children [ USE S ] }\n");
    p.finish();
    const Scene& s = p.scene();
    CHECK(s.diagnostics.items.empty());
    REQUIRE(s.rootNodes.size() == 2);
    REQUIRE(s.rootNodes[1]->mfnode("children").size() == 1);
    CHECK(s.rootNodes[1]->mfnode("children")[0] == s.rootNodes[0]);
  }
  SECTION("a PROTO declared early, instanced later") {
    StreamingParser p("p.wrl");
    p.feed("#VRML V2.0 utf8\nPROTO Cube [ field SFVec3f size 1 1 1 ] { Box { size IS size } }\n");
    CHECK(p.scene().protos.size() == 1);
    p.feed("Shape { geometry Cube { size 2 3 4 } }\n");
    p.finish();
    const Scene& s = p.scene();
    CHECK(s.diagnostics.items.empty());
    REQUIRE(s.rootNodes.size() == 1);
    const NodePtr g = s.rootNodes[0]->sfnode("geometry");
    REQUIRE(g);
    CHECK(g->typeName() == "Box");
    CHECK(g->protoName() == "Cube");
    CHECK(g->get<FieldType::SFVec3f>("size", glm::vec3(0)) == glm::vec3(2, 3, 4));
  }
  SECTION("a DEF, PROTO and ROUTE of a statement cut short are undone") {
    // The Group is cut just before its '}': it runs whole (two ROUTEs, DEF B, DEF A again,
    // DEF P, PROTO Inner) and is undone. Its retries must see none of that: USE B and
    // Inner are still unknown at their places, A is still the Transform for the first
    // ROUTE, and each ROUTE is stored once.
    const std::string text =
        "#VRML V2.0 utf8\n"
        "DEF A Transform {}\n"
        "Group {\n"
        "  ROUTE A.translation_changed TO A.set_translation\n"
        "  children [ Shape { geometry USE B } Inner {} Shape { geometry DEF B Box {} }\n"
        "             DEF A TimeSensor {} DEF P PositionInterpolator {} ]\n"
        "  PROTO Inner [] { Group {} }\n"
        "  ROUTE A.fraction_changed TO P.set_fraction\n"
        "}\n"
        "ROUTE A.fraction_changed TO P.set_fraction\n"
        "Inner {}\n";
    const Scene expected = parseVrml(text, "r.wrl");
    REQUIRE(expected.rootNodes.size() == 3);
    REQUIRE(expected.routes.size() == 3);
    REQUIRE(expected.protos.size() == 1);
    REQUIRE(expected.diagnostics.items.size() == 2);
    CHECK(expected.diagnostics.items[0].message == "USE of unknown DEF name 'B'");
    CHECK(expected.diagnostics.items[1].message == "unknown node type 'Inner'");
    const std::size_t cut = text.find("}\nROUTE");
    StreamingParser p("r.wrl");
    CHECK(p.feed(std::string_view(text).substr(0, cut)) == 1);
    CHECK(p.scene().rootNodes.size() == 1);
    CHECK(p.scene().routes.empty());
    CHECK(p.scene().protos.empty());
    CHECK(p.scene().diagnostics.items.empty());
    // Every byte of the rest on its own: the Group is retried and undone again.
    for (std::size_t i = cut; i < text.size(); ++i) p.feed(std::string_view(text).substr(i, 1));
    p.finish();
    CHECK(p.scene().routes.size() == 3);
    CHECK(difference(p.scene(), expected) == "");
  }
}

TEST_CASE("streaming: finish() after a truncated text reports as parseVrml does", "[streaming]") {
  std::vector<std::pair<std::string, std::string>> texts;
  for (const fs::path& f : projectWorlds()) texts.emplace_back(f.string(), readAll(f));
  texts.emplace_back(
      "strings.wrl",
      "#VRML V2.0 utf8\n# a comment\nWorldInfo { info [ \"one\" \"two, \\\" three\" ] "
      "title \"t\" }\nDEF X Transform { children Shape { geometry Text { string "
      "\"abc def\" } } }\nROUTE X.translation_changed TO X.set_translation\n");
  for (const auto& [url, text] : texts) {
    // Half the text, and a few more cut points (inside strings, comments, numbers).
    std::vector<std::size_t> cuts = {text.size() / 2, text.size() / 3, text.size() * 3 / 4};
    for (std::size_t c = 17; c < text.size(); c += std::max<std::size_t>(1, text.size() / 23))
      cuts.push_back(c);
    for (std::size_t cut : cuts) {
      const std::string part = text.substr(0, cut);
      INFO(url << " cut at " << cut);
      const Scene expected = parseVrml(part, url);
      CHECK(difference(stream(part, url, fixed(5)).scene, expected) == "");
      CHECK(difference(stream(part, url, fixed(1 << 20)).scene, expected) == "");
    }
  }
  // A cut in the middle of a node gives the end-of-file error of parseVrml.
  const std::string half = "#VRML V2.0 utf8\nShape { geometry Box { size 1 2 3 ";
  const Streamed r = stream(half, "h.wrl", fixed(3));
  REQUIRE(r.scene.diagnostics.items.size() == 1);
  CHECK(r.scene.diagnostics.items[0].message.starts_with("unexpected end of file"));
  CHECK(difference(r.scene, parseVrml(half, "h.wrl")) == "");
}

TEST_CASE("streaming: line ends of any kind give parseVrml's locations", "[streaming]") {
  std::string base =
      "#VRML V2.0 utf8\nShape { geometry Box { size 1 1 1 } }\nFoo { }\n"
      "Shape { appearance Appearance { material Material { bogus 1 } } }\n"
      "Transform { translation 1 2 3 children [ Bar {} ] }\nUSE Nope\n"
      "Shape { geometry Sphere { radius 2 } }\n";
  for (const std::string& eol : {std::string("\r\n"), std::string("\r"), std::string("\n\r")}) {
    std::string text;
    for (char c : base) text += c == '\n' ? eol : std::string(1, c);
    // A lone CR late in an otherwise CR LF file switches the line counting midway.
    std::string mixed = text;
    if (eol == "\r\n") mixed += "Group {}\rBaz {}\r\nQux {}\r\n";
    for (const std::string& t : {text, mixed}) {
      const Scene expected = parseVrml(t, "eol.wrl");
      REQUIRE(expected.diagnostics.items.size() >= 3);
      checkEquivalent(t, "eol.wrl",
                      {{"1-byte", fixed(1)}, {"2-byte", fixed(2)}, {"random", randomSizes(7, 9)}});
    }
  }
}

TEST_CASE("streaming: corrupt gzip and other headers give parseVrml's errors", "[streaming]") {
  const std::string text =
      "#VRML V2.0 utf8\nShape { geometry Box {} }\nShape { geometry Cone {} }\n";
  const std::string gz = gzip(text);
  SECTION("damaged gzip header") {
    std::string bad = gz;
    bad[2] = 7;  // compression method
    const Scene expected = parseVrml(bad, "bad.wrz");
    REQUIRE(expected.diagnostics.items.size() == 1);
    CHECK(expected.diagnostics.items[0].message.starts_with("corrupt gzip data"));
    for (std::size_t k : {1u, 3u, 1000u}) {
      INFO("chunks of " << k);
      StreamingParser p("bad.wrz");
      std::size_t added = 0;
      for (std::size_t at = 0; at < bad.size(); at += k)
        added += p.feed(std::string_view(bad).substr(at, k));
      CHECK(p.done());
      CHECK(added == 0);
      p.finish();
      CHECK(difference(p.scene(), expected) == "");
    }
  }
  SECTION("truncated, damaged and padded gzip data") {
    const std::string truncated = gz.substr(0, gz.size() - 5);
    std::string damaged = gz;
    damaged[gz.size() - 3] ^= 0x55;  // the length in the trailer
    std::string garbage = gz + "xy";
    std::string lone = gz + "\x1f";
    std::string padded = gz + std::string(4, '\0');
    std::string twice = gz + gzip("Shape { geometry Sphere {} }\n");
    const std::vector<std::string> cases = {truncated, damaged, garbage, lone, padded, twice};
    for (std::size_t c = 0; c < cases.size(); ++c) {
      const Scene expected = parseVrml(cases[c], "g.wrz");
      for (std::size_t k : {1u, 10u, 100000u}) {
        const Streamed got = stream(cases[c], "g.wrz", fixed(k));
        INFO("case " << c << " chunks of " << k);
        if (c >= 4) {  // padded, two members: fine
          CHECK(difference(got.scene, expected) == "");
          CHECK(got.scene.rootNodes.size() == (c == 5 ? 3u : 2u));
          continue;
        }
        // The nodes complete before the damage showed; the error is parseVrml's.
        REQUIRE(expected.diagnostics.items.size() == 1);
        REQUIRE(!got.scene.diagnostics.items.empty());
        CHECK(got.scene.diagnostics.items.back().format() ==
              expected.diagnostics.items[0].format());
        CHECK(got.scene.diagnostics.errorCount() == 1);
      }
    }
  }
  SECTION("VRML 1.0 and other headers") {
    for (const std::string& t :
         {std::string("#VRML V1.0 ascii\nSeparator { Cube {} }\n"),
          std::string("\xEF\xBB\xBF#VRML V2.0 utf8\nShape { geometry Box {} }\n"),
          std::string("#VRML V2.0 utf8"), std::string("#X3D V3.0 utf8\r\nShape {}\r\n"),
          std::string("\x1f"), std::string(""),
          std::string("#VRML V2.0 utf8 but a very long first line that goes on and on\n")}) {
      INFO(t);
      const Scene expected = parseVrml(t, "h.wrl");
      for (std::size_t k : {1u, 2u, 100u}) {
        CHECK(difference(stream(t, "h.wrl", fixed(k)).scene, expected) == "");
        if (!t.empty()) CHECK(difference(stream(gzip(t), "h.wrl", fixed(k)).scene, expected) == "");
      }
    }
    StreamingParser p("v1.wrl");
    p.feed("#VRML V1.0 ascii\n");
    CHECK(p.done());
    REQUIRE(p.scene().diagnostics.items.size() == 1);
    CHECK(p.scene().diagnostics.items[0].message == "VRML 1.0 is not supported");
  }
  SECTION("input over ParseLimits::maxInputBytes") {
    ParseOptions o;
    o.limits.maxInputBytes = 40;
    const Scene expected = parseVrml(text, "big.wrl", o);
    CHECK(difference(stream(text, "big.wrl", fixed(3), o).scene, expected) == "");
    const Scene expectedGz = parseVrml(gz, "big.wrl", o);
    CHECK(difference(stream(gz, "big.wrl", fixed(3), o).scene, expectedGz) == "");
  }
}

TEST_CASE("streaming: a fatal error stops the parse; later bytes are ignored", "[streaming]") {
  ParseOptions o;
  o.limits.maxNesting = 4;
  const std::string text =
      "#VRML V2.0 utf8\nShape { geometry Box {} }\n"
      "Group { children Group { children Group { children Group { children Group {} } } } }\n"
      "Shape { geometry Sphere {} }\n";
  const Scene expected = parseVrml(text, "f.wrl", o);
  REQUIRE(expected.rootNodes.size() == 1);
  REQUIRE(expected.diagnostics.items.size() == 1);
  CHECK(expected.diagnostics.items[0].message.find("maxNesting") != std::string::npos);
  for (std::size_t k : {1u, 4u, 64u, 100000u}) {
    INFO("chunks of " << k);
    StreamingParser p("f.wrl", o);
    bool stoppedEarly = false;
    for (std::size_t at = 0; at < text.size(); at += k) {
      p.feed(std::string_view(text).substr(at, k));
      stoppedEarly = stoppedEarly || (p.done() && at + k < text.size());
    }
    CHECK((stoppedEarly || k >= text.size()));
    CHECK(p.done());
    CHECK(p.feed("Shape { geometry Cone {} }\nShape {}\n") == 0);
    CHECK(p.finish() == 0);
    CHECK(difference(p.scene(), expected) == "");
  }
  // "Too many errors" ends the parse the same way.
  std::string many = "#VRML V2.0 utf8\n";
  for (int i = 0; i < 1100; ++i) many += "Foo" + std::to_string(i) + " { }\n";
  many += "Shape {}\n";
  checkEquivalent(many, "many.wrl", {{"97-byte", fixed(97)}, {"whole", fixed(1 << 20)}});
  CHECK(parseVrml(many, "many.wrl").diagnostics.items.back().message.find("giving up") !=
        std::string::npos);
}

TEST_CASE("streaming: EXTERNPROTO files load once, with their diagnostics", "[streaming]") {
  // The library file has a diagnostic of its own; the instance sits in a statement that
  // is cut and undone many times, and the file is referenced again later.
  const fs::path dir = fs::temp_directory_path() / "gs_streaming_extern";
  fs::create_directories(dir);
  {
    std::ofstream lib(dir / "lib.wrl", std::ios::binary);
    lib << "#VRML V2.0 utf8\nPROTO Ball [ field SFFloat r 1 ] { Sphere { radius IS r } }\n"
           "Nope {}\n";
  }
  const std::string text =
      "#VRML V2.0 utf8\n"
      "Group {\n"
      "  EXTERNPROTO Ball [ field SFFloat r ] \"lib.wrl#Ball\"\n"
      "  children [ Shape { geometry Ball { r 2 } } Shape { geometry Box { size 1 2 3 } } ]\n"
      "}\n"
      "EXTERNPROTO Ball2 [ field SFFloat r ] \"lib.wrl#Ball\"\n"
      "Shape { geometry Ball2 { r 3 } }\n";
  const std::string url = (dir / "main.wrl").string();
  const Scene expected = parseVrml(text, url);
  REQUIRE(expected.rootNodes.size() == 2);
  REQUIRE(expected.diagnostics.items.size() == 1);  // from lib.wrl
  CHECK(expected.diagnostics.items[0].location.file.ends_with("lib.wrl"));
  REQUIRE(expected.rootNodes[1]->sfnode("geometry"));
  CHECK(expected.rootNodes[1]->sfnode("geometry")->typeName() == "Sphere");
  checkEquivalent(text, url, {{"1-byte", fixed(1)}, {"3-byte", fixed(3)}, {"whole", fixed(4096)}});
  fs::remove_all(dir);
}

TEST_CASE("streaming: feeding byte by byte costs amortized linear time", "[streaming]") {
  // One large top-level statement: without the retry rule each byte would re-parse it.
  std::string text =
      "#VRML V2.0 utf8\nShape { geometry IndexedFaceSet { coord Coordinate { point [\n";
  for (int i = 0; i < 20000; ++i) text += std::to_string(i) + ".5 1.25 -3.75,\n";
  text += "] } } }\n";
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const Scene expected = parseVrml(text, "big.wrl");
  const auto t1 = Clock::now();
  const Streamed got = stream(text, "big.wrl", fixed(1));
  const auto t2 = Clock::now();
  CHECK(difference(got.scene, expected) == "");
  const double whole = std::chrono::duration<double>(t1 - t0).count();
  const double bytewise = std::chrono::duration<double>(t2 - t1).count();
  INFO("parseVrml " << whole << " s, byte by byte " << bytewise << " s for " << text.size()
                    << " bytes");
  CHECK(bytewise < 200 * whole + 1.0);
}

TEST_CASE("StreamingParser: a statement waits for its EXTERNPROTO file, no feed does",
          "[parser][streaming][proto]") {
  const std::string world =
      "#VRML V2.0 utf8\n"
      "Group { }\n"
      "EXTERNPROTO Ball [ field SFFloat r ] \"lib.wrl#Ball\"\n"
      "Shape { geometry Ball { r 2 } }\n"
      "Transform { }\n";
  int asked = 0;
  bool arrived = false;
  std::vector<gs::base::FetchMode> modes;
  gs::base::CallbackFetcher fetcher(
      [&](const std::string& url, const std::string& referrer, gs::base::FetchMode mode) {
        ++asked;
        modes.push_back(mode);
        CHECK(url == "http://h.org/lib.wrl");
        CHECK(referrer == "http://h.org/world.wrl");
        if (!arrived) return gs::base::Fetched{gs::base::FetchState::pending, {}, {}};
        return gs::base::fetchReady(
            "#VRML V2.0 utf8\nPROTO Ball [ field SFFloat r 1 ] { Sphere { radius IS r } }\n");
      });
  ParseOptions options;
  options.fetcher = &fetcher;
  options.externProtosInBackground = true;

  SECTION("the file arrives: the statements after it join in file order") {
    StreamingParser parser("http://h.org/world.wrl", options);
    CHECK(parser.feed(world) == 1);  // the Group; the EXTERNPROTO waits, and all after it
    CHECK(parser.waitingForExternProto());
    CHECK(asked == 1);
    CHECK(parser.feed({}) == 0);  // still on its way: retried, nothing added
    CHECK(asked == 2);
    arrived = true;
    CHECK(parser.feed({}) == 2);
    CHECK_FALSE(parser.waitingForExternProto());
    parser.finish();
    const Scene& s = parser.scene();
    CHECK(s.diagnostics.items.empty());
    REQUIRE(s.rootNodes.size() == 3);
    const NodePtr ball = s.rootNodes[1]->sfnode("geometry");
    REQUIRE(ball);
    CHECK(ball->protoName() == "Ball");
    CHECK_FALSE(ball->unresolved);
    CHECK(modes == std::vector<gs::base::FetchMode>(3, gs::base::FetchMode::background));
    // The same scene as a whole parse with the file at hand (which reads it whole).
    const Scene whole = parseVrml(world, "http://h.org/world.wrl", options);
    CHECK(modes.back() == gs::base::FetchMode::whole);
    CHECK(difference(s, whole) == "");
  }
  SECTION("the world ends first: finish() does not wait, the EXTERNPROTO fails") {
    StreamingParser parser("http://h.org/world.wrl", options);
    parser.feed(world);
    parser.finish();
    const Scene& s = parser.scene();
    CHECK(s.rootNodes.size() == 3);
    REQUIRE(s.diagnostics.items.size() == 1);
    CHECK(s.diagnostics.items[0].message.find("lib.wrl#Ball: still on its way") !=
          std::string::npos);
  }
}
