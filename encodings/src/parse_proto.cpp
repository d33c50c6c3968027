// PROTO and EXTERNPROTO declarations and the expansion of their instances (clauses 4.8
// and 4.9; annex A.3 protoStatement, externproto).
#include "encodings/node_types.hpp"
#include "parser_impl.hpp"
#include "vrml/node_table.hpp"

#include "base/text.hpp"
#include "base/url.hpp"

#include <algorithm>
#include <unordered_set>

namespace gs::vrml::parsing {

namespace {

bool carriesValue(AccessType a) {
  return a == AccessType::field || a == AccessType::exposedField;
}

struct RecursionGuard {
  int& r;
  ~RecursionGuard() { --r; }
};

}  // namespace

// interfaceDeclaration ::= eventIn fieldType eventInId | eventOut fieldType eventOutId |
//   field fieldType fieldId fieldValue | exposedField fieldType fieldId fieldValue
// (EXTERNPROTO: no values). Returns false when the declaration was reported and dropped.
bool Parser::parseInterfaceDeclaration(Scope& scope, NodeType& type, bool withValues, bool external,
                                       NameMap<int>& names) {
  const Token at = lex_.peek();
  AccessType a = AccessType::field;
  if (at.kind != Tok::id || !accessTypeFromName(at.text, a))
    lex_.failExpected(at.offset, ctx_.x3d ? "inputOnly, outputOnly, initializeOnly or inputOutput"
                                          : "eventIn, eventOut, field or exposedField");
  lex_.consume(at);
  const FieldType ft = parseFieldTypeName();
  const Token nt = lex_.peek();
  FieldSpec spec{std::string(lex_.expectId("a field or event name")), ft, a, FieldValue(ft)};
  if (withValues && carriesValue(a)) {
    // Each default value is its own DEF name scope (clause 4.4.7); PROTO names of the
    // enclosing scopes stay visible.
    Scope valueScope;
    valueScope.parent = &scope;
    valueScope.defParent = &scope;
    valueScope.routes = scope.routes;
    valueScope.hidden = scope.hidden;
    int h = 0;
    parseValue(ft, spec.defaultValue, valueScope, 0, h);
  }
  const std::string& name = spec.name;
  std::string problem;
  auto conflictsWith = [&](std::string_view other, AccessType otherAccess) {
    auto it = names.find(other);
    return it != names.end() &&
           type.fields[static_cast<std::size_t>(it->second)].access == otherAccess;
  };
  const std::string_view kind = external ? "EXTERNPROTO" : "PROTO";
  if (names.find(name) != names.end()) {
    problem = "'" + name + "' is declared twice in " + std::string(kind) + " " + type.name;
  } else if (a == AccessType::eventIn && name.starts_with("set_") &&
             conflictsWith(std::string_view(name).substr(4), AccessType::exposedField)) {
    problem = "eventIn '" + name + "' conflicts with exposedField '" + name.substr(4) + "' of " +
              std::string(kind) + " " + type.name + " (clause 4.7)";
  } else if (a == AccessType::eventOut && name.ends_with("_changed") &&
             conflictsWith(std::string_view(name).substr(0, name.size() - 8),
                           AccessType::exposedField)) {
    problem = "eventOut '" + name + "' conflicts with exposedField '" +
              name.substr(0, name.size() - 8) + "' of " + std::string(kind) + " " + type.name +
              " (clause 4.7)";
  } else if (a == AccessType::exposedField &&
             (conflictsWith("set_" + name, AccessType::eventIn) ||
              conflictsWith(name + "_changed", AccessType::eventOut))) {
    problem = "exposedField '" + name + "' conflicts with an event of " + std::string(kind) + " " +
              type.name + " (clause 4.7)";
  }
  if (!problem.empty()) {
    report(Severity::error, nt.offset, std::move(problem));
    return false;
  }
  names.emplace(name, static_cast<int>(type.fields.size()));
  type.fields.push_back(std::move(spec));
  return true;
}

// [ interfaceDeclarations ]: a bad declaration is reported and skipped up to the next
// access keyword or the closing ']'.
void Parser::parseInterface(Scope& scope, NodeType& type, bool withValues, bool external) {
  NameMap<int> names;  // declared so far: duplicate and conflict checks in constant time
  lex_.expect('[');
  while (!lex_.accept(']')) {
    if (lex_.atEnd()) lex_.failExpected(lex_.offset(), "an interface declaration or ']'");
    const std::size_t before = lex_.offset();
    try {
      parseInterfaceDeclaration(scope, type, withValues, external, names);
    } catch (const RecoverableError& e) {
      report(e);
      if (lex_.offset() == before) lex_.skipBalanced();
      while (true) {
        const Token t = lex_.peek();
        if (t.kind == Tok::end || t.kind == Tok::rbracket) break;
        AccessType ignored;
        if (t.kind == Tok::id && accessTypeFromName(t.text, ignored)) break;
        lex_.skipBalanced();
      }
    }
  }
}

// protoStatement ::= PROTO nodeTypeId [ interfaceDeclarations ] { protoBody }
void Parser::parseProto(Scope& scope) {
  const Token kw = lex_.next();
  enter(kw.offset);
  RecursionGuard guard{recursion_};
  const Token nt = lex_.peek();
  const std::string name(lex_.expectId("a PROTO name"));
  auto type = std::make_shared<NodeType>();
  type->name = name;
  auto def = std::make_shared<ProtoDefinition>();
  def->name = name;
  def->location = lex_.locationAt(kw.offset);
  parseInterface(scope, *type, true, false);
  if (scope.protos.find(name) != scope.protos.end())
    report(Severity::warning, nt.offset, "PROTO '" + name + "' redefines an earlier one");
  setProto(scope, name, nullptr);  // being defined: an instance in its own body is an error
  protosDeclared_ = true;
  Scope body;
  body.parent = &scope;
  ProtoBuilder builder{type, def};
  body.proto = &builder;
  body.routes = &def->routes;
  body.hidden = &def->hidden;
  try {
    if (lex_.peekChar() != '{') lex_.failExpected(lex_.offset(), "'{' to open the PROTO body");
    lex_.setOffset(lex_.offset() + 1);
    parseStatements(body, &def->body, 0, true, &def->height);
  } catch (const RecoverableError&) {
    eraseProto(scope, name);
    throw;
  }
  if (def->body.empty())
    report(Severity::error, nt.offset, "PROTO '" + name + "' has no node in its body");
  type->proto = def;
  setProto(scope, name, type);
  if (scope.declared != nullptr) scope.declared->push_back(type);
}

// externproto ::= EXTERNPROTO nodeTypeId [ externInterfaceDeclarations ] URLList
void Parser::parseExternProto(Scope& scope) {
  const Token kw = lex_.next();
  const std::string name(lex_.expectId("an EXTERNPROTO name"));
  auto type = std::make_shared<NodeType>();
  type->name = name;
  auto def = std::make_shared<ProtoDefinition>();
  def->name = name;
  def->location = lex_.locationAt(kw.offset);
  def->external = true;
  parseInterface(scope, *type, false, true);
  FieldValue urls(FieldType::MFString);
  int h = 0;
  parseValue(FieldType::MFString, urls, scope, 0, h);
  def->urls = std::move(urls.get<FieldType::MFString>());
  // "urn:ghostspace:NAME" names one of this browser's own extension nodes
  // (docs/vrml-extensions.md): use the built-in node, not the fallback PROTO.
  for (const std::string& url : def->urls) {
    constexpr std::string_view kUrn = "urn:ghostspace:";
    if (!base::startsWithNoCase(url, kUrn)) continue;
    const auto builtIn = builtInNodeType(std::string_view(url).substr(kUrn.size()));
    if (builtIn && builtIn->extension) {
      setProto(scope, name, builtIn);
      protosDeclared_ = true;
      return;
    }
  }
  resolveExternProto(scope, *def, *type, kw.offset);
  type->proto = def;
  setProto(scope, name, type);
  protosDeclared_ = true;
  if (scope.declared != nullptr) scope.declared->push_back(type);
}

void Parser::resolveExternProto(Scope& scope, ProtoDefinition& def, const NodeType& declared,
                                std::size_t offset) {
  std::string reasons;
  auto addReason = [&](const std::string& url, const std::string& why) {
    if (!reasons.empty()) reasons += "; ";
    reasons += url.empty() ? why : url + ": " + why;
  };
  if (def.urls.empty()) addReason("", "no URL given");
  for (const std::string& url : def.urls) {
    const std::size_t hash = url.find('#');
    const std::string file = url.substr(0, hash);
    const std::string protoName = hash == std::string::npos ? "" : url.substr(hash + 1);
    if (base::startsWithNoCase(url, "urn:")) {
      addReason(url, "urn: names are not resolved");
      continue;
    }
    std::shared_ptr<const NodeType> target;
    if (file.empty()) {
      // "#Name": a PROTO of this file declared before the EXTERNPROTO (clause 4.9.3), seen
      // from the EXTERNPROTO's scope.
      for (Scope* s = &scope; s != nullptr && !target && !protoName.empty(); s = s->parent)
        if (auto it = s->protos.find(protoName); it != s->protos.end()) target = it->second;
      while (target && target->proto && target->proto->external) target = target->proto->resolved;
      if (!target) {
        addReason(url, protoName.empty() ? "no PROTO named"
                                         : "this file declares no PROTO '" + protoName +
                                               "' before the EXTERNPROTO");
        continue;
      }
    } else {
      const std::string resolved = base::resolveUrl(lex_.file(), file);
      if (externDepth_ + 1 > ctx_.options.limits.maxExternProtoDepth) {
        addReason(url, "EXTERNPROTO files nested deeper than " +
                           std::to_string(ctx_.options.limits.maxExternProtoDepth) +
                           " (ParseLimits::maxExternProtoDepth)");
        continue;
      }
      std::shared_ptr<ExternFile> f;
      std::string reason;
      if (!loadExternFile(resolved, f, reason)) {
        addReason(url, reason);
        continue;
      }
      for (const auto& p : f->protos)
        if (protoName.empty() || p->name == protoName) target = p;  // the last of that name
      if (protoName.empty() && !f->protos.empty()) target = f->protos.front();
      // Follow EXTERNPROTOs of that file to the PROTO they name.
      while (target && target->proto && target->proto->external) target = target->proto->resolved;
      if (!target) {
        addReason(url, protoName.empty() ? "the file declares no PROTO"
                                         : "the file declares no PROTO '" + protoName + "'");
        continue;
      }
    }
    def.memberMap.assign(declared.fields.size(), -1);
    for (std::size_t i = 0; i < declared.fields.size(); ++i) {
      const FieldSpec& m = declared.fields[i];
      const int k = memberIndex(target, m.name);
      if (k >= 0 && target->fields[static_cast<std::size_t>(k)].type == m.type &&
          target->fields[static_cast<std::size_t>(k)].access == m.access)
        def.memberMap[i] = k;
      else
        report(Severity::warning, offset,
               "EXTERNPROTO '" + declared.name + "' member '" + m.name +
                   "' does not match the interface of PROTO '" + target->name + "' in " + url);
    }
    def.resolved = std::move(target);
    def.resolvedUrl = url;
    return;
  }
  std::string list;
  for (const std::string& url : def.urls) list += (list.empty() ? "\"" : ", \"") + url + "\"";
  report(
      Severity::warning, offset,
      "EXTERNPROTO '" + declared.name + "' could not be resolved from [" + list + "]: " + reasons);
}

bool Parser::loadExternFile(const std::string& url, std::shared_ptr<ExternFile>& out,
                            std::string& reason) {
  if (auto it = ctx_.externFiles.find(url); it != ctx_.externFiles.end()) {
    if (it->second->loading) {
      reason = "recursive EXTERNPROTO reference";
      return false;
    }
    if (!it->second->error.empty()) {
      reason = it->second->error;
      return false;
    }
    out = it->second;
    if (out->replay) {
      // Loaded by a statement that StreamingParser undid: report as that load did.
      out->replay = false;
      ctx_.nodeCount += out->nodes;
      for (const Diagnostic& d : out->diagnostics) {
        if (diag_.items.size() >= 1000) break;
        diag_.items.push_back(d);
      }
      if (ctx_.loaded != nullptr && externDepth_ == 0) ctx_.loaded->push_back(out);
    }
    return true;
  }
  const bool background = ctx_.externInBackground && externDepth_ == 0;
  base::Fetched got = base::fetcherOr(ctx_.options.fetcher)
                          .fetch(url, lex_.file(),
                                 background ? base::FetchMode::background : base::FetchMode::whole);
  if (got.pending()) {  // the StreamingParser undoes this statement and retries it later
    ctx_.externPending = true;
    reason = "still on its way";
    return false;
  }
  auto f = std::make_shared<ExternFile>();
  ctx_.externFiles[url] = f;
  std::string& bytes = got.bytes;
  f->loading = false;
  if (!got.ready()) {
    f->error = got.error.empty() ? "cannot be read" : got.error;
    reason = f->error;
    return false;
  }
  f->loading = true;
  Scene sub;
  const std::size_t nodesBefore = ctx_.nodeCount;
  parseInto(bytes, url, ctx_, externDepth_ + 1, sub);
  f->loading = false;
  const bool log = ctx_.loaded != nullptr && externDepth_ == 0;
  if (log) {
    f->nodes = ctx_.nodeCount - nodesBefore;
    f->diagnostics = sub.diagnostics.items;
    ctx_.loaded->push_back(f);
  }
  for (Diagnostic& d : sub.diagnostics.items) {
    if (diag_.items.size() >= 1000) break;
    diag_.items.push_back(std::move(d));
  }
  f->protos = std::move(sub.protos);
  markExternNodes(f->protos, url);
  out = f;
  return true;
}

namespace {

void markNode(const NodePtr& n, const std::shared_ptr<const std::string>& base,
              std::unordered_set<const Node*>& seen);

void markValue(const FieldValue& v, const std::shared_ptr<const std::string>& base,
               std::unordered_set<const Node*>& seen) {
  if (v.type() == FieldType::SFNode) {
    markNode(v.get<FieldType::SFNode>(), base, seen);
  } else if (v.type() == FieldType::MFNode) {
    for (const NodePtr& c : v.get<FieldType::MFNode>()) markNode(c, base, seen);
  }
}

void markNode(const NodePtr& n, const std::shared_ptr<const std::string>& base,
              std::unordered_set<const Node*>& seen) {
  if (!n || !seen.insert(n.get()).second) return;
  // A node that already has a base came from a file nested deeper (an EXTERNPROTO of
  // this file): it keeps that file's.
  if (!n->urlBase) n->urlBase = base;
  for (std::size_t i = 0; i < n->fieldCount(); ++i) markValue(n->fieldAt(i), base, seen);
}

}  // namespace

void markExternNodes(const std::vector<std::shared_ptr<const NodeType>>& protos,
                     const std::string& url) {
  const auto base = std::make_shared<const std::string>(url);
  std::unordered_set<const Node*> seen;
  for (const auto& type : protos) {
    if (!type) continue;
    for (const FieldSpec& f : type->fields) markValue(f.defaultValue, base, seen);
    if (!type->proto || type->proto->external) continue;
    for (const NodePtr& n : type->proto->body) markNode(n, base, seen);
    for (const NodePtr& n : type->proto->hidden) markNode(n, base, seen);
  }
}

NodePtr Parser::copyTree(const NodePtr& n, std::unordered_map<const Node*, NodePtr>& memo,
                         std::vector<NodePtr>& keep) {
  if (!n) return n;
  const bool owning = n.use_count() != 0;
  if (auto it = memo.find(n.get()); it != memo.end())
    return owning ? it->second : NodePtr(NodePtr(), it->second.get());
  countNode(lex_.offset());
  auto c = std::make_shared<Node>(*n);
  memo.emplace(n.get(), c);
  for (std::size_t i = 0; i < c->fieldCount(); ++i) {
    FieldValue& v = c->fieldAt(i);
    if (v.type() == FieldType::SFNode) {
      NodePtr& p = v.get<FieldType::SFNode>();
      p = copyTree(p, memo, keep);
    } else if (v.type() == FieldType::MFNode) {
      for (NodePtr& p : v.get<FieldType::MFNode>()) p = copyTree(p, memo, keep);
    }
  }
  if (!owning) {
    // First met through a back reference: someone must own the copy.
    keep.push_back(c);
    return NodePtr(NodePtr(), c.get());
  }
  return c;
}

std::span<const IsConnection> connectionsOf(const std::vector<IsConnection>& links, int member) {
  auto range = std::equal_range(links.begin(), links.end(), member, ConnectionOrder{});
  return {range.first, range.second};
}

int treeHeight(const NodePtr& n, std::unordered_map<const Node*, int>& memo) {
  if (!n || n.use_count() == 0) return 0;
  if (auto it = memo.find(n.get()); it != memo.end()) return it->second;
  int h = 0;
  for (std::size_t i = 0; i < n->fieldCount(); ++i) {
    const FieldValue& v = n->fieldAt(i);
    if (v.type() == FieldType::SFNode) {
      h = std::max(h, treeHeight(v.get<FieldType::SFNode>(), memo));
    } else if (v.type() == FieldType::MFNode) {
      for (const NodePtr& p : v.get<FieldType::MFNode>()) h = std::max(h, treeHeight(p, memo));
    }
  }
  memo.emplace(n.get(), h + 1);
  return h + 1;
}

// Expands a PROTO instance (clause 4.8.3): copies the body, gives each IS-connected field
// the instance's value or the interface default, copies the body's ROUTEs, and returns
// the copy of the first body node. IS statements on the instance itself (inside another
// PROTO body) become connections of that PROTO.
NodePtr Parser::instantiate(Scope& scope, InstanceValues& inst, std::size_t offset, int depth,
                            int& height, std::shared_ptr<const std::vector<IsConnection>>& links) {
  const std::shared_ptr<const NodeType>& declared = inst.type;
  const ProtoDefinition& decl = *declared->proto;
  const std::size_t maxNesting = static_cast<std::size_t>(ctx_.options.limits.maxNesting);
  auto tooDeep = [&](int h) {
    if (static_cast<std::size_t>(depth) + static_cast<std::size_t>(h) <= maxNesting) return false;
    report(Severity::error, offset,
           "PROTO instance '" + declared->name + "' nests deeper than " +
               std::to_string(maxNesting) + " levels (ParseLimits::maxNesting)");
    return true;
  };
  auto l = std::make_shared<std::vector<IsConnection>>();
  if (decl.external && !decl.resolved) {
    countNode(offset);
    auto node = std::make_shared<Node>(declared);
    node->unresolved = true;
    // The node's own type is the declared interface: the record names the PROTO only.
    auto record = std::make_shared<ProtoInstance>();
    record->type = declared;
    node->protoInstance = std::move(record);
    node->location = inst.location;
    for (std::size_t i = 0; i < inst.values.size(); ++i)
      if (inst.given[i]) node->fieldAt(i) = std::move(inst.values[i]);
    for (std::size_t i = 0; i < declared->fields.size(); ++i)
      l->push_back(
          IsConnection{node, static_cast<int>(i), declared->fields[i].access, static_cast<int>(i)});
    for (const IsConnection& r : inst.isRefs)
      scope.proto->def->connections.push_back(
          IsConnection{node, r.nodeField, r.nodeAccess, r.protoField});
    height = inst.valueHeight + 1;
    if (tooDeep(height)) return nullptr;
    links = l;
    return node;
  }
  const NodeType& impl = decl.external ? *decl.resolved : *declared;
  const ProtoDefinition& def = *impl.proto;
  if (def.body.empty()) {
    height = 0;
    return nullptr;
  }
  // Map the declared interface (an EXTERNPROTO's) to the implementing PROTO's.
  std::vector<int> toImpl(declared->fields.size());
  std::vector<int> toDeclared(impl.fields.size(), -1);
  for (std::size_t i = 0; i < declared->fields.size(); ++i) {
    const int k = decl.external ? decl.memberMap[i] : static_cast<int>(i);
    toImpl[i] = k;
    if (k >= 0) toDeclared[static_cast<std::size_t>(k)] = static_cast<int>(i);
  }
  std::vector<const FieldValue*> value(impl.fields.size());
  for (std::size_t j = 0; j < impl.fields.size(); ++j) value[j] = &impl.fields[j].defaultValue;
  for (std::size_t i = 0; i < declared->fields.size(); ++i)
    if (inst.given[i] && toImpl[i] >= 0)
      value[static_cast<std::size_t>(toImpl[i])] = &inst.values[i];

  std::unordered_map<const Node*, NodePtr> memo;
  std::vector<NodePtr> keep;
  std::vector<NodePtr> copies;
  copies.reserve(def.body.size() + def.hidden.size());
  for (const NodePtr& n : def.body) copies.push_back(copyTree(n, memo, keep));
  for (const NodePtr& n : def.hidden) copies.push_back(copyTree(n, memo, keep));
  // PROTO instances inside the body: their records must name this copy's nodes.
  for (auto& [original, copy] : memo) {
    if (!copy->protoInstance || copy->protoInstance->links.empty()) continue;
    auto record = std::make_shared<ProtoInstance>(*copy->protoInstance);
    for (InstanceLink& k : record->links)
      if (auto it = memo.find(k.node.lock().get()); it != memo.end()) k.node = it->second;
    copy->protoInstance = std::move(record);
  }
  for (const IsConnection& c : def.connections) {
    auto it = memo.find(c.node.get());
    if (it == memo.end()) continue;
    const auto member = static_cast<std::size_t>(c.protoField);
    if (carriesValue(c.nodeAccess) && carriesValue(impl.fields[member].access))
      it->second->fieldAt(static_cast<std::size_t>(c.nodeField)) = *value[member];
    if (toDeclared[member] >= 0)
      l->push_back(IsConnection{it->second, c.nodeField, c.nodeAccess, toDeclared[member]});
  }
  // Sorted by interface member: IS refs here and ROUTEs later find theirs by bisection.
  std::stable_sort(l->begin(), l->end(), [](const IsConnection& a, const IsConnection& b) {
    return a.protoField < b.protoField;
  });
  for (const IsConnection& r : inst.isRefs)
    for (const IsConnection& c : connectionsOf(*l, r.nodeField))
      scope.proto->def->connections.push_back(
          IsConnection{c.node, c.nodeField, c.nodeAccess, r.protoField});
  if (scope.routes != nullptr) {
    for (const Route& r : def.routes) {
      auto from = memo.find(r.fromNode.get());
      auto to = memo.find(r.toNode.get());
      if (from != memo.end() && to != memo.end())
        scope.routes->push_back(
            Route{from->second, r.fromField, to->second, r.toField, r.location});
    }
  }
  if (scope.hidden != nullptr) {
    for (std::size_t i = 1; i < copies.size(); ++i) scope.hidden->push_back(copies[i]);
    for (NodePtr& k : keep) scope.hidden->push_back(std::move(k));
  }
  NodePtr result = copies.front();
  auto record = std::make_shared<ProtoInstance>();
  record->type = declared;
  record->values.reserve(declared->fields.size());
  for (std::size_t i = 0; i < declared->fields.size(); ++i)
    record->values.push_back(inst.given[i] ? inst.values[i] : declared->fields[i].defaultValue);
  record->links.reserve(l->size());
  for (const IsConnection& c : *l)
    record->links.push_back(InstanceLink{c.node, c.nodeField, c.nodeAccess, c.protoField});
  result->protoInstance = std::move(record);
  result->location = inst.location;
  std::unordered_map<const Node*, int> heights;
  height = treeHeight(result, heights);
  if (tooDeep(height)) return nullptr;
  links = l;
  return result;
}

}  // namespace gs::vrml::parsing
