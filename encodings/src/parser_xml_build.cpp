// X3D's XML encoding (ISO/IEC 19776-1) read without Classic VRML text where it can be:
// parseXmlInto() runs XmlToClassic and the Parser side by side, and each plain top-level
// statement (node elements with attributes, DEF/USE, containerField) is built straight
// into nodes by Parser::buildXmlStatement, through the parser's own machinery (DEF scope,
// limits, field lookup, the value readers over each attribute's text, the node class and
// unit rules), so that it gives what the parse of its translation gives. Whatever that
// parse would report, and whatever the XML spells with more than node elements, is
// translated and parsed as before, in document order with the built statements.
#include "base/text.hpp"
#include "parser_impl.hpp"
#include "x3d_numbers.hpp"
#include "x3d_values.hpp"
#include "x3d_xml.hpp"
#include "x3d_xml_tree.hpp"

#include <algorithm>
#include <atomic>

namespace gs::vrml::parsing {

namespace {

// Thrown inside buildXmlStatement when the statement needs its Classic translation.
struct NotPlain {};

// Bytes of space after an attribute value's text, so that the lexer's inline number
// paths (which want 24 bytes ahead) read every number of it.
constexpr std::size_t kValuePadding = 32;

bool blank(std::string_view s) {
  return std::all_of(s.begin(), s.end(), xmlSpace);
}

// Whether an MFString attribute reads as its translation does with nothing to report:
// no backslash that escapes nothing (a warning of the translation) and no '#' outside the
// strings (a comment in the Classic text, which would run past the value).
bool plainMFString(std::string_view v) {
  bool inString = false;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const char c = v[i];
    if (c == '\\' && i + 1 < v.size()) {
      if (v[i + 1] != '"' && v[i + 1] != '\\') return false;
      ++i;
    } else if (c == '"') {
      inString = !inString;
    } else if (c == '#' && !inString) {
      return false;
    }
  }
  return true;
}

// Whether appendXmlIdent() writes `s` as it stands.
bool cleanIdent(std::string_view s) {
  if (s.empty() || isDigit(s[0]) || s[0] == '+' || s[0] == '-') return false;
  for (char c : s)
    if (!isIdRest(c)) return false;
  return true;
}

}  // namespace

struct Parser::XmlBuild {
  Scope& scope;
  const XmlTreeInfo& info;
  std::string expected;  // nodeClassAllowed's answer (unused: a mismatch is not plain)
};

// The member `name` of built-in `type` as parseNodeBody finds it for a value: exact, or
// X3D's alias; an eventIn or eventOut takes no value. Not plain otherwise.
int Parser::xmlMember(const NodeType& type, std::string_view name) {
  int i = findMember(type, name);
  if (i < 0) {
    if (type.findField(name) >= 0) throw NotPlain{};  // set_x / x_changed: an error
    i = x3dFieldAlias(type, name);
    if (i < 0) throw NotPlain{};
  }
  const AccessType a = type.fields[static_cast<std::size_t>(i)].access;
  if (a == AccessType::eventIn || a == AccessType::eventOut) throw NotPlain{};
  return i;
}

// The value of type `t` written as XML attribute text `text`, read as parseValue reads
// its translation (x3d_values.hpp): SFString as it stands, the rest through their Classic
// text with the lexer over it. lex_ is valueLex_ here.
void Parser::xmlValue(Scope& scope, FieldType t, const std::string& text, FieldValue& out) {
  if (xmlNumbers(t, text, out)) return;
  if (t == FieldType::SFString) {
    out.storage().emplace<static_cast<std::size_t>(FieldType::SFString)>(std::string(text));
    return;
  }
  if (t == FieldType::SFNode || t == FieldType::MFNode) throw NotPlain{};
  if (t == FieldType::MFString ? !plainMFString(text) : text.find('#') != std::string_view::npos)
    throw NotPlain{};
  std::string& v = valueText_;
  v.clear();
  if (t == FieldType::MFString || t == FieldType::SFBool || t == FieldType::MFBool) {
    appendXmlValueAsClassic(v, t, text, xmlScratch_);
    if (!xmlScratch_.empty()) throw NotPlain{};  // a lenient MFString: warned
  } else if (isMultiValued(t)) {                 // numbers: as appendXmlValueAsClassic writes them
    v += "[ ";
    v += text;
    v += " ]";
  } else {
    v += text;
  }
  v.append(kValuePadding, ' ');
  lex_.rebind(v);
  int h = 0;
  parseValue(t, out, scope, 0, h);
  if (!lex_.atEnd()) throw NotPlain{};  // more than one value: an error
}

// The number lists of xmlValue in their plain forms (x3d_numbers.hpp), and SFBool and
// the float vectors (SFFloat ... SFRotation) as the lexer reads their one value; false
// when `t` is none of them or the text is not plain.
bool Parser::xmlNumbers(FieldType t, const std::string& text, FieldValue& out) {
  auto& st = out.storage();
  switch (t) {
    case FieldType::SFBool: {
      // One word, true or false in any case (as appendXmlValueAsClassic turns it into
      // TRUE or FALSE for readBool).
      std::string_view w = text;
      while (!w.empty() && xmlSpace(w.front())) w.remove_prefix(1);
      while (!w.empty() && xmlSpace(w.back())) w.remove_suffix(1);
      if (base::equalsNoCase(w, "true")) {
        st.emplace<static_cast<std::size_t>(FieldType::SFBool)>(true);
        return true;
      }
      if (base::equalsNoCase(w, "false")) {
        st.emplace<static_cast<std::size_t>(FieldType::SFBool)>(false);
        return true;
      }
      return false;
    }
    case FieldType::SFFloat:
    case FieldType::SFVec2f:
    case FieldType::SFVec3f:
    case FieldType::SFColor:
    case FieldType::SFRotation: {
      const int n = t == FieldType::SFFloat      ? 1
                    : t == FieldType::SFVec2f    ? 2
                    : t == FieldType::SFRotation ? 4
                                                 : 3;
      if (!readPlainFloats(text.c_str(), n, floatScratch_) ||
          floatScratch_.size() != static_cast<std::size_t>(n))
        return false;
      const float* f = floatScratch_.data();
      if (t == FieldType::SFFloat)
        st.emplace<static_cast<std::size_t>(FieldType::SFFloat)>(f[0]);
      else if (t == FieldType::SFVec2f)
        st.emplace<static_cast<std::size_t>(FieldType::SFVec2f)>(glm::vec2(f[0], f[1]));
      else if (t == FieldType::SFVec3f)
        st.emplace<static_cast<std::size_t>(FieldType::SFVec3f)>(glm::vec3(f[0], f[1], f[2]));
      else if (t == FieldType::SFColor)
        st.emplace<static_cast<std::size_t>(FieldType::SFColor)>(glm::vec3(f[0], f[1], f[2]));
      else
        st.emplace<static_cast<std::size_t>(FieldType::SFRotation)>(
            glm::vec4(f[0], f[1], f[2], f[3]));
      return true;
    }
    default:
      break;
  }
  const int components = plainListComponents(t);
  if (components == 0) return false;
  if (t == FieldType::MFInt32 ? !readPlainInts(text.c_str(), intScratch_)
                              : !readPlainFloats(text.c_str(), components, floatScratch_))
    return false;
  assignPlainList(out, t, intScratch_, floatScratch_);
  return true;
}

// parseNodeStatement + parseNode + parseNodeBody for node element `n` (depth and height
// as there).
NodePtr Parser::xmlNode(XmlBuild& b, const XNode& n, int depth, int& height) {
  if (n.kind != XKind::node) throw NotPlain{};
  Scope& scope = b.scope;
  if (const std::string* use = n.attr("USE")) {
    std::string_view name = *use;
    if (!cleanIdent(name)) {
      xmlName_.clear();
      appendXmlIdent(xmlName_, name);
      name = xmlName_;
    }
    const DefEntry* e = findDef(scope, name);
    if (e == nullptr || e->open) throw NotPlain{};  // unknown, or a cycle
    height = e->height;
    return e->node;
  }
  const NodeType* const xmlType = n.type;
  if (xmlType == nullptr || n.instance || n.source || xmlType->userFields || xmlType->script)
    throw NotPlain{};
  // The type lookupType gives for the name: with no PROTO declared, the built-in one the
  // translator found (kept here by address); else asked (a PROTO of that name is not
  // plain).
  std::shared_ptr<const NodeType> type;
  if (!protosDeclared_)
    for (const auto& t : xmlTypes_)
      if (t.get() == xmlType) type = t;
  if (!type) {
    bool defining = false;
    type = lookupType(scope, n.name, defining);
    if (!type || type.get() != xmlType || type->proto) throw NotPlain{};
    if (!protosDeclared_ && xmlTypes_.size() < 32) xmlTypes_.push_back(type);
  }
  if (recursion_ + 1 > ctx_.options.limits.maxNesting || depth >= ctx_.options.limits.maxNesting ||
      ctx_.nodeCount + 1 > ctx_.options.limits.maxNodes)
    throw NotPlain{};  // fatal there
  ++recursion_;        // (buildXmlStatement restores it)
  ++ctx_.nodeCount;
  auto node = std::make_shared<Node>(std::move(type));
  node->location = SourceLocation{lex_.sourceFile(), n.line, n.column};
  if (ctx_.x3dVersion3) applyX3d3Defaults(*node);
  const NodeType& ty = node->type();
  if (const std::string* def = n.attr("DEF"); def != nullptr && !blank(*def)) {
    node->defName = xmlIdent(*def);
    define(scope, node->defName, DefEntry{node, node->typePtr(), nullptr, 1, true});
  }
  // The attributes, in order: fields (the translation's `name value`).
  for (std::size_t ai = 0; ai < n.attrCount; ++ai) {
    const auto& [k, v] = n.attrStore[ai];
    const bool ignored = xmlIgnoredAttribute(k);
    if (ignored && k != "class" && k != "id" && k != "style") continue;
    int i = findMember(ty, k);
    if (i < 0) {
      // Not the name of a member: HTML's attribute (skipped by the translation unless the
      // type has a field of that name), or an alias, whose value the translation wrote by
      // its own idea of the type.
      const auto t = b.info.fieldTypeOf(n, k);
      if (ignored && !t) continue;
      i = xmlMember(ty, k);
      if (!t || *t != ty.fields[static_cast<std::size_t>(i)].type) throw NotPlain{};
    } else {
      const AccessType a = ty.fields[static_cast<std::size_t>(i)].access;
      if (a == AccessType::eventIn || a == AccessType::eventOut) throw NotPlain{};
    }
    const FieldSpec& spec = ty.fields[static_cast<std::size_t>(i)];
    FieldValue& dst = node->fieldAt(static_cast<std::size_t>(i));
    if (const XNode::Numbers* numbers = n.numbersOf(ai)) {
      if (numbers->type != spec.type) throw NotPlain{};
      assignPlainList(dst, spec.type, numbers->ints, numbers->floats);
    } else {
      xmlValue(scope, spec.type, v, dst);
    }
    if (ctx_.units.angle != 1.0) applyAngleUnit(spec, dst);
  }
  // The child elements, grouped by containerField in the order the groups first appear.
  const auto level = static_cast<std::size_t>(recursion_);
  while (xmlGroups_.size() <= level) xmlGroups_.push_back(std::make_unique<XmlGroups>());
  XmlGroups& gs = *xmlGroups_[level];
  gs.used = 0;
  for (const XNode* c : n.children) {
    if (c->kind != XKind::node) throw NotPlain{};  // ROUTE, IS, field ...: translated
    // The usual case first: the child's default field, which the parent has (what the
    // translator's containerFieldOf answers then); the rest asked of the translator.
    std::string_view field;
    int member = -1;
    if (const NodeModel* m = c->model;
        m != nullptr && !c->instance && !m->containerField.empty() && !metadataName(c->name) &&
        c->attr("containerField") == nullptr && (member = findMember(ty, m->containerField)) >= 0) {
      field = m->containerField;
      const AccessType a = ty.fields[static_cast<std::size_t>(member)].access;
      if (a == AccessType::eventIn || a == AccessType::eventOut) member = -1;
    } else {
      field = b.info.containerField(*c, n);
      member = -1;
    }
    std::size_t g = 0;
    while (g < gs.used && gs.groups[g].field != field) ++g;
    if (g == gs.used) {
      if (g == gs.groups.size()) gs.groups.emplace_back();
      gs.groups[g].field = field;
      gs.groups[g].member = member;
      gs.groups[g].nodes.clear();
      ++gs.used;
    }
    gs.groups[g].nodes.push_back(c);
  }
  int h = 0;
  const bool check = ty.builtIn && !ty.extension && !ty.userFields;
  for (std::size_t g = 0; g < gs.used; ++g) {
    // (gs stays put: deeper levels have their own entries.)
    const XmlGroup& group = gs.groups[g];
    // (The translation writes the name as an identifier: no field has a name it changes.)
    int i = group.member;
    if (i < 0) {
      if (!cleanIdent(group.field)) throw NotPlain{};
      i = xmlMember(ty, group.field);
    }
    const FieldSpec& spec = ty.fields[static_cast<std::size_t>(i)];
    const bool list = spec.type == FieldType::MFNode;
    if (!list && (spec.type != FieldType::SFNode || group.nodes.size() != 1)) throw NotPlain{};
    FieldValue& dst = node->fieldAt(static_cast<std::size_t>(i));
    auto one = [&](const XNode& c) {
      int ch = 0;
      NodePtr child = xmlNode(b, c, depth + 1, ch);
      h = std::max(h, ch);
      if (check && !nodeClassAllowed(&ty, spec.name, child->type(), b.expected)) throw NotPlain{};
      return child;
    };
    if (list) {
      auto& v = dst.storage().emplace<static_cast<std::size_t>(FieldType::MFNode)>();
      v.reserve(group.nodes.size());
      for (const XNode* c : group.nodes) v.push_back(one(*c));
    } else {
      NodePtr child = one(*group.nodes.front());
      dst.storage().emplace<static_cast<std::size_t>(FieldType::SFNode)>(std::move(child));
    }
  }
  --recursion_;
  height = h + 1;
  if (node->typeId() == NodeTypeId::Inline) {
    const FieldValue* url = node->field("url");
    if (url != nullptr && url->type() == FieldType::MFString)
      for (const std::string& u : url->get<FieldType::MFString>())
        if (urlNamesFile(lex_.file(), u)) throw NotPlain{};  // an error there
  }
  closeDef(scope, node->defName, *node, height);
  return node;
}

bool Parser::buildXmlStatement(Scope& top, const XNode& root, const XmlTreeInfo& info,
                               std::vector<NodePtr>& roots) {
  if (giveUp_ || tableMode_) return false;
  // DEF names go through define(), logged so that a statement found not plain half-way
  // leaves nothing behind.
  ScopeUndo local;
  struct BuildState {
    Parser& p;
    Scope& top;
    ScopeUndo* undo;
    std::size_t mark;
    std::size_t nodes;
    int recursion;
    bool done = false;
    BuildState(Parser& parser, Scope& s, ScopeUndo& own)
        : p(parser),
          top(s),
          undo(s.undo),
          mark(s.undo != nullptr ? s.undo->defs.size() : 0),
          nodes(parser.ctx_.nodeCount),
          recursion(parser.recursion_) {
      if (top.undo == nullptr) top.undo = &own;
      p.lex_.swapText(p.valueLex_);
    }
    ~BuildState() {
      p.lex_.swapText(p.valueLex_);
      p.recursion_ = recursion;
      ScopeUndo& log = *top.undo;
      if (!done) {
        for (std::size_t i = log.defs.size(); i > mark; --i) {
          auto& [name, before] = log.defs[i - 1];
          if (before)
            top.defs[name] = std::move(*before);
          else
            top.defs.erase(name);
        }
        log.defs.resize(mark);
        p.ctx_.nodeCount = nodes;
      }
      top.undo = undo;
    }
    BuildState(const BuildState&) = delete;
    BuildState& operator=(const BuildState&) = delete;
  } state(*this, top, local);
  XmlBuild b{top, info, {}};
  NodePtr n;
  try {
    int h = 0;
    n = xmlNode(b, root, 0, h);
    if (top.checkRoots && !nodeClassAllowed(nullptr, {}, n->type(), b.expected)) return false;
  } catch (const NotPlain&) {
    return false;
  } catch (const ParseError&) {
    return false;  // (a value that does not read: reported by the parse of the translation)
  }
  state.done = true;
  if (top.x3d != nullptr && ctx_.units.length != 1.0) n = applyLengthUnit(n);
  roots.push_back(std::move(n));
  if (top.checkRoots && ctx_.options.onRootNode) ctx_.options.onRootNode(roots.back());
  return true;
}

namespace {

// parseInto's reader of an XML document: the translator fed the whole text, the parser
// run over the Classic text as it grows, each time a statement is to be built (so that
// every statement before it is in the scene), and at the end.
class XmlDocument final : public XmlStatementBuilder {
 public:
  XmlDocument(const std::string& url, Context& ctx, int externDepth, Scene& scene,
              std::string& classic, XmlToClassic& xml)
      : url_(url),
        ctx_(ctx),
        externDepth_(externDepth),
        scene_(scene),
        classic_(classic),
        xml_(xml),
        wasX3d_(ctx.x3d),
        wasUnits_(ctx.units) {}
  ~XmlDocument() {
    ctx_.x3d = wasX3d_;
    ctx_.units = wasUnits_;
  }
  XmlDocument(const XmlDocument&) = delete;
  XmlDocument& operator=(const XmlDocument&) = delete;

  bool build(const XNode& root, const XmlTreeInfo& info) override {
    if (!parsePending(false)) return false;
    return parser_->buildXmlStatement(top_, root, info, scene_.rootNodes);
  }

  /// The document ended: parses what is left and ends the scene as parseScene does.
  void finish() {
    if (parsePending(true)) parser_->endScene(nullptr);
    if (!headerProblem_.empty()) scene_.diagnostics.error({url_, 1, 1}, std::move(headerProblem_));
  }

 private:
  // Starts the parser once the header is written (as parseInto reads a header); false
  // when it cannot run (no header yet, a bad one, or the parse stopped).
  bool start() {
    if (parser_ || stopped_) return parser_ != nullptr && !stopped_;
    if (!xml_.wroteHeader()) return false;
    const std::string_view all(classic_);
    const std::size_t eol = all.find_first_of("\r\n");
    const std::string_view line = all.substr(0, eol);
    std::string version;
    headerProblem_ = headerProblem(line, version);
    if (!headerProblem_.empty()) {
      stopped_ = true;
      return false;
    }
    ctx_.units = {};
    ctx_.x3d = !version.empty();
    ctx_.x3dVersion3 = version.starts_with("3");
    if (ctx_.x3d) scene_.x3d.version = version;
    parser_ = std::make_unique<Parser>(all, url_, eol == std::string_view::npos ? all.size() : eol,
                                       ctx_, scene_.diagnostics, externDepth_, &xml_.origin());
    top_.routes = &scene_.routes;
    top_.hidden = &scene_.hiddenNodes;
    top_.declared = &scene_.protos;
    top_.x3d = &scene_.x3d;
    top_.checkRoots = externDepth_ == 0;
    return true;
  }

  // Parses the statements translated since the last call; false when the parser does not
  // run (or stopped: a fatal error, reported as parseScene reports it).
  bool parsePending(bool final) {
    if (!start()) return false;
    if (!final && classic_.size() == parsedSize_) return true;  // nothing new
    parsedSize_ = classic_.size();
    parser_->extendText(classic_, final);
    try {
      while (parser_->parseTopStatement(top_, scene_.rootNodes)) {
      }
    } catch (const ParseError& e) {
      parser_->endScene(&e);
      stopped_ = true;
      return false;
    }
    return true;
  }

  const std::string& url_;
  Context& ctx_;
  int externDepth_;
  Scene& scene_;
  std::string& classic_;
  XmlToClassic& xml_;
  bool wasX3d_;
  Context::Units wasUnits_;
  std::unique_ptr<Parser> parser_;
  Scope top_;
  bool stopped_ = false;
  std::size_t parsedSize_ = 0;  // size of the Classic text when it was last parsed
  std::string headerProblem_;
};

}  // namespace

namespace {
std::atomic<bool> gXmlDirectBuild{true};
}  // namespace

bool xmlDirectBuild() {
  return gXmlDirectBuild.load(std::memory_order_relaxed);
}

void setXmlDirectBuild(bool on) {
  gXmlDirectBuild.store(on, std::memory_order_relaxed);
}

void parseXmlInto(std::string_view bytes, const std::string& url, Context& ctx, int externDepth,
                  Scene& scene) {
  const std::size_t before = scene.diagnostics.items.size();
  std::string classic;
  XmlToClassic xml(classic, url, ctx.options.limits.maxNesting);
  {
    XmlDocument doc(url, ctx, externDepth, scene, classic, xml);
    if (xmlDirectBuild()) xml.setBuilder(&doc);
    xml.feed(bytes, true);
    doc.finish();
    xml.setBuilder(nullptr);
  }
  // The translation's warnings first, as when the whole translation was parsed after it.
  xml.addWarnings(scene, before);
  scene.x3d.encoding = "XML";
  if (xml.failed()) scene.diagnostics.items.push_back(xml.fatalError());
}

}  // namespace gs::vrml::parsing
