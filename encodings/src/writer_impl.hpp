// What the writers of writer.hpp write, decided once for every encoding (writer_model.cpp):
// a document of statements (nodes, PROTO declarations, ROUTEs, IMPORT / EXPORT) made from
// a Scene, with PROTO instances folded back into instances, ROUTEs mapped back onto the
// interfaces they named, only non-default fields, and the diagnostics of what the target
// cannot hold. The Classic printer (writer_classic.cpp), the XML printer and the JSON
// printer (writer_xml.cpp, writer_json.cpp) only spell it. Internal to gs_encodings.
#pragma once

#include "encodings/writer.hpp"
#include "vrml/field.hpp"
#include "vrml/node.hpp"
#include "vrml/proto.hpp"
#include "vrml/scene.hpp"

#include <deque>
#include <memory>
#include <string>
#include <vector>

namespace gs::vrml::writing {

struct WNode;
struct WProto;

/// One field of a node written with a value, or connected by IS inside a PROTO body.
struct WField {
  std::string name;  // as the target spells it (X3D's `children` for Switch's `choice`)
  FieldType type = FieldType::SFBool;
  const FieldValue* value = nullptr;        // null when only `isMember` is written
  std::vector<WNode> nodes;                 // SFNode (0 or 1) / MFNode values
  std::string isMember;                     // `name IS isMember`; empty when none
  AccessType isAccess = AccessType::field;  // how the IS statement named the member
};

/// A declaration of an interface member: of a PROTO, an EXTERNPROTO (no value), or the
/// user fields of a Script or shader node (value, or IS inside a PROTO body).
struct WDecl {
  AccessType access = AccessType::field;
  FieldType type = FieldType::SFBool;
  std::string name;
  const FieldValue* value = nullptr;  // null for eventIn / eventOut and EXTERNPROTO
  std::vector<WNode> nodes;           // SFNode / MFNode values
  std::string isMember;               // Script field `IS` (empty when none)
};

/// A node as written: `USE name`, or `[DEF name] Type { fields }`, or a PROTO instance.
struct WNode {
  const Node* node = nullptr;
  bool use = false;
  bool instance = false;  // PROTO / EXTERNPROTO instance: `typeName` is the PROTO's name
  std::string def;        // DEF or USE name
  std::string typeName;
  /// PROTOs declared in the node's body (Classic encodings only: a PROTO the file declared
  /// inside a node, which Scene::protos does not list), before everything else.
  std::vector<std::shared_ptr<WProto>> protos;
  std::vector<WDecl> decls;  // Script and shader user fields, before `fields`
  std::vector<WField> fields;
  /// The XML encoding's containerField default of the node's type (empty for instances).
  std::string containerDefault;
};

struct WStatement;

/// PROTO or EXTERNPROTO declaration.
struct WProto {
  std::string name;
  bool external = false;
  std::vector<WDecl> interface;
  const std::vector<std::string>* urls = nullptr;  // EXTERNPROTO
  std::vector<WStatement> body;                    // PROTO
};

struct WRoute {
  std::string fromNode, fromField, toNode, toField;
  const Node* from = nullptr;  // the nodes named (null for an IMPORTed name)
  const Node* to = nullptr;
};

/// One statement, at the top of the file or in a PROTO body.
struct WStatement {
  enum class Kind { node, proto, route, import, exported } kind = Kind::node;
  WNode node;
  std::shared_ptr<WProto> proto;
  WRoute route;
  std::string a, b, c;  // IMPORT inlineDEF, importedDEF, AS; EXPORT localDEF, AS
};

/// A whole world as written.
struct WDocument {
  bool x3d = false;  // an X3D encoding (else VRML97)
  std::string version, profile;
  std::vector<std::pair<std::string, int>> components;
  std::vector<X3dUnit> units;  // mass and force only (length and angle values are converted)
  std::vector<std::pair<std::string, std::string>> meta;
  std::vector<WStatement> statements;
  std::deque<FieldValue> owned;  // values converted for the target, pointed to by WField
};

/// Builds the document of `scene` for `encoding`, adding to `diagnostics` what is left out.
WDocument buildDocument(const Scene& scene, const WriteOptions& options, Diagnostics& diagnostics);

/// The printers: Classic (VRML97 or X3D by WDocument::x3d), XML, JSON.
std::string printClassic(const WDocument& doc);
std::string printXml(const WDocument& doc);
std::string printJson(const WDocument& doc);

/// One element of the XML encoding (ISO/IEC 19776-1), which the JSON encoding mirrors
/// (ISO/IEC 19776-5): attributes as text, or as a field value the JSON printer writes
/// with its JSON type.
struct XAttr {
  std::string name;
  std::string text;                   // when `value` is null
  const FieldValue* value = nullptr;  // a field's value
};
struct XElem {
  std::string name;
  std::vector<XAttr> attrs;
  std::vector<XElem> children;
  bool node = false;               // a node (or USE / ProtoInstance), not a statement or structure
  std::string containerField;      // of a node in a node's field; empty in Scene, ProtoBody ...
  bool explicitContainer = false;  // the XML printer writes containerField
  bool sfnode = false;             // the value of an SFNode field (JSON: an object, no array)
  std::string source;              // Script source (CDATA / "#sourceCode")
};
/// The <X3D> element of `doc` (head and Scene); values made for it (an EXTERNPROTO's url
/// list, a Script's url without its inline source) go to `owned`, which must outlive it.
XElem xmlDocument(const WDocument& doc, std::deque<FieldValue>& owned);

// ---- the scene (writer_scene.cpp) --------------------------------------------------------

/// The PROTO body an instance of `type` copied: its own, or a resolved EXTERNPROTO's
/// target's; null for built-in types and unresolved EXTERNPROTOs.
const ProtoDefinition* bodyOf(const NodeType* type);
/// The PROTO or EXTERNPROTO type `n` stands for an instance of (expanded, or an unresolved
/// EXTERNPROTO's instance); null for a plain node.
const NodeType* instanceType(const Node& n);
/// The PROTO types of the instances in `d`'s body (with repeats), not looking into the
/// instances' own bodies.
std::vector<const NodeType*> instanceTypesIn(const ProtoDefinition& d);
/// `raw` as a name every encoding reads back as itself (ISO/IEC 19776-2 clause 5.2.3,
/// ISO/IEC 14772-1 annex A.2 IdFirstChar / IdRestChars): each byte that is white space, a
/// control character, a quote, '#', ',', '.', a bracket, a brace or a backslash becomes
/// '_' (as the XML reader spells XML IDs such as "Cube.001"), '_' goes before a leading
/// digit or sign and after a keyword.
std::string classicIdent(std::string_view raw);

// ---- values ------------------------------------------------------------------------------

/// `v` as the Classic encodings write a field value (ISO/IEC 19776-2 clause 5, ISO/IEC
/// 14772-1 clause 5): numbers with the fewest digits that read back the same, SFString
/// quoted, MF values in brackets. Not for SFNode / MFNode. `indent` starts the lines of a
/// long MF value.
std::string classicValue(const FieldValue& v, const std::string& indent);

/// `v` as an XML attribute value before XML escaping (ISO/IEC 19776-1 clause 5): like the
/// Classic text without brackets or commas, SFString raw, MFString as "a" "b" with \" and
/// \\ escaped, booleans `true` / `false`.
std::string xmlValue(const FieldValue& v);

/// Appends the shortest text that reads back as `f` / `d` (std::to_chars).
void appendNumber(std::string& out, float f);
void appendNumber(std::string& out, double d);

/// The numbers of `v` (any type but SFNode, MFNode, SFString, MFString, SFBool, MFBool) as
/// JSON number tokens (ISO/IEC 19776-5 clause 5): the Classic text's numbers in order,
/// SFImage pixels in decimal; each reads back as the same value.
std::vector<std::string> numberTokens(const FieldValue& v);

}  // namespace gs::vrml::writing
