// The VRML97 parser's internals (annex A grammar): scopes, DEF entries and the Parser
// class whose members are spread over parser.cpp (statements and nodes),
// value_parser.cpp (the 20 field types), parse_proto.cpp (PROTO, EXTERNPROTO, instances) and
// parse_route.cpp (ROUTE). Internal to gs_encodings.
#pragma once

#include "base/gzip.hpp"
#include "encodings/node_types.hpp"
#include "encodings/parser.hpp"
#include "gltf/import.hpp"
#include "lexer.hpp"
#include "vrml/node.hpp"
#include "vrml/node_table.hpp"
#include "vrml/proto.hpp"
#include "vrml/scene.hpp"

#include <array>
#include <cstring>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace gs::vrml::parsing {

struct XNode;       // x3d_xml_tree.hpp
class XmlTreeInfo;  // x3d_xml_tree.hpp

struct StringHash {
  using is_transparent = void;
  std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
};
template <class V>
using NameMap = std::unordered_map<std::string, V, StringHash, std::equal_to<>>;

/// What a DEF name stands for (clause 4.6.2).
struct DefEntry {
  NodePtr node;
  /// The type the file named: for PROTO instances the PROTO type, whose interface ROUTEs
  /// use; for other nodes node->typePtr().
  std::shared_ptr<const NodeType> declared;
  /// For PROTO instances: what each interface member is connected to (for ROUTEs).
  std::shared_ptr<const std::vector<IsConnection>> links;
  int height = 1;     // nesting levels of the node's tree
  bool open = false;  // its body is being parsed: a USE now makes a back reference
};

/// The PROTO whose body is being parsed (IS statements refer to its interface).
struct ProtoBuilder {
  std::shared_ptr<NodeType> type;
  std::shared_ptr<ProtoDefinition> def;
};

/// What a statement changed in a scope's names, so that StreamingParser can undo a
/// statement cut short by the end of the bytes so far: each name with the entry it had
/// before (none: it was not there), in order.
struct ScopeUndo {
  std::vector<std::pair<std::string, std::optional<DefEntry>>> defs;
  std::vector<std::pair<std::string, std::optional<std::shared_ptr<const NodeType>>>> protos;
};

/// A name scope (clause 4.4.7): DEF names do not cross PROTO bodies or PROTO field
/// defaults; PROTO names are looked up through `parent` too.
struct Scope {
  Scope* parent = nullptr;
  /// Where DEF names not found here are looked up: the declaring scope for a PROTO
  /// field default (it may USE nodes of the file, castle's proto_nodes.wrl), null for
  /// a PROTO body (its own name space, clause 4.8.3).
  Scope* defParent = nullptr;
  NameMap<DefEntry> defs;
  /// PROTO / EXTERNPROTO types; null while the PROTO of that name is being defined.
  NameMap<std::shared_ptr<const NodeType>> protos;
  ProtoBuilder* proto = nullptr;           // non-null inside a PROTO body
  std::vector<Route>* routes = nullptr;    // where ROUTEs go
  std::vector<NodePtr>* hidden = nullptr;  // where hidden instance nodes go
  std::vector<std::shared_ptr<const NodeType>>* declared = nullptr;  // Scene::protos
  X3dInfo* x3d = nullptr;     // top scope: where X3D header statements go
  bool checkRoots = false;    // root nodes are checked against the children node class
  ScopeUndo* undo = nullptr;  // when set, changes to defs and protos are logged there
};

/// An EXTERNPROTO file loaded during this parse (cached by resolved URL).
struct ExternFile {
  bool loading = true;  // being parsed: a reference now is recursive
  std::vector<std::shared_ptr<const NodeType>> protos;
  std::string error;
  // For StreamingParser, which may undo the statement that loaded the file: what its
  // parse added (diagnostics, nodes counted), added again by the next reference when
  // `replay` is set.
  std::vector<Diagnostic> diagnostics;
  std::size_t nodes = 0;
  bool replay = false;
};

/// State shared by the parse of a file and the EXTERNPROTO files it loads.
struct Context {
  explicit Context(const ParseOptions& o) : options(o) {}
  const ParseOptions& options;
  /// The file being parsed is X3D (its header said #X3D): X3D node types and interfaces,
  /// the X3D statements. Set per file by parseInto / StreamingParser.
  bool x3d = false;
  /// The X3D file's header says version 3.x: the fields whose default X3D 4 changed take
  /// X3D 3's (applyX3d3Defaults). Per file, like `x3d`.
  bool x3dVersion3 = false;
  /// The file's UNIT conversion factors (X3D clause 4.3.6) for length and angle: what a
  /// value the file writes is in metres and radians. Set by its UNIT statements; 1 in a
  /// VRML97 file. Per file, like `x3d`.
  struct Units {
    double length = 1.0;
    double angle = 1.0;
  } units;
  std::size_t nodeCount = 0;
  NameMap<std::shared_ptr<ExternFile>> externFiles;
  /// When set (StreamingParser), the files the top-level file loads, in order.
  std::vector<std::shared_ptr<ExternFile>>* loaded = nullptr;
  /// StreamingParser with ParseOptions::externProtosInBackground: EXTERNPROTO files of
  /// the top-level file are asked for in the background while this is set (cleared by
  /// finish(), when a file still on its way fails instead).
  bool externInBackground = false;
  /// Set when an EXTERNPROTO file of the statement being parsed is still on its way: the
  /// StreamingParser undoes the statement and retries it at a later feed().
  bool externPending = false;
};

/// The members a Script node declares in its body (clause 6.40), gathered into one
/// per-instance NodeType that the node receives when its body ends.
struct ScriptBuild {
  std::shared_ptr<NodeType> type;  // built-in Script members, then the declared ones
  std::vector<FieldValue> values;  // values of the declared members, in order
  NameMap<int> names;              // declared member name -> index in type->fields
};

/// A hashed member index of a NodeType with many members (PROTOs), kept for the parse.
struct MemberIndex {
  std::shared_ptr<const NodeType> keep;
  NameMap<int> names;
};

/// Values given to a PROTO instance before it is expanded.
struct InstanceValues {
  std::shared_ptr<const NodeType> type;  // the PROTO / EXTERNPROTO type
  std::vector<FieldValue> values;        // per interface member
  std::vector<char> given;               // value written in the file
  std::vector<IsConnection> isRefs;      // nodeField: instance member, protoField: outer
  int valueHeight = 0;                   // tallest node tree among the values
  SourceLocation location;               // of the type name (taken before the body)
};

/// The glTF importer's options for a parse with `options`: its fetcher, limits and
/// root-node callback, and the X3D node types of node_types.hpp.
gltf::ImportOptions gltfImportOptions(const ParseOptions& options);

class Parser {
 public:
  /// The member an X3D field-name alias stands for in `type`: Switch/LOD `children`
  /// (VRML97's choice/level), Collision `enabled` (collide), ComposedCubeMapTexture's X3D 3
  /// face names (back ... top for X3D 4's backTexture ... topTexture), LoadSensor's X3D 3
  /// `watchList` (X3D 4's `children`), ParticleSystem's X3D 3 `colorRamp` and
  /// `texCoordRamp` (X3D 4's `color` and `texCoord`); -1 when none.
  static int x3dFieldAlias(const NodeType& type, std::string_view name);
  /// `text` is the whole file; parsing starts at byte `start` (after the header).
  /// `origin`: the text is a translation of X3D XML or JSON, whose locations it gives.
  Parser(std::string_view text, std::string file, std::size_t start, Context& ctx,
         Diagnostics& diag, int externDepth, TextOrigin* origin = nullptr);

  /// Parses statements up to the end of input into `scene` (clause 4.4 / A.3
  /// vrmlScene). Reports fatal errors as diagnostics and stops there.
  void parseScene(Scene& scene);

  /// Parses the node table's interface text of node `name` (table mode: no nodes).
  /// Throws ParseError on any problem.
  std::vector<FieldSpec> parseInterfaceText(std::string_view name);
  /// Parses the whole text as one value of type `t` (table mode: SFNode only NULL).
  /// Throws ParseError on any problem.
  FieldValue parseValueText(FieldType t);

  // For StreamingParser: the top-level statements one at a time, over a text that grows.
  /// Parses the next statement of `top` (set up as parseScene sets its top scope) into
  /// `roots`; false when only space is left. A fatal error throws ParseError.
  bool parseTopStatement(Scope& top, std::vector<NodePtr>& roots);
  /// What parseScene does after the statements: reports `fatal` (null when the text
  /// ended) unless giving up, then the give-up and suppressed-diagnostics summaries.
  void endScene(const ParseError* fatal);
  /// Builds the nodes of the X3D XML encoding's top-level statement `root` (its elements
  /// as XmlToClassic buffered them; `info` answers for the translator) straight into
  /// `roots`, at the XML's locations, as parseTopStatement() would from the statement's
  /// Classic translation (parser_xml_build.cpp): DEF/USE in `top` (logged in top.undo
  /// when set), the limits, field values from the attributes (ISO/IEC 19776-1 5.3),
  /// children by containerField, the units of the file, the node class checks. Only when
  /// that parse would report nothing: a statement with anything it would report (or that
  /// the XML encoding spells with more than node elements and their attributes: PROTOs,
  /// IS, fields, Scripts and shaders, ROUTEs inside nodes) gives false, with nothing
  /// changed, and is then translated and parsed.
  bool buildXmlStatement(Scope& top, const XNode& root, const XmlTreeInfo& info,
                         std::vector<NodePtr>& roots);
  /// The text grew (Lexer::extend).
  void extendText(std::string_view text, bool final) { lex_.extend(text, final); }
  Lexer& lexer() { return lex_; }
  /// The parser's own state that a statement changes.
  struct State {
    Lexer::Position position;
    std::size_t errors;
    std::size_t suppressed;
    bool giveUp;
    bool protosDeclared;
  };
  State state() const {
    return State{lex_.position(), errors_, suppressed_, giveUp_, protosDeclared_};
  }
  void restore(const State& s) {
    lex_.restore(s.position);
    errors_ = s.errors;
    suppressed_ = s.suppressed;
    giveUp_ = s.giveUp;
    protosDeclared_ = s.protosDeclared;
    recursion_ = 0;
  }

 private:
  // parser.cpp: statements and nodes
  void parseStatements(Scope& scope, std::vector<NodePtr>* nodes, int depth, bool untilBrace,
                       int* height);
  /// One statement of parseStatements, starting at `t` (peeked: an id or other token).
  void parseStatement(Scope& scope, std::vector<NodePtr>* nodes, int depth, int* height,
                      const Token& t);
  /// scope.defs[name] = e, logged in scope.undo when set.
  void define(Scope& scope, std::string_view name, DefEntry e);
  /// Ends the DEF entry `name` of `node` once its body is read (no longer open: USE may
  /// now refer to it; its height and declared type recorded). Nothing when `name` is
  /// empty or now names another node.
  static void closeDef(Scope& scope, std::string_view name, const Node& node, int height);
  /// scope.protos[name] = type (null: being defined) or erased, logged in scope.undo.
  void setProto(Scope& scope, const std::string& name, std::shared_ptr<const NodeType> type);
  void eraseProto(Scope& scope, const std::string& name);
  NodePtr parseNodeStatement(Scope& scope, int depth, int& height, bool allowNull);
  /// `t` is the node type name token, peeked and not consumed.
  NodePtr parseNode(Scope& scope, const Token& t, int depth, int& height, std::string_view defName);
  void parseNodeBody(Scope& scope, const NodePtr& node, InstanceValues* inst, int depth,
                     int& height);
  /// Reads a field type name; throws ParseError "unknown field type 'X'" at its place.
  FieldType parseFieldTypeName();
  void parseScriptDeclaration(Scope& scope, const NodePtr& node, const Token& keyword, int depth,
                              int& height, ScriptBuild& script);
  /// Index of the member called exactly `name`, hashed for types with many members.
  int memberIndex(const std::shared_ptr<const NodeType>& type, std::string_view name);
  void parseIs(Scope& scope, const NodeType& type, int index, AccessType access,
               std::string_view asWritten, std::size_t offset, const NodePtr& node,
               InstanceValues* inst);
  void skipUnknownValue(const NodeType& type);
  void resync(const NodeType* type);
  std::shared_ptr<const NodeType> lookupType(Scope& scope, std::string_view name, bool& defining);
  void retype(Node& node, std::shared_ptr<const NodeType> type, std::vector<FieldValue>& extra);
  void countNode(std::size_t offset);
  void enter(std::size_t offset);
  void checkNodeClass(const NodeType* parent, std::string_view field, const NodePtr& child,
                      std::size_t offset);
  void checkInline(const Node& node, std::size_t offset);

  // parser_xml_build.cpp: buildXmlStatement's nodes and values
  struct XmlBuild;
  NodePtr xmlNode(XmlBuild& b, const XNode& n, int depth, int& height);
  void xmlValue(Scope& scope, FieldType t, const std::string& text, FieldValue& out);
  bool xmlNumbers(FieldType t, const std::string& text, FieldValue& out);
  int xmlMember(const NodeType& type, std::string_view name);

  // value_parser.cpp: field values (clause 5)
  void parseValue(FieldType t, FieldValue& out, Scope& scope, int depth, int& height,
                  const NodeType* parent = nullptr, std::string_view field = {});
  /// The X3D field types (SFDouble ... MFMatrix4d), Classic VRML encoding.
  void parseX3dValue(FieldType t, FieldValue& out);
  NodePtr parseSFNode(Scope& scope, int depth, int& height, const NodeType* parent,
                      std::string_view field);
  bool readBool();
  glm::vec2 readVec2();
  glm::vec3 readVec3();
  glm::vec4 readRotation();
  void readImage(SFImage& image);
  template <class T, class F>
  void readList(std::vector<T>& v, F&& one);
  template <int N, class T>
  void readFloatList(std::vector<T>& v, std::vector<T>& scratch);
  void readInt32List(std::vector<std::int32_t>& v);

  // proto.cpp: PROTO, EXTERNPROTO and instances (clauses 4.8, 4.9)
  void parseProto(Scope& scope);
  void parseExternProto(Scope& scope);
  void parseInterface(Scope& scope, NodeType& type, bool withValues, bool external);
  bool parseInterfaceDeclaration(Scope& scope, NodeType& type, bool withValues, bool external,
                                 NameMap<int>& names);
  void resolveExternProto(Scope& scope, ProtoDefinition& def, const NodeType& declared,
                          std::size_t offset);
  bool loadExternFile(const std::string& url, std::shared_ptr<ExternFile>& out,
                      std::string& reason);
  NodePtr instantiate(Scope& scope, InstanceValues& inst, std::size_t offset, int depth,
                      int& height, std::shared_ptr<const std::vector<IsConnection>>& links);
  NodePtr copyTree(const NodePtr& n, std::unordered_map<const Node*, NodePtr>& memo,
                   std::vector<NodePtr>& keep);

  // x3d_statements.cpp: PROFILE, COMPONENT, UNIT, META, IMPORT, EXPORT (X3D 19776-2 4.x)
  /// True when `t` starts an X3D statement, which is then parsed.
  bool parseX3dStatement(Scope& scope, const Token& t);
  /// Applies the file's angle unit (Context::units.angle) to the value `v` just read for
  /// field `spec`: the angle of SFRotation / MFRotation values and the fields X3D gives in
  /// angle units (fieldOfView, creaseAngle, skyAngle ...).
  void applyAngleUnit(const FieldSpec& spec, FieldValue& v) const;
  /// `n` inside a Transform scaled by the file's length unit (Context::units.length), so
  /// that its lengths are metres; `n` itself when the unit is the metre or n is no child.
  NodePtr applyLengthUnit(const NodePtr& n) const;

  // route.cpp: ROUTE (clause 4.10)
  void parseRoute(Scope& scope);
  void parseRouteStatement(Scope& scope);
  static DefEntry* findDef(Scope& scope, std::string_view name);

  // diagnostics
  void report(Severity s, std::size_t offset, std::string message);
  void report(const ParseError& e);

  Lexer lex_;
  Context& ctx_;
  Diagnostics& diag_;
  int externDepth_ = 0;
  int recursion_ = 0;              // parseNode frames on the stack (bounded by maxNesting)
  int scriptValueRecursion_ = -1;  // recursion_ while a Script field's value is read
  bool tableMode_ = false;         // parsing the node table: no nodes allowed
  bool giveUp_ = false;            // too many errors: stop
  std::size_t errors_ = 0;         // errors reported by this parser
  std::size_t suppressed_ = 0;     // diagnostics not stored (over the limit)
  bool protosDeclared_ = false;    // no PROTO seen yet: node types are all built-in
  struct TypeCacheEntry {
    std::shared_ptr<const NodeType> type;
  };
  std::array<TypeCacheEntry, 64> typeCache_{};                 // recent built-in types (lookupType)
  std::unordered_map<const NodeType*, MemberIndex> bigIndex_;  // memberIndex()
  // MF number lists are read into these first (they keep their capacity between lists).
  std::vector<float> floatScratch_;
  std::vector<glm::vec2> vec2Scratch_;
  std::vector<glm::vec3> vec3Scratch_;
  std::vector<glm::vec4> vec4Scratch_;
  std::vector<std::int32_t> intScratch_;
  // buildXmlStatement: a lexer over one attribute value at a time (swapped with lex_
  // while a statement is built), that value's Classic text, names, children by field.
  Lexer valueLex_;
  std::string valueText_;
  std::string xmlName_;
  std::string xmlScratch_;
  struct XmlGroup {
    std::string_view field;
    int member = -1;  // its index in the parent's type when known
    std::vector<const XNode*> nodes;
  };
  struct XmlGroups {
    std::vector<XmlGroup> groups;
    std::size_t used = 0;
  };
  std::vector<std::unique_ptr<XmlGroups>> xmlGroups_;      // one per nesting level
  std::vector<std::shared_ptr<const NodeType>> xmlTypes_;  // built-in types met (no PROTOs)
};

/// NodeType::findExact for the hot path: most names differ in length or first byte.
inline int findMember(const NodeType& type, std::string_view name) {
  const std::size_t n = type.fields.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::string& f = type.fields[i].name;
    if (f.size() == name.size() && f[0] == name[0] && sameName(f, name)) return static_cast<int>(i);
  }
  return -1;
}

/// Orders IsConnections by interface member (protoField), for equal_range.
struct ConnectionOrder {
  bool operator()(const IsConnection& a, int m) const { return a.protoField < m; }
  bool operator()(int m, const IsConnection& a) const { return m < a.protoField; }
};

/// The connections of interface member `member` in `links` (sorted by protoField, as
/// instantiate() leaves them).
std::span<const IsConnection> connectionsOf(const std::vector<IsConnection>& links, int member);

/// Nesting levels of the tree under `n` (1 for a leaf), following owning pointers only.
int treeHeight(const NodePtr& n, std::unordered_map<const Node*, int>& memo);

/// Whether a node of type `child` may be the value of `field` of built-in `parent`
/// (null: at the root of a scene), by the field's acceptableNodeTypes in the node model
/// (node_model.hpp). PROTO types and Script fields are always allowed. On false,
/// `expected` names what the field takes ("X3DChildNode", "Coordinate or
/// CoordinateDouble").
bool nodeClassAllowed(const NodeType* parent, std::string_view field, const NodeType& child,
                      std::string& expected);

/// Decompresses gzip data (1f 8b ...) into `out` (base::gunzip); throws ParseError naming
/// `url` with base::GzipError's reason.
void gunzipInto(std::string_view bytes, const std::string& url, std::size_t maxBytes,
                std::string& out);

/// The problem with the first line `line` of a file ("VRML 1.0 is not supported", "expected
/// '#VRML V2.0 utf8' ... header, got '...'"), empty when it is a VRML97 header or an X3D
/// Classic VRML header ("#X3D V3.3 utf8", versions 3.0 to 4.x), whose version ("3.3") is
/// then put in `x3dVersion` (cleared otherwise).
std::string headerProblem(std::string_view line, std::string& x3dVersion);

/// Gives a node just made for an X3D 3.x file the defaults X3D 3.3 had where X3D 4.0
/// changed them (before its fields are read): WindPhysicsModel.direction 0 0 0 (X3D 3.3
/// clause 40.4.11; 4.0: 1 0 0), as X_ITE reads 3.3 files.
void applyX3d3Defaults(Node& node);

/// Parses `bytes` (a whole file, gzip or not) into `scene` with shared context `ctx`.
/// `origin`: `bytes` is the Classic translation of X3D XML or JSON, whose locations it gives.
/// Sets Node::urlBase to `url` on every node written in the EXTERNPROTO file `url`: the
/// bodies, hidden nodes and interface defaults of its PROTOs `protos` (nodes that have a
/// base already, from a file nested deeper, keep theirs).
void markExternNodes(const std::vector<std::shared_ptr<const NodeType>>& protos,
                     const std::string& url);

void parseInto(std::string_view bytes, const std::string& url, Context& ctx, int externDepth,
               Scene& scene, TextOrigin* origin = nullptr);

/// parseInto() for X3D's XML encoding (`bytes` plain, within the limits): translated into
/// Classic VRML text where a statement needs it and parsed as it comes, plain statements
/// built straight from their elements (Parser::buildXmlStatement); diagnostics at the
/// XML's file:line:column (parser_xml_build.cpp).
void parseXmlInto(std::string_view bytes, const std::string& url, Context& ctx, int externDepth,
                  Scene& scene);

/// Whether parseXmlInto and StreamingParser build plain XML statements straight from their
/// elements (true, the default) or translate every statement (false: what the tests
/// compare the direct path with). Process-wide.
bool xmlDirectBuild();
void setXmlDirectBuild(bool on);

/// Whether `url` (relative to the file `base`) names the local file `base` itself.
bool urlNamesFile(const std::string& base, const std::string& url);

/// Reads the whole local file named by the path or file: URL `url` (base::readFile);
/// false with `error` set when it cannot.
bool readFile(const std::string& path, std::size_t maxBytes, std::string& bytes,
              std::string& error);

}  // namespace gs::vrml::parsing
