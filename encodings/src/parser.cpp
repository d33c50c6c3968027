// Statements and nodes (annex A.3 "Nodes" grammar: vrmlScene, statements, nodeStatement,
// node, nodeBody, scriptBody), DEF/USE (clause 4.6.2) and error recovery; the entry points
// are parse_entry.cpp's.
#include "parser_impl.hpp"

#include <algorithm>
#include <cstring>

namespace gs::vrml::parsing {

namespace {

constexpr std::size_t kMaxDiagnostics = 1000;
constexpr std::size_t kMaxScriptMembers = 4096;

bool isAccessKeyword(std::string_view s) {
  AccessType a;
  return accessTypeFromName(s, a);
}

bool isStatementKeyword(std::string_view s) {
  return s == "PROTO" || s == "EXTERNPROTO" || s == "ROUTE";
}

}  // namespace

Parser::Parser(std::string_view text, std::string file, std::size_t start, Context& ctx,
               Diagnostics& diag, int externDepth, TextOrigin* origin)
    : lex_(text, file, start),
      ctx_(ctx),
      diag_(diag),
      externDepth_(externDepth),
      valueLex_({}, std::move(file)) {
  lex_.setOrigin(origin);
}

// At most kMaxDiagnostics are kept (the rest are counted and summarised at the end);
// that many errors end the parse, since the input is then most likely not VRML at all.
void Parser::report(Severity s, std::size_t offset, std::string message) {
  if (s == Severity::error && ++errors_ >= kMaxDiagnostics) giveUp_ = true;
  if (diag_.items.size() >= kMaxDiagnostics) {
    ++suppressed_;
    return;
  }
  diag_.items.push_back({s, lex_.locationAt(offset), std::move(message)});
}

void Parser::report(const ParseError& e) {
  if (++errors_ >= kMaxDiagnostics) giveUp_ = true;
  if (diag_.items.size() >= kMaxDiagnostics) {
    ++suppressed_;
    return;
  }
  diag_.items.push_back(e.diagnostic);
}

void Parser::countNode(std::size_t offset) {
  if (++ctx_.nodeCount > ctx_.options.limits.maxNodes)
    lex_.fatal(offset, "more than " + std::to_string(ctx_.options.limits.maxNodes) +
                           " nodes (ParseLimits::maxNodes)");
}

void Parser::enter(std::size_t offset) {
  if (++recursion_ > ctx_.options.limits.maxNesting)
    lex_.fatal(offset, "nodes nested deeper than " +
                           std::to_string(ctx_.options.limits.maxNesting) +
                           " levels (ParseLimits::maxNesting)");
}

void Parser::parseScene(Scene& scene) {
  Scope top;
  top.routes = &scene.routes;
  top.hidden = &scene.hiddenNodes;
  top.declared = &scene.protos;
  top.x3d = &scene.x3d;
  top.checkRoots = externDepth_ == 0;
  try {
    parseStatements(top, &scene.rootNodes, 0, false, nullptr);
  } catch (const ParseError& e) {
    endScene(&e);
    return;
  }
  endScene(nullptr);
}

void Parser::endScene(const ParseError* fatal) {
  if (fatal != nullptr && !giveUp_) report(*fatal);
  if (giveUp_)
    diag_.items.push_back(
        {Severity::error, lex_.locationAt(lex_.offset()),
         "too many errors (" + std::to_string(kMaxDiagnostics) + "): giving up on this file"});
  if (suppressed_ > 0)
    diag_.items.push_back({Severity::warning,
                           {lex_.file(), 0, 0},
                           std::to_string(suppressed_) + " more diagnostics not shown (at most " +
                               std::to_string(kMaxDiagnostics) + " are kept)"});
}

// statements ::= statement*; statement ::= nodeStatement | protoStatement | routeStatement
void Parser::parseStatements(Scope& scope, std::vector<NodePtr>* nodes, int depth, bool untilBrace,
                             int* height) {
  const std::size_t open = lex_.offset();
  while (true) {
    if (giveUp_) throw ParseError(Diagnostic{Severity::error, {}, "giving up"});
    const Token t = lex_.peek();
    if (t.kind == Tok::end) {
      if (untilBrace)
        lex_.fatal(t.offset, "unexpected end of file: missing '}' for the PROTO body opened at " +
                                 std::to_string(lex_.locationAt(open).line) + ":" +
                                 std::to_string(lex_.locationAt(open).column));
      return;
    }
    if (untilBrace && t.kind == Tok::rbrace) {
      lex_.consume(t);
      return;
    }
    parseStatement(scope, nodes, depth, height, t);
  }
}

bool Parser::parseTopStatement(Scope& top, std::vector<NodePtr>& roots) {
  if (giveUp_) throw ParseError(Diagnostic{Severity::error, {}, "giving up"});
  const Token t = lex_.peek();
  if (t.kind == Tok::end) return false;
  parseStatement(top, &roots, 0, nullptr, t);
  return true;
}

void Parser::parseStatement(Scope& scope, std::vector<NodePtr>* nodes, int depth, int* height,
                            const Token& t) {
  try {
    if (t.kind != Tok::id) lex_.failExpected(t.offset, "a node, PROTO, EXTERNPROTO or ROUTE");
    if (t.text == "PROTO") {
      parseProto(scope);
    } else if (ctx_.x3d && parseX3dStatement(scope, t)) {
    } else if (t.text == "EXTERNPROTO") {
      parseExternProto(scope);
    } else if (t.text == "ROUTE") {
      parseRoute(scope);
    } else {
      int h = 0;
      NodePtr n = parseNodeStatement(scope, depth, h, false);
      if (n) {
        if (height != nullptr) *height = std::max(*height, h);
        if (scope.checkRoots) checkNodeClass(nullptr, {}, n, t.offset);
        if (scope.x3d != nullptr) n = applyLengthUnit(n);
        nodes->push_back(n);
        if (scope.checkRoots && ctx_.options.onRootNode) ctx_.options.onRootNode(n);
      }
    }
  } catch (const RecoverableError& e) {
    report(e);
    if (lex_.offset() <= t.offset) {
      lex_.setOffset(t.offset);
      lex_.skipBalanced();
    }
  }
}

// nodeStatement ::= node | DEF nodeNameId node | USE nodeNameId (and NULL for SFNode)
NodePtr Parser::parseNodeStatement(Scope& scope, int depth, int& height, bool allowNull) {
  const Token t = lex_.peek();
  if (t.kind != Tok::id) lex_.failExpected(t.offset, "a node");
  if (t.text == "NULL") {
    lex_.consume(t);
    if (!allowNull) lex_.fail(t.offset, "NULL is not allowed here");
    height = 0;
    return nullptr;
  }
  if (t.text == "USE") {
    lex_.consume(t);
    const Token nt = lex_.peek();
    const std::string_view name = lex_.expectId("a DEF name after USE");
    const DefEntry* found = findDef(scope, name);
    if (found == nullptr)
      lex_.fail(nt.offset, "USE of unknown DEF name '" + std::string(name) + "'");
    const DefEntry& e = *found;
    if (e.open) {
      // A back reference to a node still being read: allowed from a Script's fields
      // (clause 6.40), a cycle anywhere else. Stored without ownership so the cycle
      // does not keep the nodes alive.
      if (!e.node->type().script && recursion_ != scriptValueRecursion_)
        lex_.fail(nt.offset,
                  "USE '" + std::string(name) + "' inside its own definition would make a cycle");
      height = 0;
      return NodePtr(NodePtr(), e.node.get());
    }
    height = e.height;
    return e.node;
  }
  if (t.text == "DEF") {
    lex_.consume(t);
    const std::string_view defName = lex_.expectId("a DEF name");
    return parseNode(scope, lex_.peek(), depth, height, defName);
  }
  return parseNode(scope, t, depth, height, {});
}

void Parser::define(Scope& scope, std::string_view name, DefEntry e) {
  if (scope.undo == nullptr) {
    scope.defs[std::string(name)] = std::move(e);
    return;
  }
  auto [it, added] = scope.defs.try_emplace(std::string(name));
  scope.undo->defs.emplace_back(it->first,
                                added ? std::nullopt : std::optional<DefEntry>(it->second));
  it->second = std::move(e);
}

void Parser::setProto(Scope& scope, const std::string& name, std::shared_ptr<const NodeType> type) {
  if (scope.undo == nullptr) {
    scope.protos[name] = std::move(type);
    return;
  }
  auto [it, added] = scope.protos.try_emplace(name);
  scope.undo->protos.emplace_back(
      name, added ? std::nullopt : std::optional<std::shared_ptr<const NodeType>>(it->second));
  it->second = std::move(type);
}

void Parser::eraseProto(Scope& scope, const std::string& name) {
  auto it = scope.protos.find(name);
  if (it == scope.protos.end()) return;
  if (scope.undo != nullptr) scope.undo->protos.emplace_back(name, it->second);
  scope.protos.erase(it);
}

void Parser::closeDef(Scope& scope, std::string_view name, const Node& node, int height) {
  if (name.empty()) return;
  auto it = scope.defs.find(name);
  if (it != scope.defs.end() && it->second.node.get() == &node) {
    it->second.open = false;
    it->second.height = height;
    it->second.declared = node.typePtr();
  }
}

DefEntry* Parser::findDef(Scope& scope, std::string_view name) {
  for (Scope* s = &scope; s != nullptr; s = s->defParent) {
    auto it = s->defs.find(name);
    if (it != s->defs.end()) return &it->second;
  }
  return nullptr;
}

std::shared_ptr<const NodeType> Parser::lookupType(Scope& scope, std::string_view name,
                                                   bool& defining) {
  for (Scope* s = protosDeclared_ ? &scope : nullptr; s != nullptr; s = s->parent) {
    auto it = s->protos.find(name);
    if (it != s->protos.end()) {
      if (!it->second) defining = true;
      return it->second;
    }
  }
  // A small cache in front of the built-in table: a file uses few node types, and they
  // differ in length, first or last byte.
  TypeCacheEntry& e = typeCache_[(name.size() + static_cast<unsigned char>(name.front()) * 5u +
                                  static_cast<unsigned char>(name.back()) * 3u +
                                  static_cast<unsigned char>(name[name.size() / 2]) * 11u) &
                                 (typeCache_.size() - 1)];
  if (e.type && sameName(e.type->name, name)) return e.type;
  std::shared_ptr<const NodeType> t = ctx_.x3d ? x3dNodeType(name) : builtInNodeType(name);
  if (t) e.type = t;
  return t;
}

// node ::= nodeTypeId { nodeBody } | Script { scriptBody }
NodePtr Parser::parseNode(Scope& scope, const Token& t, int depth, int& height,
                          std::string_view defName) {
  if (t.kind != Tok::id) lex_.failExpected(t.offset, "a node type name");
  if (tableMode_) lex_.fatal(t.offset, "nodes are not allowed in the node table");
  lex_.consume(t);
  bool defining = false;
  std::shared_ptr<const NodeType> type = lookupType(scope, t.text, defining);
  if (!type) {
    report(Severity::error, t.offset,
           defining ? "PROTO '" + std::string(t.text) + "' is used inside its own definition"
                    : "unknown node type '" + std::string(t.text) + "'");
    if (lex_.peekChar() == '{') lex_.skipBalanced();
    height = 0;
    return nullptr;
  }
  struct Guard {
    int& r;
    ~Guard() { --r; }
  };
  enter(t.offset);
  Guard guard{recursion_};
  if (depth >= ctx_.options.limits.maxNesting)
    lex_.fatal(t.offset, "nodes nested deeper than " +
                             std::to_string(ctx_.options.limits.maxNesting) +
                             " levels (ParseLimits::maxNesting)");

  if (type->proto) {
    InstanceValues inst;
    inst.type = type;
    inst.location = lex_.locationAt(t.offset);
    inst.values.reserve(type->fields.size());
    for (const FieldSpec& f : type->fields) inst.values.push_back(f.defaultValue);
    inst.given.assign(type->fields.size(), 0);
    parseNodeBody(scope, nullptr, &inst, depth, inst.valueHeight);
    std::shared_ptr<const std::vector<IsConnection>> links;
    NodePtr n = instantiate(scope, inst, t.offset, depth, height, links);
    if (n && !defName.empty()) {
      n->defName = defName;
      define(scope, defName, DefEntry{n, type, links, height, false});
    }
    return n;
  }

  countNode(t.offset);
  auto node = std::make_shared<Node>(std::move(type));
  node->location = lex_.locationAt(t.offset);
  if (ctx_.x3dVersion3) applyX3d3Defaults(*node);
  if (!defName.empty()) {
    node->defName = defName;
    define(scope, defName, DefEntry{node, node->typePtr(), nullptr, 1, true});
  }
  // Close the DEF entry however the body ends (a body cut short by an error still
  // leaves a node that later USEs may share).
  // (It holds the Node by address: `return node` moves the NodePtr out before this runs.)
  struct Closer {
    Scope& scope;
    std::string_view name;
    const Node* node;
    int& height;
    ~Closer() { closeDef(scope, name, *node, height); }
  } closer{scope, defName, node.get(), height};
  height = 1;
  int h = 0;
  parseNodeBody(scope, node, nullptr, depth, h);
  height = h + 1;
  if (node->typeId() == NodeTypeId::Inline) checkInline(*node, t.offset);
  return node;
}

// nodeBody ::= nodeBodyElement*; nodeBodyElement ::= fieldId fieldValue | fieldId IS id |
// eventInId IS id | eventOutId IS id | routeStatement | protoStatement
void Parser::parseNodeBody(Scope& scope, const NodePtr& node, InstanceValues* inst, int depth,
                           int& height) {
  if (lex_.peekChar() != '{') lex_.failExpected(lex_.offset(), "'{'");
  const std::size_t open = lex_.offset();
  lex_.setOffset(open + 1);
  // The members a Script node declares (clause 6.40); made only for Script nodes.
  std::unique_ptr<ScriptBuild> scriptBuild;
  if (node && node->type().userFields) scriptBuild = std::make_unique<ScriptBuild>();
  static ScriptBuild noScript;  // never written: only Script nodes declare members
  ScriptBuild& script = scriptBuild ? *scriptBuild : noScript;
  while (true) {
    if (giveUp_) throw ParseError(Diagnostic{Severity::error, {}, "giving up"});
    const NodeType& ty = script.type ? *script.type : node ? node->type() : *inst->type;
    const Token t = lex_.peek();
    if (t.kind == Tok::rbrace) {
      lex_.consume(t);
      if (script.type) retype(*node, script.type, script.values);
      return;
    }
    if (t.kind == Tok::end) {
      const SourceLocation at = lex_.locationAt(open);
      lex_.fatal(t.offset, "unexpected end of file: missing '}' for the " + ty.name +
                               " node opened at " + std::to_string(at.line) + ":" +
                               std::to_string(at.column));
    }
    try {
      if (t.kind != Tok::id) lex_.failExpected(t.offset, "a field name or '}'");
      if (isStatementKeyword(t.text)) {
        if (t.text == "PROTO")
          parseProto(scope);
        else if (t.text == "EXTERNPROTO")
          parseExternProto(scope);
        else
          parseRoute(scope);
        continue;
      }
      lex_.consume(t);
      if (node && ty.userFields && isAccessKeyword(t.text)) {
        parseScriptDeclaration(scope, node, t, depth, height, script);
        continue;
      }
      int i = -1;
      if (inst != nullptr) {
        i = memberIndex(inst->type, t.text);
      } else if (script.type) {
        auto it = script.names.find(t.text);
        i = it != script.names.end() ? it->second : findMember(node->type(), t.text);
      } else {
        i = findMember(ty, t.text);
      }
      AccessType access = AccessType::field;
      if (i >= 0) {
        access = ty.fields[static_cast<std::size_t>(i)].access;
      } else if ((i = ty.findField(t.text)) >= 0) {
        access = t.text.starts_with("set_") ? AccessType::eventIn : AccessType::eventOut;
      } else if (ctx_.x3d && (i = x3dFieldAlias(ty, t.text)) >= 0) {
        access = ty.fields[static_cast<std::size_t>(i)].access;
      } else {
        report(Severity::error, t.offset,
               "unknown field '" + std::string(t.text) + "' in " + ty.name);
        skipUnknownValue(ty);
        continue;
      }
      if (lex_.peekChar() == 'I' && lex_.acceptKeyword("IS")) {
        parseIs(scope, ty, i, access, t.text, t.offset, node, inst);
        continue;
      }
      if (access == AccessType::eventIn || access == AccessType::eventOut) {
        report(Severity::error, t.offset,
               "cannot give a value to " + std::string(accessTypeName(access)) + " '" +
                   std::string(t.text) + "' of " + ty.name);
        skipUnknownValue(ty);
        continue;
      }
      const auto ui = static_cast<std::size_t>(i);
      const FieldSpec& spec = ty.fields[ui];
      FieldValue& dst = inst != nullptr           ? inst->values[ui]
                        : ui < node->fieldCount() ? node->fieldAt(ui)
                                                  : script.values[ui - node->fieldCount()];
      const bool check = node && ty.builtIn && !ty.extension && !ty.userFields;
      int h = 0;
      parseValue(spec.type, dst, scope, depth, h, check ? &ty : nullptr, spec.name);
      if (ctx_.units.angle != 1.0) applyAngleUnit(spec, dst);
      height = std::max(height, h);
      if (inst != nullptr) inst->given[ui] = 1;
    } catch (const RecoverableError& e) {
      report(e);
      resync(script.type ? script.type.get() : node ? &node->type() : inst->type.get());
      if (lex_.offset() <= t.offset) {
        lex_.setOffset(t.offset);
        lex_.skipBalanced();
      }
    }
  }
}

// fieldType ::= MFColor | MFFloat | ... | SFVec3f (the 20 names of clause 5).
FieldType Parser::parseFieldTypeName() {
  const Token tt = lex_.peek();
  const std::string_view typeName = lex_.expectId("a field type");
  FieldType ft = FieldType::SFBool;
  if (fieldTypeFromName(typeName, ft)) return ft;
  // VRML 1.0's SFLong / MFLong, still found in castle's X3D shader worlds: SFInt32 / MFInt32.
  // castle-engine reads them as those in X3D worlds without a word, so an X3D world does
  // too; a VRML97 world (which never had them) is told.
  if (typeName == "SFLong" || typeName == "MFLong") {
    if (!ctx_.x3d)
      report(Severity::warning, tt.offset,
             std::string(typeName) + " is VRML 1.0's name: read as " +
                 (typeName == "SFLong" ? "SFInt32" : "MFInt32"));
    return typeName == "SFLong" ? FieldType::SFInt32 : FieldType::MFInt32;
  }
  lex_.fail(tt.offset, "unknown field type '" + std::string(typeName) + "'");
}

// scriptBodyElement ::= nodeBodyElement | restrictedInterfaceDeclaration |
// eventIn fieldType eventInId IS eventInId | eventOut ... | field fieldType fieldId IS fieldId
void Parser::parseScriptDeclaration(Scope& scope, const NodePtr& node, const Token& keyword,
                                    int depth, int& height, ScriptBuild& script) {
  AccessType a = AccessType::field;
  accessTypeFromName(keyword.text, a);
  const FieldType ft = parseFieldTypeName();
  const Token nt = lex_.peek();
  const std::string name(lex_.expectId("a field name"));
  const Token after = lex_.peek();
  const bool isRef = after.kind == Tok::id && after.text == "IS";
  const bool hasValue = !isRef && (a == AccessType::field || a == AccessType::exposedField);
  const NodeType& base = node->type();  // the built-in Script type until the body ends
  std::string problem;
  Severity severity = Severity::error;
  const auto earlier = script.names.find(name);
  if (a == AccessType::exposedField && !ctx_.x3d && node->type().script) {
    problem = "exposedField is not allowed in a Script node (clause 6.40)";
  } else if (earlier != script.names.end() &&
             script.type->fields[static_cast<std::size_t>(earlier->second)].access == a &&
             script.type->fields[static_cast<std::size_t>(earlier->second)].type == ft) {
    // An identical second declaration (NIST and Sourcebook worlds have them): read as the
    // first, as Coin3D and castle-model-viewer do.
    severity = Severity::warning;
    problem = "'" + name + "' is declared twice in this Script node; the second is ignored";
  } else if (const int own = base.findField(name);
             own >= 0 && earlier == script.names.end() && ctx_.x3d && !isRef &&
             base.fields[static_cast<std::size_t>(own)].type == ft) {
    // A declaration of one of X3D 4's own Script fields (`description`, in X_ITE's test
    // worlds written before X3D 4 gave Script one) with its type: its value is the field's.
    report(Severity::warning, nt.offset,
           "'" + name + "' is the Script node's own field in X3D 4: the declaration sets it");
    if (hasValue) {
      int h = 0;
      parseValue(ft, node->fieldAt(static_cast<std::size_t>(own)), scope, depth, h);
      height = std::max(height, h);
    }
    return;
  } else if (earlier != script.names.end() || base.findField(name) >= 0) {
    problem = "'" + name + "' is already declared in this Script node";
  } else if (script.names.size() >= kMaxScriptMembers)
    problem =
        "more than " + std::to_string(kMaxScriptMembers) + " fields and events in one Script node";
  if (!problem.empty()) {
    report(severity, a == AccessType::exposedField ? keyword.offset : nt.offset, problem);
    if (isRef) {
      lex_.consume(after);
      lex_.expectId("an interface name after IS");
    } else if (hasValue) {
      skipUnknownValue(script.type ? *script.type : base);
    }
    return;
  }
  // The per-instance type is built here and given to the node when its body ends
  // (parseNodeBody), so many declarations cost linear time.
  if (!script.type) script.type = std::make_shared<NodeType>(base);
  script.type->fields.push_back(FieldSpec{name, ft, a, FieldValue(ft)});
  script.values.emplace_back(ft);
  const int index = static_cast<int>(script.type->fields.size()) - 1;
  script.names.emplace(name, index);
  if (isRef) {
    lex_.consume(after);
    parseIs(scope, *script.type, index, a, name, nt.offset, node, nullptr);
    return;
  }
  if (hasValue) {
    int h = 0;
    // A node named directly as the value may be any node still being read (a Script's
    // field USEs an ancestor: clause 6.40, castle's node_cycle_in_script.x3d).
    const int outer = scriptValueRecursion_;
    scriptValueRecursion_ = recursion_;
    try {
      parseValue(ft, script.values.back(), scope, depth, h);
    } catch (...) {
      scriptValueRecursion_ = outer;
      throw;
    }
    scriptValueRecursion_ = outer;
    height = std::max(height, h);
  }
}

void Parser::retype(Node& node, std::shared_ptr<const NodeType> type,
                    std::vector<FieldValue>& extra) {
  Node fresh(std::move(type));
  const std::size_t n = node.fieldCount();
  for (std::size_t i = 0; i < n; ++i) fresh.fieldAt(i) = std::move(node.fieldAt(i));
  for (std::size_t k = 0; k < extra.size() && n + k < fresh.fieldCount(); ++k)
    fresh.fieldAt(n + k) = std::move(extra[k]);
  fresh.defName = std::move(node.defName);
  fresh.protoInstance = std::move(node.protoInstance);
  fresh.unresolved = node.unresolved;
  fresh.location = std::move(node.location);
  node = std::move(fresh);  // same address: USE back references stay valid
}

int Parser::memberIndex(const std::shared_ptr<const NodeType>& type, std::string_view name) {
  if (type->fields.size() <= 16) return findMember(*type, name);
  auto it = bigIndex_.find(type.get());
  if (it == bigIndex_.end()) {
    MemberIndex index;
    index.keep = type;  // keeps the address from being reused during the parse
    for (std::size_t i = 0; i < type->fields.size(); ++i)
      index.names.try_emplace(type->fields[i].name, static_cast<int>(i));
    it = bigIndex_.emplace(type.get(), std::move(index)).first;
  }
  auto f = it->second.names.find(name);
  return f == it->second.names.end() ? -1 : f->second;
}

// `member IS interfaceMember` (clause 4.8.3): only inside a PROTO body, same type, and
// access types compatible per table 4.4 (an exposedField connects to anything, other
// members only to their own kind).
void Parser::parseIs(Scope& scope, const NodeType& type, int index, AccessType access,
                     std::string_view asWritten, std::size_t offset, const NodePtr& node,
                     InstanceValues* inst) {
  const Token nt = lex_.peek();
  const std::string_view name = lex_.expectId("an interface name after IS");
  if (scope.proto == nullptr) {
    report(Severity::error, offset,
           "IS statement outside a PROTO body: '" + std::string(asWritten) + " IS " +
               std::string(name) + "'");
    return;
  }
  const NodeType& iface = *scope.proto->type;
  const int j = iface.findExact(name);
  if (j < 0) {
    report(Severity::error, nt.offset,
           "'" + std::string(name) + "' is not in the interface of PROTO '" + iface.name + "'");
    return;
  }
  const FieldSpec& outer = iface.fields[static_cast<std::size_t>(j)];
  const FieldSpec& inner = type.fields[static_cast<std::size_t>(index)];
  if (outer.type != inner.type) {
    report(Severity::error, nt.offset,
           "IS type mismatch: '" + std::string(asWritten) + "' of " + type.name + " is " +
               std::string(fieldTypeName(inner.type)) + " but '" + outer.name + "' of PROTO " +
               iface.name + " is " + std::string(fieldTypeName(outer.type)));
    return;
  }
  // Leniency: a field connected to an eventIn of the interface is accepted without a
  // diagnostic (castle's prototypes/proto_other.wrl; Coin3D and castle read it too); it
  // carries no value.
  const bool lenient = access == AccessType::field && outer.access == AccessType::eventIn;
  if (access != AccessType::exposedField && access != outer.access && !lenient) {
    report(Severity::error, nt.offset,
           "IS access mismatch: " + std::string(accessTypeName(access)) + " '" +
               std::string(asWritten) + "' of " + type.name + " cannot be connected to " +
               std::string(accessTypeName(outer.access)) + " '" + outer.name + "' (clause 4.8.3)");
    return;
  }
  if (node)
    scope.proto->def->connections.push_back(IsConnection{node, index, access, j});
  else
    inst->isRefs.push_back(IsConnection{nullptr, index, access, j});
}

// After an unknown field or a value that may not be given: skip what follows. A '[' list
// or a `Type { ... }` node is skipped whole; anything else token by token up to the next
// field of this node or its '}'.
void Parser::skipUnknownValue(const NodeType& type) {
  const Token t = lex_.peek();
  if (t.kind == Tok::lbracket || t.kind == Tok::lbrace) {
    lex_.skipBalanced();
    return;
  }
  if (t.kind == Tok::id && type.findField(t.text) < 0 && !isStatementKeyword(t.text)) {
    lex_.consume(t);
    if (lex_.peek().kind == Tok::lbrace) {
      lex_.skipBalanced();
      return;
    }
    lex_.setOffset(t.offset);
  }
  resync(&type);
}

void Parser::resync(const NodeType* type) {
  while (true) {
    const Token t = lex_.peek();
    if (t.kind == Tok::end || t.kind == Tok::rbrace) return;
    if (t.kind == Tok::id) {
      if (isStatementKeyword(t.text)) return;
      if (type != nullptr &&
          (type->findField(t.text) >= 0 || (type->userFields && isAccessKeyword(t.text))))
        return;
    }
    lex_.skipBalanced();
  }
}

void Parser::checkNodeClass(const NodeType* parent, std::string_view field, const NodePtr& child,
                            std::size_t offset) {
  std::string expected;
  if (nodeClassAllowed(parent, field, child->type(), expected)) return;
  if (parent == nullptr)
    report(Severity::warning, offset,
           child->typeName() + " node is not allowed at the root of a scene (expected " + expected +
               ")");
  else
    report(Severity::warning, offset,
           child->typeName() + " node is not allowed in '" + std::string(field) + "' of " +
               parent->name + " (expected " + expected + ")");
}

void Parser::checkInline(const Node& node, std::size_t offset) {
  const FieldValue* url = node.field("url");
  if (url == nullptr || url->type() != FieldType::MFString) return;
  for (const std::string& u : url->get<FieldType::MFString>()) {
    if (urlNamesFile(lex_.file(), u)) {
      report(Severity::error, offset,
             "Inline url '" + u + "' names the file that contains it (endless recursion)");
      return;
    }
  }
}

FieldValue Parser::parseValueText(FieldType t) {
  tableMode_ = true;
  Scope scope;
  FieldValue v(t);
  int h = 0;
  try {
    parseValue(t, v, scope, 0, h);
  } catch (const RecoverableError& e) {
    throw ParseError(e.diagnostic);
  }
  if (!lex_.atEnd()) lex_.fatal(lex_.offset(), "unexpected text after the value");
  return v;
}

std::vector<FieldSpec> Parser::parseInterfaceText(std::string_view name) {
  tableMode_ = true;
  Scope scope;
  NodeType type;
  type.name = name;
  NameMap<int> names;
  while (!lex_.atEnd()) {
    const std::size_t before = diag_.items.size();
    parseInterfaceDeclaration(scope, type, true, false, names);
    if (diag_.items.size() != before) throw ParseError(diag_.items.back());
  }
  return std::move(type.fields);
}

}  // namespace gs::vrml::parsing
