// PROTO, EXTERNPROTO and ROUTE (clauses 4.8, 4.9, 4.10): expansion, IS, scoping, checks.
#include "test_parser_support.hpp"

#include "vrml/proto.hpp"

#include <catch2/catch.hpp>

#include <string>

using namespace gs::vrml;
using gs::test::parse;

namespace {

std::string dataDir() {
  return (gs::test::sourceDir() / "tests/data/vrml").string();
}

Diagnostic onlyDiagnostic(const Scene& s) {
  REQUIRE(s.diagnostics.items.size() == 1);
  return s.diagnostics.items[0];
}

}  // namespace

TEST_CASE("PROTO instance: copy of the first body node with IS values", "[parser][proto]") {
  Scene s = parse(R"(
PROTO Ball [
  field SFFloat r 1
  exposedField SFColor c 1 1 1
  field SFNode extra NULL
] {
  Transform {
    children Shape {
      appearance Appearance { material Material { diffuseColor IS c } }
      geometry Sphere { radius IS r }
    }
  }
}
Ball { r 2 c 0 0 1 }
Ball { }
)");
  REQUIRE(s.diagnostics.items.empty());
  REQUIRE(s.rootNodes.size() == 2);
  REQUIRE(s.protos.size() == 1);
  CHECK(s.protos[0]->name == "Ball");
  REQUIRE(s.protos[0]->proto);
  CHECK(s.protos[0]->proto->connections.size() == 2);
  const Node& a = *s.rootNodes[0];
  CHECK(a.typeName() == "Transform");
  CHECK(a.protoName() == "Ball");
  CHECK(a.location.line == 15);
  auto shape = [](const Node& t) { return t.mfnode("children").at(0); };
  CHECK(shape(a)->sfnode("geometry")->get<FieldType::SFFloat>("radius", 0.0f) == 2.0f);
  CHECK(shape(a)
            ->sfnode("appearance")
            ->sfnode("material")
            ->get<FieldType::SFColor>("diffuseColor", glm::vec3(9)) == glm::vec3(0, 0, 1));
  const Node& b = *s.rootNodes[1];
  CHECK(shape(b)->sfnode("geometry")->get<FieldType::SFFloat>("radius", 0.0f) == 1.0f);
  CHECK(shape(b)
            ->sfnode("appearance")
            ->sfnode("material")
            ->get<FieldType::SFColor>("diffuseColor", glm::vec3(9)) == glm::vec3(1));
  // Each instance is its own copy; the template is untouched.
  CHECK(shape(a) != shape(b));
  CHECK(s.protos[0]
            ->proto->body[0]
            ->mfnode("children")[0]
            ->sfnode("geometry")
            ->get<FieldType::SFFloat>("radius", 0.0f) == 1.0f);
}

TEST_CASE("PROTO: DEF/USE sharing inside the copy, hidden body nodes, body ROUTEs",
          "[parser][proto]") {
  Scene s = parse(R"(
PROTO Pair [] {
  Group { children [ DEF X Shape {} Transform { children USE X } ] }
  DEF TS TimeSensor {}
  DEF SI ScalarInterpolator {}
  ROUTE TS.fraction_changed TO SI.set_fraction
}
Pair {}
Pair {}
)");
  REQUIRE(s.diagnostics.items.empty());
  REQUIRE(s.rootNodes.size() == 2);
  for (const NodePtr& g : s.rootNodes) {
    CHECK(g->mfnode("children")[0] == g->mfnode("children")[1]->mfnode("children")[0]);
  }
  CHECK(s.rootNodes[0]->mfnode("children")[0] != s.rootNodes[1]->mfnode("children")[0]);
  REQUIRE(s.hiddenNodes.size() == 4);
  CHECK(s.hiddenNodes[0]->typeName() == "TimeSensor");
  REQUIRE(s.routes.size() == 2);
  CHECK(s.routes[0].fromNode == s.hiddenNodes[0]);
  CHECK(s.routes[0].toNode == s.hiddenNodes[1]);
  CHECK(s.routes[1].fromNode == s.hiddenNodes[2]);
  CHECK(s.routes[0].fromField == "fraction_changed");
  CHECK(s.routes[0].toField == "set_fraction");
}

TEST_CASE("PROTO: nested instances pass IS values through", "[parser][proto]") {
  Scene s = parse(R"(
PROTO MatLib [ field SFNode mat NULL ] {
  Shape { appearance Appearance { material IS mat } geometry Sphere { } }
}
PROTO Yellow [ exposedField SFColor col 1 1 0  field SFFloat shine 0.5 ] {
  MatLib { mat Material { diffuseColor IS col shininess IS shine } }
}
PROTO Outer [ field SFColor c 0 1 0 ] {
  Yellow { col IS c }
}
Yellow { }
Yellow { col 1 0 1 }
Outer { }
Outer { c 0.5 0.5 0.5 }
)");
  REQUIRE(s.diagnostics.items.empty());
  REQUIRE(s.rootNodes.size() == 4);
  auto color = [](const NodePtr& shape) {
    return shape->sfnode("appearance")
        ->sfnode("material")
        ->get<FieldType::SFColor>("diffuseColor", glm::vec3(9));
  };
  CHECK(s.rootNodes[0]->typeName() == "Shape");
  CHECK(color(s.rootNodes[0]) == glm::vec3(1, 1, 0));
  CHECK(color(s.rootNodes[1]) == glm::vec3(1, 0, 1));
  CHECK(color(s.rootNodes[2]) == glm::vec3(0, 1, 0));
  CHECK(color(s.rootNodes[3]) == glm::vec3(0.5f));
  CHECK(s.rootNodes[3]->protoName() == "Outer");
}

TEST_CASE("PROTO scope: nested PROTOs are local, DEF names do not cross the body",
          "[parser][proto]") {
  Scene s = parse(R"(
DEF Outside Shape {}
PROTO Table [] {
  PROTO Leg [] { Shape {} }
  Group { children [ Leg {} Leg {} ] }
}
Table {}
Leg {}
PROTO Sees [] { Group { children USE Outside } }
)");
  REQUIRE(s.diagnostics.items.size() == 2);
  CHECK(s.diagnostics.items[0].message == "unknown node type 'Leg'");
  CHECK(s.diagnostics.items[0].location.line == 9);
  CHECK(s.diagnostics.items[1].message == "USE of unknown DEF name 'Outside'");
  CHECK(s.rootNodes.size() == 2);
  CHECK(s.rootNodes[1]->mfnode("children").size() == 2);
  // A PROTO declared inside a node of the file is visible after it (same scope).
  Scene v = parse(
      "Transform { PROTO Red [] { Material {} } } Shape { appearance Appearance { "
      "material Red {} } }");
  CHECK(v.diagnostics.items.empty());
}

TEST_CASE("PROTO field defaults: own DEF scope, may USE nodes of the file", "[parser][proto]") {
  Scene good = parse(R"(
DEF Y Material { diffuseColor 1 1 0 }
PROTO P [
  field MFNode two [ Group { children [ DEF G Group {} ] }, Group { children [ USE G ] } ]
  field SFNode app Appearance { material USE Y }
] { Shape { appearance IS app } }
P {}
)");
  CHECK(good.diagnostics.errorCount() == 0);
  REQUIRE(good.rootNodes.size() == 2);
  CHECK(good.rootNodes[1]->sfnode("appearance")->sfnode("material") == good.rootNodes[0]);

  Scene bad = parse(R"(
PROTO P [
  field SFNode a Group { children [ DEF G Group {} ] }
  field SFNode b Group { children [ USE G ] }
] { Group {} }
)");
  REQUIRE(bad.diagnostics.items.size() == 1);
  CHECK(bad.diagnostics.items[0].message == "USE of unknown DEF name 'G'");
  CHECK(bad.diagnostics.items[0].location.line == 5);
  CHECK(bad.diagnostics.items[0].location.column == 41);
}

TEST_CASE("PROTO checks: IS types and access, interface conflicts, eventIn values",
          "[parser][proto]") {
  SECTION("IS type mismatch") {
    const Diagnostic d = onlyDiagnostic(
        parse("PROTO P [ exposedField SFBool v TRUE ] {\n  Group { children IS v }\n}"));
    CHECK(d.message ==
          "IS type mismatch: 'children' of Group is MFNode but 'v' of PROTO P is SFBool");
    CHECK(d.location.line == 3);
    CHECK(d.location.column == 23);
  }
  SECTION("IS access: a field of the node cannot carry an exposedField") {
    const Diagnostic d =
        onlyDiagnostic(parse("PROTO P [ exposedField SFFloat r 1 ] { Sphere { radius IS r } }"));
    CHECK(d.message.find("IS access mismatch") == 0);
  }
  SECTION("IS access: an eventOut cannot be connected to an eventIn") {
    const Diagnostic d =
        onlyDiagnostic(parse("PROTO P [ eventIn SFBool e ] { TimeSensor { isActive IS e } }"));
    CHECK(d.message.find("IS access mismatch") == 0);
  }
  SECTION("IS to a name not in the interface") {
    const Diagnostic d = onlyDiagnostic(parse("PROTO P [] { Material { diffuseColor IS nope } }"));
    CHECK(d.message == "'nope' is not in the interface of PROTO 'P'");
  }
  SECTION("eventIn set_foo conflicts with exposedField foo") {
    const Diagnostic d = onlyDiagnostic(
        parse("PROTO P [ exposedField MFNode foo [] eventIn MFNode set_foo ] { Group {} }"));
    CHECK(d.message ==
          "eventIn 'set_foo' conflicts with exposedField 'foo' of PROTO P (clause 4.7)");
    CHECK(d.location.column == 53);
  }
  SECTION("eventOut foo_changed conflicts with exposedField foo") {
    const Diagnostic d = onlyDiagnostic(
        parse("PROTO P [ exposedField SFBool foo TRUE eventOut SFBool foo_changed ] { Group {} }"));
    CHECK(d.message.find("conflicts with exposedField 'foo'") != std::string::npos);
  }
  SECTION("a name declared twice") {
    const Diagnostic d =
        onlyDiagnostic(parse("PROTO P [ field SFBool a TRUE field SFInt32 a 1 ] { Group {} }"));
    CHECK(d.message == "'a' is declared twice in PROTO P");
  }
  SECTION("a value for an eventIn of a PROTO instance") {
    const Diagnostic d = onlyDiagnostic(parse(
        "PROTO P [ eventIn SFBool go field SFBool f TRUE ] { Group {} }\nP { go TRUE f FALSE }"));
    CHECK(d.message == "cannot give a value to eventIn 'go' of P");
    CHECK(d.location.line == 3);
    CHECK(d.location.column == 5);
  }
  SECTION("IS events of the node through exposedField aliases") {
    Scene s = parse(
        "PROTO P [ eventIn MFNode set_children eventOut MFNode children_changed ] {\n"
        "  Group { set_children IS set_children children_changed IS children_changed } }\nP {}");
    CHECK(s.diagnostics.items.empty());
    REQUIRE(s.protos.size() == 1);
    const auto& c = s.protos[0]->proto->connections;
    REQUIRE(c.size() == 2);
    CHECK(c[0].nodeAccess == AccessType::eventIn);
    CHECK(c[1].nodeAccess == AccessType::eventOut);
  }
  SECTION("an empty PROTO body") {
    Scene s = parse("PROTO E [] { }\nE {}\nGroup {}");
    REQUIRE(s.diagnostics.errorCount() == 1);
    CHECK(s.diagnostics.items[0].message == "PROTO 'E' has no node in its body");
    CHECK(s.rootNodes.size() == 1);
  }
}

TEST_CASE("ROUTE: checked and stored; PROTO interfaces are flattened", "[parser][route]") {
  Scene s = parse(R"(
DEF T Transform {}
DEF PI PositionInterpolator {}
DEF TS TimeSensor {}
ROUTE TS.fraction_changed TO PI.set_fraction
ROUTE PI.value_changed TO T.set_translation
ROUTE T.translation_changed TO T.translation
ROUTE TS.fraction TO PI.fraction
)");
  REQUIRE(s.diagnostics.items.empty());
  REQUIRE(s.routes.size() == 4);
  CHECK(s.routes[0].fromNode == s.rootNodes[2]);
  CHECK(s.routes[0].toNode == s.rootNodes[1]);
  CHECK(s.routes[0].location.line == 6);
  CHECK(s.routes[0].location.column == 1);
  CHECK(s.routes[1].toField == "set_translation");

  Scene p = parse(R"(
PROTO Mover [ eventIn SFFloat go exposedField SFVec3f where 0 0 0 ] {
  DEF T Transform { translation IS where }
  DEF I PositionInterpolator { set_fraction IS go }
}
DEF M Mover {}
DEF TS TimeSensor {}
ROUTE TS.fraction_changed TO M.go
ROUTE M.where_changed TO M.set_where
)");
  REQUIRE(p.diagnostics.items.empty());
  REQUIRE(p.routes.size() == 2);
  REQUIRE(p.hiddenNodes.size() == 1);
  CHECK(p.routes[0].toNode == p.hiddenNodes[0]);
  CHECK(p.routes[0].toField == "set_fraction");
  CHECK(p.routes[1].fromNode == p.rootNodes[0]);
  CHECK(p.routes[1].fromField == "translation");
}

TEST_CASE("ROUTE errors carry their place", "[parser][route]") {
  Scene s = parse(R"(
DEF T Transform {}
DEF TS TimeSensor {}
DEF S Switch {}
ROUTE Nobody.x TO T.set_translation
ROUTE TS.loop TO T.set_translation
ROUTE TS.isActive TO T.bboxCenter
ROUTE TS.isActive TO TS.isActive
ROUTE T.addChildren TO T.addChildren
ROUTE T.bboxSize TO T.set_scale
ROUTE TS.isActive TO S.whichChoice
ROUTE TS.isActive TO Nobody.x
ROUTE TS.nothing TO T.set_scale
)");
  const auto& d = s.diagnostics.items;
  REQUIRE(d.size() == 9);
  CHECK(s.routes.empty());
  for (const Diagnostic& x : d) CHECK(x.severity == Severity::error);
  CHECK(d[0].message == "ROUTE from unknown DEF name 'Nobody'");
  CHECK(d[0].location.line == 6);
  CHECK(d[0].location.column == 7);
  CHECK(d[1].message == "ROUTE type mismatch: TS.loop is SFBool but T.set_translation is SFVec3f");
  CHECK(d[1].location.line == 7);
  CHECK(d[1].location.column == 20);
  CHECK(d[2].message ==
        "ROUTE destination 'bboxCenter' of Transform is a field; it must be an "
        "eventIn or exposedField");
  CHECK(d[3].message ==
        "ROUTE destination 'isActive' of TimeSensor is an eventOut; it must be "
        "an eventIn or exposedField");
  CHECK(d[4].message ==
        "ROUTE source 'addChildren' of Transform is an eventIn; it must be an "
        "eventOut or exposedField");
  CHECK(d[4].location.column == 9);
  CHECK(d[5].message ==
        "ROUTE source 'bboxSize' of Transform is a field; it must be an "
        "eventOut or exposedField");
  CHECK(d[6].message == "ROUTE type mismatch: TS.isActive is SFBool but S.whichChoice is SFInt32");
  CHECK(d[7].message == "ROUTE to unknown DEF name 'Nobody'");
  CHECK(d[8].message == "TimeSensor has no eventOut 'nothing' for a ROUTE source");
  CHECK(d[8].location.line == 14);

  Scene self = parse("DEF G1 Group {}\nDEF G2 Group { ROUTE G1.children TO G2.children }");
  CHECK(self.diagnostics.items.empty());
  CHECK(self.routes.size() == 1);
}

TEST_CASE("EXTERNPROTO resolved from a local file", "[parser][proto]") {
  const std::string url = dataDir() + "/virtual_user.wrl";
  Scene s = gs::vrml::parseVrml(R"(#VRML V2.0 utf8
EXTERNPROTO Box2 [ exposedField SFColor color field SFVec3f size ]
  [ "missing_first.wrl#ColoredBox", "extern_lib.wrl#ColoredBox" ]
EXTERNPROTO Mv [ eventIn SFFloat set_fraction exposedField SFVec3f where ]
  "extern_lib.wrl#Mover"
EXTERNPROTO First [ exposedField SFColor color ] "extern_lib.wrl"
Box2 { color 0 1 0 }
DEF M Mv { where 1 2 3 }
DEF TS TimeSensor {}
ROUTE TS.fraction_changed TO M.set_fraction
First {}
)",
                                url);
  REQUIRE(s.diagnostics.items.empty());
  REQUIRE(s.protos.size() == 3);
  REQUIRE(s.protos[0]->proto->resolved);
  CHECK(s.protos[0]->proto->resolvedUrl == "extern_lib.wrl#ColoredBox");
  REQUIRE(s.rootNodes.size() == 4);
  const Node& box = *s.rootNodes[0];
  CHECK(box.typeName() == "Shape");
  CHECK(box.protoName() == "Box2");
  CHECK(!box.unresolved);
  CHECK(box.sfnode("appearance")
            ->sfnode("material")
            ->get<FieldType::SFColor>("diffuseColor", glm::vec3(9)) == glm::vec3(0, 1, 0));
  // Not given: the default of the PROTO in the library.
  CHECK(box.sfnode("geometry")->get<FieldType::SFVec3f>("size", glm::vec3(0)) == glm::vec3(2));
  CHECK(box.sfnode("geometry")->location.file == dataDir() + "/extern_lib.wrl");
  const Node& mover = *s.rootNodes[1];
  CHECK(mover.typeName() == "Transform");
  CHECK(mover.get<FieldType::SFVec3f>("translation", glm::vec3(0)) == glm::vec3(1, 2, 3));
  REQUIRE(s.routes.size() == 2);  // the body's own ROUTE and ours, flattened
  CHECK(s.routes[1].toField == "set_fraction");
  CHECK(s.routes[1].toNode->typeName() == "PositionInterpolator");
  CHECK(s.rootNodes[3]->protoName() == "First");
  CHECK(s.rootNodes[3]->typeName() == "Shape");
}

TEST_CASE("EXTERNPROTO unresolved: a warning and a node of the declared interface",
          "[parser][proto]") {
  const std::string url = dataDir() + "/virtual_user.wrl";
  Scene s = gs::vrml::parseVrml(R"(#VRML V2.0 utf8
EXTERNPROTO Gone [ exposedField SFBool on field MFNode kids ]
  [ "nowhere.wrl#Gone" "urn:web3d:x" "http://example.com/lib.wrl#Gone" "extern_lib.wrl#NoSuch" ]
Gone { on TRUE }
)",
                                url);
  REQUIRE(s.diagnostics.items.size() == 1);
  const Diagnostic& d = s.diagnostics.items[0];
  CHECK(d.severity == Severity::warning);
  CHECK(d.location.line == 2);
  CHECK(d.location.column == 1);
  CHECK(d.message.find("EXTERNPROTO 'Gone' could not be resolved from [\"nowhere.wrl#Gone\", "
                       "\"urn:web3d:x\", \"http://example.com/lib.wrl#Gone\", "
                       "\"extern_lib.wrl#NoSuch\"]: ") == 0);
  CHECK(d.message.find("urn:web3d:x: urn: names are not resolved") != std::string::npos);
  CHECK(d.message.find("http://example.com/lib.wrl: only local files can be read without a "
                       "network loader") != std::string::npos);
  CHECK(d.message.find("the file declares no PROTO 'NoSuch'") != std::string::npos);
  REQUIRE(s.rootNodes.size() == 1);
  const Node& n = *s.rootNodes[0];
  CHECK(n.unresolved);
  CHECK(n.typeName() == "Gone");
  CHECK(n.protoName() == "Gone");
  CHECK(n.get<FieldType::SFBool>("on", false));
  CHECK(n.mfnode("kids").empty());
}

TEST_CASE("EXTERNPROTO through ParseOptions::fetcher", "[parser][proto]") {
  std::vector<std::string> asked;
  gs::base::CallbackFetcher fetcher(
      [&](const std::string& u, const std::string& referrer, gs::base::FetchMode mode) {
        CHECK(referrer == "http://host/dir/world.wrl");
        CHECK(mode == gs::base::FetchMode::whole);
        asked.push_back(u);
        if (u == "http://host/dir/lib.wrl")
          return gs::base::fetchReady(
              "#VRML V2.0 utf8\nPROTO Q [ field SFFloat r 3 ] { Sphere { radius IS r } }");
        return gs::base::fetchFailed(u + ": 404");
      });
  ParseOptions o;
  o.fetcher = &fetcher;
  Scene s = parseVrml(
      "#VRML V2.0 utf8\nEXTERNPROTO Q [ field SFFloat r ] [ \"x.wrl\" \"lib.wrl#Q\" ]\n"
      "Shape { geometry Q { } }\n",
      "http://host/dir/world.wrl", o);
  CHECK(asked == std::vector<std::string>{"http://host/dir/x.wrl", "http://host/dir/lib.wrl"});
  CHECK(s.diagnostics.errorCount() == 0);
  CHECK(s.diagnostics.warningCount() == 0);
  REQUIRE(s.rootNodes.size() == 1);
  CHECK(s.rootNodes[0]->sfnode("geometry")->get<FieldType::SFFloat>("radius", 0.0f) == 3.0f);
}

TEST_CASE("EXTERNPROTO cycles and depth are bounded", "[parser][proto]") {
  Scene s = loadVrmlFile(dataDir() + "/extern_cycle_a.wrl");
  CHECK(s.diagnostics.errorCount() == 0);
  CHECK(s.diagnostics.warningCount() >= 1);
  bool recursive = false;
  for (const Diagnostic& d : s.diagnostics.items)
    recursive = recursive || d.message.find("recursive EXTERNPROTO reference") != std::string::npos;
  CHECK(recursive);
  CHECK(s.rootNodes.size() == 1);

  ParseOptions o;
  o.limits.maxExternProtoDepth = 0;
  Scene d = parseVrml("#VRML V2.0 utf8\nEXTERNPROTO C [] \"extern_lib.wrl#ColoredBox\"\nC {}",
                      dataDir() + "/v.wrl", o);
  REQUIRE(d.diagnostics.items.size() == 1);
  CHECK(d.diagnostics.items[0].message.find("maxExternProtoDepth") != std::string::npos);
}

TEST_CASE("PROTO recursion and expansion bombs end with an error", "[parser][proto][bad_input]") {
  Scene self = parse("PROTO A [] { Group { children A {} } }\nA {}");
  REQUIRE(self.diagnostics.errorCount() == 1);
  CHECK(self.diagnostics.items[0].message == "PROTO 'A' is used inside its own definition");
  CHECK(self.diagnostics.items[0].location.line == 2);

  Scene def = parse("PROTO A [ field SFNode n A {} ] { Group {} }");
  CHECK(def.diagnostics.errorCount() == 1);

  // Each level instantiates the previous one ten times: 10^9 nodes if unbounded.
  std::string bomb = "PROTO L0 [] { Group {} }\n";
  for (int i = 1; i <= 9; ++i) {
    bomb += "PROTO L" + std::to_string(i) + " [] { Group { children [";
    for (int k = 0; k < 10; ++k) bomb += " L" + std::to_string(i - 1) + " {}";
    bomb += " ] } }\n";
  }
  bomb += "L9 {}\n";
  ParseOptions o;
  o.limits.maxNodes = 200000;
  Scene b = parse(bomb, o);
  REQUIRE(b.diagnostics.errorCount() >= 1);
  CHECK(gs::test::firstError(b).find("ParseLimits::maxNodes") != std::string::npos);

  // Deep PROTO nesting by instantiation: each level adds depth.
  std::string deep = "PROTO D0 [] { Group {} }\n";
  for (int i = 1; i <= 130; ++i)
    deep += "PROTO D" + std::to_string(i) + " [] { Group { children [ Group { children D" +
            std::to_string(i - 1) + " {} } ] } }\n";
  deep += "D130 {}\n";
  Scene dp = parse(deep);
  REQUIRE(dp.diagnostics.errorCount() >= 1);
  CHECK(gs::test::firstError(dp).find("nests deeper than 256") != std::string::npos);
}

TEST_CASE("PROTO: an instance keeps its declared interface, values and IS map", "[proto]") {
  Scene s = parse(R"(
PROTO Lamp [ exposedField SFFloat level 0.5 field SFColor tint 1 0 0 eventIn SFBool unused ] {
  Group { children [ PointLight { intensity IS level color IS tint } ] }
}
PROTO Pair [ exposedField SFFloat both 0.1 ] {
  Group { children [ Lamp { level IS both } ] }
}
Lamp { level 0.25 }
Pair { }
Pair { both 0.9 }
)");
  REQUIRE(s.diagnostics.items.empty());
  REQUIRE(s.rootNodes.size() == 3);
  const Node& lamp = *s.rootNodes[0];
  REQUIRE(lamp.protoInstance);
  const ProtoInstance& p = *lamp.protoInstance;
  CHECK(declaredInterface(lamp) == &p);
  CHECK(p.type->name == "Lamp");
  REQUIRE(p.values.size() == 3);
  CHECK(p.values[0].get<FieldType::SFFloat>() == 0.25f);
  CHECK(p.values[1].get<FieldType::SFColor>() == glm::vec3(1, 0, 0));
  REQUIRE(p.linksOf(0).size() == 1);
  CHECK(p.linksOf(2).empty());
  const NodePtr light = lamp.mfnode("children").at(0);
  CHECK(p.linksOf(0)[0].node.lock() == light);
  CHECK(p.value(0)->get<FieldType::SFFloat>() == 0.25f);
  CHECK(p.value(7) == nullptr);
  // The inner Lamp of each Pair links to that Pair's own copy of the body, not the template.
  for (std::size_t k = 1; k < 3; ++k) {
    const NodePtr inner = s.rootNodes[k]->mfnode("children").at(0);
    REQUIRE(inner->protoInstance);
    CHECK(inner->protoName() == "Lamp");
    const NodePtr innerLight = inner->mfnode("children").at(0);
    REQUIRE(inner->protoInstance->linksOf(0).size() == 1);
    CHECK(inner->protoInstance->linksOf(0)[0].node.lock() == innerLight);
    CHECK(inner->protoInstance->value(0)->get<FieldType::SFFloat>() == (k == 1 ? 0.1f : 0.9f));
  }
  // A plain node has no interface of its own.
  CHECK(declaredInterface(*lamp.mfnode("children").at(0)) == nullptr);
}
