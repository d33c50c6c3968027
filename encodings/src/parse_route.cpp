// ROUTE statements (clause 4.10.2; annex A.3 routeStatement):
// ROUTE nodeNameId . eventOutId TO nodeNameId . eventInId
#include "parser_impl.hpp"

namespace gs::vrml::parsing {

namespace {

/// One end of a route resolved against a node's interface.
struct End {
  int index = -1;                         // into the interface
  AccessType access = AccessType::field;  // as named
};

// Finds the eventOut (out = true) or eventIn named `name`: the member itself, the
// exposedField aliases `x_changed` / `set_x` (clause 4.10.3), or leniently an
// eventOut `name_changed` / eventIn `set_name`. Empty `problem` on success.
// `exact(n)` is the index of the member called exactly n, or -1.
template <class Exact>
End resolveEnd(const NodeType& type, Exact&& exact, std::string_view name, bool out,
               std::string& problem) {
  const AccessType want = out ? AccessType::eventOut : AccessType::eventIn;
  const char* role = out ? "source" : "destination";
  const char* wantName = out ? "an eventOut or exposedField" : "an eventIn or exposedField";
  End e;
  int i = exact(name);
  if (i >= 0) {
    const AccessType a = type.fields[static_cast<std::size_t>(i)].access;
    if (a == want || a == AccessType::exposedField) return End{i, a};
    problem = "ROUTE " + std::string(role) + " '" + std::string(name) + "' of " + type.name +
              " is " +
              (a == AccessType::field ? "a field"
               : out                  ? "an eventIn"
                                      : "an eventOut") +
              "; it must be " + wantName;
    return e;
  }
  // exposedField aliases (NodeType::findField, through the hashed lookup).
  const bool isIn = name.starts_with("set_");
  const std::string_view base = isIn                         ? name.substr(4)
                                : name.ends_with("_changed") ? name.substr(0, name.size() - 8)
                                                             : std::string_view();
  i = base.empty() ? -1 : exact(base);
  if (i >= 0 && type.fields[static_cast<std::size_t>(i)].access != AccessType::exposedField) i = -1;
  if (i >= 0) {
    if (isIn != out) return End{i, want};
    problem = "ROUTE " + std::string(role) + " '" + std::string(name) + "' of " + type.name +
              " is " + (isIn ? "an eventIn" : "an eventOut") + "; it must be " + wantName;
    return e;
  }
  const std::string alt = out ? std::string(name) + "_changed" : "set_" + std::string(name);
  i = exact(alt);
  if (i >= 0 && type.fields[static_cast<std::size_t>(i)].access == want) return End{i, want};
  problem = std::string(type.name) + " has no " + (out ? "eventOut" : "eventIn") + " '" +
            std::string(name) + "' for a ROUTE " + role;
  return e;
}

bool canSend(AccessType a) {
  return a == AccessType::eventOut || a == AccessType::exposedField;
}
bool canReceive(AccessType a) {
  return a == AccessType::eventIn || a == AccessType::exposedField;
}

}  // namespace

void Parser::parseRoute(Scope& scope) {
  try {
    parseRouteStatement(scope);
  } catch (const RecoverableError& e) {
    // Skip what is left of the statement (names, periods, TO) so that one bad ROUTE
    // gives one diagnostic.
    report(e);
    bool afterPeriod = false;
    while (true) {
      const Token t = lex_.peek();
      const bool take = t.kind == Tok::period ||
                        (t.kind == Tok::id && (afterPeriod || t.text == "TO" ||
                                               (t.offset + t.text.size() < lex_.text().size() &&
                                                lex_.text()[t.offset + t.text.size()] == '.')));
      if (!take) break;
      afterPeriod = t.kind == Tok::period;
      lex_.consume(t);
    }
  }
}

void Parser::parseRouteStatement(Scope& scope) {
  const Token kw = lex_.next();
  const Token fromTok = lex_.peek();
  const std::string_view fromName = lex_.expectId("a DEF name after ROUTE");
  lex_.expect('.');
  const Token fromFieldTok = lex_.peek();
  const std::string_view fromField = lex_.expectId("an eventOut name");
  const Token toKw = lex_.peek();
  if (toKw.kind != Tok::id || toKw.text != "TO") lex_.failExpected(toKw.offset, "TO");
  lex_.consume(toKw);
  const Token toTok = lex_.peek();
  const std::string_view toName = lex_.expectId("a DEF name after TO");
  lex_.expect('.');
  const Token toFieldTok = lex_.peek();
  const std::string_view toField = lex_.expectId("an eventIn name");

  const DefEntry* from = findDef(scope, fromName);
  const DefEntry* to0 = findDef(scope, toName);
  // An end naming an IMPORTed node (X3D 4.4.6): kept until the Inline's world arrives.
  auto imported = [&](std::string_view name) {
    if (scope.x3d == nullptr) return false;
    for (const X3dImport& im : scope.x3d->imports)
      if (im.localName == name) return true;
    return false;
  };
  const bool fromImported = from == nullptr && imported(fromName);
  const bool toImported = to0 == nullptr && imported(toName);
  if ((fromImported || toImported) && (from != nullptr || fromImported) &&
      (to0 != nullptr || toImported)) {
    X3dImportedRoute r;
    if (fromImported)
      r.fromImport = fromName;
    else
      r.fromNode = from->node;
    r.fromField = fromField;
    if (toImported)
      r.toImport = toName;
    else
      r.toNode = to0->node;
    r.toField = toField;
    r.location = lex_.locationAt(kw.offset);
    scope.x3d->importedRoutes.push_back(std::move(r));
    return;
  }
  if (from == nullptr) {
    report(Severity::error, fromTok.offset,
           "ROUTE from unknown DEF name '" + std::string(fromName) + "'");
    return;
  }
  const DefEntry* to = findDef(scope, toName);
  if (to == nullptr) {
    report(Severity::error, toTok.offset,
           "ROUTE to unknown DEF name '" + std::string(toName) + "'");
    return;
  }
  const DefEntry& a = *from;
  const DefEntry& b = *to;
  std::string problem;
  const End src = resolveEnd(
      *a.declared, [&](std::string_view n) { return memberIndex(a.declared, n); }, fromField, true,
      problem);
  if (src.index < 0) {
    report(Severity::error, fromFieldTok.offset, problem);
    return;
  }
  const End dst = resolveEnd(
      *b.declared, [&](std::string_view n) { return memberIndex(b.declared, n); }, toField, false,
      problem);
  if (dst.index < 0) {
    report(Severity::error, toFieldTok.offset, problem);
    return;
  }
  const FieldType st = a.declared->fields[static_cast<std::size_t>(src.index)].type;
  const FieldType dt = b.declared->fields[static_cast<std::size_t>(dst.index)].type;
  if (st != dt) {
    report(Severity::error, toFieldTok.offset,
           "ROUTE type mismatch: " + std::string(fromName) + "." + std::string(fromField) + " is " +
               std::string(fieldTypeName(st)) + " but " + std::string(toName) + "." +
               std::string(toField) + " is " + std::string(fieldTypeName(dt)));
    return;
  }
  if (scope.routes == nullptr) return;
  const SourceLocation where = lex_.locationAt(kw.offset);
  // A PROTO instance's interface is flattened to the body members IS connects it to, so
  // every stored route joins members of built-in (or Script) nodes.
  struct Endpoint {
    NodePtr node;
    std::string field;
  };
  auto endpoints = [](const DefEntry& e, const End& end, std::string_view asWritten, bool sending) {
    std::vector<Endpoint> out;
    if (!e.links) {
      out.push_back(Endpoint{e.node, std::string(asWritten)});
      return out;
    }
    for (const IsConnection& c : connectionsOf(*e.links, end.index)) {
      if (sending ? !canSend(c.nodeAccess) : !canReceive(c.nodeAccess)) continue;
      out.push_back(
          Endpoint{c.node, c.node->type().fields[static_cast<std::size_t>(c.nodeField)].name});
    }
    return out;
  };
  const std::vector<Endpoint> froms = endpoints(a, src, fromField, true);
  const std::vector<Endpoint> tos = endpoints(b, dst, toField, false);
  for (const Endpoint& f : froms)
    for (const Endpoint& t : tos)
      scope.routes->push_back(Route{f.node, f.field, t.node, t.field, where});
}

}  // namespace gs::vrml::parsing
