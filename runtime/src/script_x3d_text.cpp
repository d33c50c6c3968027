// X3DScene.toVRMLString / toXMLString / toJSONString and SFNode's (as X_ITE 15 names them;
// ISO/IEC 19777-1 has the node's toVRMLString and toXMLString): a scene or node written in
// X3D's Classic VRML, XML or JSON encoding by the writer of `ghostspace convert`
// (encodings/writer.hpp). Installed on __gsX3D by installX3DHooks.
#include "encodings/parser.hpp"
#include "encodings/writer.hpp"
#include "script_ecmascript_internal.hpp"
#include "vrml/proto.hpp"
#include "vrml/scene.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace gs::runtime::es {

namespace {

// The encoding of a hook's `encoding` argument: 0 Classic VRML, 1 XML, 2 JSON.
vrml::Encoding encodingArg(duk_context* c, duk_idx_t idx) {
  const int e = duk_to_int(c, idx);
  return e == 1 ? vrml::Encoding::xml : e == 2 ? vrml::Encoding::json : vrml::Encoding::classic;
}

std::vector<std::string_view> splitLines(std::string_view text) {
  std::vector<std::string_view> lines;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    lines.push_back(text.substr(0, end));
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
  return lines;
}

std::size_t indentOf(std::string_view line) {
  const std::size_t i = line.find_first_not_of(' ');
  return i == std::string_view::npos ? line.size() : i;
}

// Lines [first, last) of `lines`, each without `indent` leading spaces, joined by '\n'.
std::string joinDedented(const std::vector<std::string_view>& lines, std::size_t first,
                         std::size_t last, std::size_t indent) {
  std::string out;
  for (std::size_t i = first; i < last; ++i) {
    std::string_view line = lines[i];
    line.remove_prefix(std::min(indent, indentOf(line)));
    out.append(line);
    out.push_back('\n');
  }
  return out;
}

// The one root node of a written one-node scene, without the file around it: Classic VRML
// after the header statements, XML inside <Scene>, JSON the element of Scene's -children.
std::string nodeOfFile(const std::string& text, vrml::Encoding encoding) {
  const std::vector<std::string_view> lines = splitLines(text);
  if (encoding == vrml::Encoding::classic) {
    std::size_t i = 0;
    while (i < lines.size() &&
           (lines[i].empty() || lines[i].starts_with("#") || lines[i].starts_with("PROFILE ") ||
            lines[i].starts_with("COMPONENT ") || lines[i].starts_with("UNIT ") ||
            lines[i].starts_with("META ")))
      ++i;
    return joinDedented(lines, i, lines.size(), 0);
  }
  // XML and JSON: from the line after the scene's opening to its closing, less their indent.
  const std::string_view open = encoding == vrml::Encoding::xml ? "<Scene>" : "\"-children\": [";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].find(open) == std::string_view::npos) continue;
    const std::size_t outer = indentOf(lines[i]);
    std::size_t end = i + 1;
    while (end < lines.size() && indentOf(lines[end]) > outer) ++end;
    if (i + 1 >= end) return std::string();
    return joinDedented(lines, i + 1, end, indentOf(lines[i + 1]));
  }
  return std::string();
}

// What the writer may be given: a graph a Script made can hold a node among its own
// descendants (the writer, made for parsed files, would recurse forever), a chain deeper
// than any file, or a node without a DEF name shared by many parents, which the writer
// writes out at each place (a chain of such pairs doubles at every level). At most the
// nesting a file may have (ParseLimits::maxNesting: a deeper text would not read back) and
// kMaxTextNodes nodes written, counted as the writer counts them.
const std::size_t kMaxTextDepth = static_cast<std::size_t>(vrml::ParseLimits{}.maxNesting);
constexpr std::uint64_t kMaxTextNodes = 1'000'000;

// Calls `f` with each node-valued field value of `n`, and of its PROTO interface.
template <class F>
void forEachChild(const vrml::Node& n, F&& f) {
  auto values = [&](const vrml::FieldValue& v) {
    if (v.type() == vrml::FieldType::SFNode) {
      if (const vrml::NodePtr& c = v.get<vrml::FieldType::SFNode>()) f(*c);
    } else if (v.type() == vrml::FieldType::MFNode) {
      for (const vrml::NodePtr& c : v.get<vrml::FieldType::MFNode>())
        if (c) f(*c);
    }
  };
  for (std::size_t i = 0; i < n.fieldCount(); ++i) values(n.fieldAt(i));
  if (const vrml::ProtoInstance* p = vrml::declaredInterface(n))
    for (const vrml::FieldValue& v : p->values) values(v);
}

// Empty when the graph under `roots` may be written; else why not. Depth first without
// recursion; each node's written size (1 + its children's, or 1 for a USE of a DEF name
// already written: counted as its first place) is computed once.
std::string unwritable(const std::vector<vrml::NodePtr>& roots) {
  enum : std::uint8_t { kOnPath = 1, kDone = 2 };
  std::unordered_map<const vrml::Node*, std::pair<std::uint8_t, std::uint64_t>> state;
  struct Frame {
    const vrml::Node* node;
    std::vector<const vrml::Node*> children;
    std::size_t next = 0;
    std::uint64_t size = 1;
  };
  std::vector<Frame> path;
  std::uint64_t total = 0;
  for (const vrml::NodePtr& root : roots) {
    if (!root) continue;
    auto enter = [&](const vrml::Node& n) {
      Frame f{&n, {}};
      forEachChild(n, [&](const vrml::Node& c) { f.children.push_back(&c); });
      state[&n] = {kOnPath, 0};
      path.push_back(std::move(f));
    };
    if (state.contains(root.get())) continue;
    enter(*root);
    std::uint64_t rootSize = 0;
    while (!path.empty()) {
      Frame& f = path.back();
      if (f.next < f.children.size()) {
        const vrml::Node* c = f.children[f.next++];
        auto it = state.find(c);
        if (it == state.end()) {
          if (path.size() >= kMaxTextDepth)
            return "the node graph is deeper than " + std::to_string(kMaxTextDepth) + " levels";
          enter(*c);
          continue;
        }
        if (it->second.first == kOnPath) return "a node is among its own descendants";
        // Written again in full where the node has no DEF name, else as a USE.
        f.size += c->defName.empty() ? it->second.second : 1;
        f.size = std::min<std::uint64_t>(f.size, kMaxTextNodes + 1);
        continue;
      }
      const Frame done = std::move(path.back());
      path.pop_back();
      state[done.node] = {kDone, done.size};
      if (path.empty())
        rootSize = done.size;
      else
        path.back().size = std::min<std::uint64_t>(path.back().size + done.size, kMaxTextNodes + 1);
    }
    total += rootSize;
    if (total > kMaxTextNodes)
      return "it would write more than " + std::to_string(kMaxTextNodes) +
             " nodes (nodes without a DEF name shared by many parents)";
  }
  return std::string();
}

// A RangeError naming `what` when unwritable(roots) says why.
void requireWritable(duk_context* c, const std::vector<vrml::NodePtr>& roots, const char* what) {
  const std::string why = unwritable(roots);
  if (!why.empty()) GS_DUK_ERROR(c, DUK_ERR_RANGE_ERROR, "%s: not written: %s", what, why.c_str());
}

// sceneText(scene, encoding): the X3DScene's whole file in that encoding.
duk_ret_t x3dSceneText(duk_context* c) {
  EsScript& self = EsScript::of(c);
  const vrml::Scene* scene = x3dSceneOf(self, c, 0);
  if (scene == nullptr)
    GS_DUK_ERROR(c, DUK_ERR_TYPE_ERROR, "toVRMLString: the Script has no scene");
  requireWritable(c, scene->rootNodes, "toVRMLString");
  requireWritable(c, scene->hiddenNodes, "toVRMLString");
  vrml::WriteOptions options;
  options.encoding = encodingArg(c, 1);
  const vrml::WriteResult w = vrml::writeScene(*scene, options);
  duk_push_lstring(c, w.text.data(), w.text.size());
  return 1;
}

// nodeText(node, encoding): the node (its fields that differ from their defaults, its
// children, DEF and USE names) in that encoding, in the X3D version of the Script's world.
duk_ret_t x3dNodeText(duk_context* c) {
  EsScript& self = EsScript::of(c);
  const vrml::NodePtr node = self.nodeAt(c, 0);
  if (!node) GS_DUK_ERROR(c, DUK_ERR_TYPE_ERROR, "toVRMLString: not a node");
  vrml::Scene one;
  const vrml::Scene* own = self.context().sceneOf(self.node());
  one.x3d.version = own != nullptr && !own->x3d.version.empty() ? own->x3d.version : "4.0";
  one.rootNodes.push_back(node);
  requireWritable(c, one.rootNodes, "toVRMLString");
  vrml::WriteOptions options;
  options.encoding = encodingArg(c, 1);
  const std::string text = nodeOfFile(vrml::writeScene(one, options).text, options.encoding);
  duk_push_lstring(c, text.data(), text.size());
  return 1;
}

}  // namespace

void installX3DText(duk_context* c) {
  duk_push_c_function(c, x3dSceneText, 2);
  duk_put_prop_string(c, -2, "sceneText");
  duk_push_c_function(c, x3dNodeText, 2);
  duk_put_prop_string(c, -2, "nodeText");
}

}  // namespace gs::runtime::es
