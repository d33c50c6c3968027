// The X3D XML reader's state (x3d_xml.hpp: XmlToClassic::Impl): the element stack, the
// buffered statement and what it knows of the file's PROTOs. The expat callbacks and the
// element tree are x3d_xml.cpp's; the writing of each statement as Classic VRML text is
// x3d_xml_statements.cpp's. Internal to gs_encodings.
#pragma once

#include "x3d_xml.hpp"

#include "encodings/node_types.hpp"
#include "vrml/field.hpp"
#include "vrml/node_model.hpp"
#include "vrml/node_table.hpp"
#include "x3d_numbers.hpp"
#include "x3d_positions.hpp"
#include "x3d_values.hpp"
#include "x3d_xml_tree.hpp"

#include <expat.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <iterator>
#include <optional>
#include <span>
#include <unordered_map>
#include <unordered_set>

namespace gs::vrml::parsing {

// Small helpers of both halves of the reader.
namespace xml_reader {

inline bool blank(std::string_view s) {
  return std::all_of(s.begin(), s.end(), xmlSpace);
}

inline std::string_view trimLeft(std::string_view s) {
  while (!s.empty() && xmlSpace(s.front())) s.remove_prefix(1);
  return s;
}

// The XML encoding's element for a PROTO instance (ISO/IEC 19776-1 5.3.6): a statement of
// the encoding, not a node class.
constexpr std::string_view kProtoInstanceElement = "ProtoInstance";

// Nodes whose <field> children declare interface members (ISO/IEC 19776-1 5.3.7): Script
// and the X3DProgrammableShaderObject nodes (NodeType::userFields).
inline bool declaresFields(const NodeType* type) {
  return type != nullptr && type->userFields;
}

// Nodes whose text content is source code, added to `url`: Script, ShaderPart and the
// programmable shader nodes that carry a url (ShaderProgram, PackagedShader).
inline bool xmlTakesSource(const NodeType* type) {
  if (type == nullptr) return false;
  return type->script || type->id() == NodeTypeId::ShaderPart ||
         (type->userFields && type->is(AbstractType::X3DUrlObject));
}

// Script source gets the ecmascript: scheme; shader source a data: URL.
inline bool isScript(const NodeType* type) {
  return type != nullptr && type->script;
}

}  // namespace xml_reader

struct XmlToClassic::Impl final : XmlTreeInfo {
  Impl(std::string& o, std::string u, int maxNesting)
      : out(o), url(std::move(u)), maxDepth(std::max(maxNesting, 1) + 8) {
    xp = XML_ParserCreate(nullptr);
    if (xp == nullptr) throw std::bad_alloc();
    XML_SetUserData(xp, this);
    XML_SetElementHandler(xp, &Impl::onStart, &Impl::onEnd);
    // (The character data handler is set only inside elements that take source text.)
    // No external entity handler and no parameter-entity parsing: DTDs and external
    // entities named by the document are never fetched.
    XML_SetParamEntityParsing(xp, XML_PARAM_ENTITY_PARSING_NEVER);
  }
  ~Impl() { XML_ParserFree(xp); }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  enum class Frame : std::uint8_t { x3d, head, scene, item, skip, buffered };

  std::string& out;
  std::string url;
  int maxDepth;
  XML_Parser xp = nullptr;
  std::vector<Frame> stack;
  std::vector<std::unique_ptr<XNode>> pool;  // XNodes; the first poolUsed are in use
  std::size_t poolUsed = 0;
  XNode* root = nullptr;  // the statement being buffered
  XNode* cur = nullptr;   // its open element
  bool wroteHeader = false;
  bool x3d3 = false;  // version 3.x: metadata nodes go to `metadata` by default
  bool failed = false;
  Diagnostic fatal;
  std::vector<Diagnostic> warnings;
  std::unordered_map<std::string, ProtoInfo> protos;
  // Classic offset -> XML location, one entry per element start (increasing offsets).
  OffsetLocations lines;
  bool finished = false;   // the last bytes were fed
  XmlPositions positions;  // element start -> line and column (startHere)
  // Plain statements are offered to `builder` while `classicSafe`: no statement translated
  // so far can run into the text that follows it (see checkRaw).
  XmlStatementBuilder* builder = nullptr;
  bool classicSafe = true;

  // ---- expat callbacks -----------------------------------------------------------------

  static void XMLCALL onStart(void* ud, const XML_Char* name, const XML_Char** atts);
  static void XMLCALL onEnd(void* ud, const XML_Char* /*name*/) { static_cast<Impl*>(ud)->end(); }
  static void XMLCALL onText(void* ud, const XML_Char* s, int len);

  std::pair<int, int> here() const;

  void fail(int line, int column, std::string message);

  void warn(const XNode& n, std::string message);

  // here() at an element's start: from the byte offset and the line starts of the fed bytes
  // where that is exact and cheap, else from expat.
  std::pair<int, int> startHere();

  void start(const XML_Char* name, const XML_Char** atts);

  // x3dNodeType(n) through a small cache of the names met (a file uses few): no hash of
  // the whole name, no reference count. The table lives as long as the program.
  struct TypeCacheEntry {
    std::string name;
    const NodeType* type = nullptr;
    const NodeModel* model = nullptr;  // nodeModel(name)
    bool valid = false;
  };
  // (Two entries per hash: Material and Coordinate, which alternate in many worlds, share
  // one. A name in neither replaces the second, or the first while it is empty.)
  std::array<TypeCacheEntry, 64> typeCache;
  const TypeCacheEntry& lookupType(std::string_view n);

  // A pooled XNode for element `n`, reset.
  XNode* newNode(std::string_view n);

  // node()'s lists, one per nesting level of node(), kept for their capacity.
  struct NodeScratch {
    std::vector<std::pair<std::string, std::vector<const XNode*>>> group;  // by field
    std::size_t groups = 0;                                                // in use
    std::vector<const XNode*> routes;
  };
  std::vector<std::unique_ptr<NodeScratch>> scratch;
  std::size_t scratchDepth = 0;
  struct ScratchLevel {
    std::size_t& depth;
    explicit ScratchLevel(std::size_t& d) : depth(d) { ++depth; }
    ~ScratchLevel() { --depth; }
    ScratchLevel(const ScratchLevel&) = delete;
    ScratchLevel& operator=(const ScratchLevel&) = delete;
  };

  void end();

  // Character data matters only in an element that takes source text: expat reports it
  // only there (fewer calls for the white space between elements).
  bool textOn = false;
  void textHandler();

  // <component>, <unit>, <meta> of <head>.
  void headItem(std::string_view n, const XML_Char** atts, int line, int column);

  // ---- output with line map ------------------------------------------------------------

  // An element's translation begins: on a line of its own (for a reader of the text),
  // its first byte recorded with the element's XML location.
  void beginLine(int line, int column);
  void beginLine(const XNode& n) { beginLine(n.line, n.column); }

  // ---- statements ----------------------------------------------------------------------

  void statement(const XNode& n);

  void route(const XNode& n);

  // `accessType type name [value]` of a <field> in a ProtoInterface, ExternProtoDeclare,
  // Script or shader. Returns the field's type when it names one.
  std::optional<FieldType> fieldDeclaration(const XNode& f, bool withValue);

  // Raw XML text written into the Classic text (numbers, MFString lists, words): once
  // some could open a string, a comment or a bracket that the parse of its statement would
  // not close, the statements after it may be read as part of it, so none is built
  // straight from its elements any more (classicSafe).
  void checkRaw(std::string_view text);

  void convertedValue(const XNode& n, FieldType t, std::string_view value);

  // One node or a list of nodes as the value of an SFNode / MFNode field.
  void nodeValue(bool list, const std::vector<const XNode*>& nodes);

  void protoDeclare(const XNode& n);

  void externProtoDeclare(const XNode& n);

  // Elements that are nodes (not statements or the XML encoding's structure).
  static bool isNodeElement(const XNode& n) { return n.kind == XKind::node; }

  // Where child `c` of `parent` goes: its containerField, else its type's default (X3D
  // 3's `metadata` for metadata nodes in a 3.x file). A default the parent (of a known
  // type) has no field for falls back to `metadata` for metadata nodes, else to
  // `children` where the parent has it, as castle-model-viewer does (HAnimMotion in a
  // Group, a 3.x MetadataSet in a 4.0 world). The view is into `c`, the node model, the
  // PROTOs declared or a literal.
  std::string_view containerFieldOf(const XNode& c, const XNode* parent) const;
  std::string_view containerField(const XNode& c, const XNode& parent) const override;
  std::optional<FieldType> fieldTypeOf(const XNode& p, std::string_view f) const override;

  // Whether the fields of node element `p` are all known here.
  bool knownFields(const XNode& p) const;

  // The type of field `f` of node element `p`; nothing when unknown.
  std::optional<FieldType> fieldType(const XNode& p, std::string_view f) const;

  // The type of field `f` of built-in `type`, through a small cache of the pairs met (a
  // file uses few; the table lives as long as the program).
  struct FieldCacheEntry {
    const NodeType* type = nullptr;
    std::string name;
    std::optional<FieldType> fieldType;
  };
  mutable std::array<FieldCacheEntry, 256> fieldCache;
  std::optional<FieldType> builtInFieldType(const NodeType& type, std::string_view f) const;
  void node(const XNode& n);

  // <fieldValue name value> or with node children, in a ProtoInstance.
  void fieldValue(const XNode& inst, const XNode& fv);
};

}  // namespace gs::vrml::parsing
