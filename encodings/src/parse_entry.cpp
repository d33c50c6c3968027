// The encodings' entry points parseVrml() and loadVrmlFile(): which encoding the bytes are
// (gzip, glTF, X3D XML, X3D JSON, or the Classic header of clause 4.2.2 / ISO/IEC 19776-2
// clause 4.2.2) and the parse that reads them.
#include "gltf/import.hpp"
#include "parser_impl.hpp"
#include "x3d_json.hpp"
#include "x3d_xml.hpp"

namespace gs::vrml::parsing {

void applyX3d3Defaults(Node& node) {
  if (node.typeId() == NodeTypeId::WindPhysicsModel)
    if (FieldValue* d = node.field("direction"); d && d->type() == FieldType::SFVec3f)
      d->get<FieldType::SFVec3f>() = glm::vec3(0.0f);
}

std::string headerProblem(std::string_view line, std::string& x3dVersion) {
  x3dVersion.clear();
  if (line.starts_with("#VRML V2.0 utf8")) return {};
  if (line.starts_with("#VRML V1.0")) return "VRML 1.0 is not supported";
  // "#X3D V3.0 utf8" ... "#X3D V4.1 utf8" (ISO/IEC 19776-2 clause 4.2.2).
  if (line.starts_with("#X3D V") && line.size() >= 9) {
    const std::string_view rest = line.substr(6);
    const std::size_t sp = rest.find(' ');
    const std::string_view v = rest.substr(0, sp);
    const bool digits = v.size() >= 3 && v[0] >= '3' && v[0] <= '4' && v[1] == '.' &&
                        v.find_first_not_of("0123456789", 2) == std::string_view::npos;
    if (!digits)
      return "unsupported X3D version '" + std::string(v.substr(0, 16)) +
             "' (this browser reads X3D 3.0 to 4.1)";
    if (sp == std::string_view::npos || !rest.substr(sp + 1).starts_with("utf8"))
      return "expected 'utf8' after '#X3D V" + std::string(v) + "'";
    x3dVersion = v;
    return {};
  }
  // Quoted with every byte that is not printable ASCII escaped, so that a binary file's
  // bytes never reach the terminal as control sequences.
  std::string got;
  static constexpr char kHex[] = "0123456789abcdef";
  for (char c : line.substr(0, 40)) {
    const auto b = static_cast<unsigned char>(c);
    if (b < 0x20 || b >= 0x7f) {
      got += "\\x";
      got += kHex[b >> 4];
      got += kHex[b & 15];
    } else {
      got += c;
    }
  }
  if (line.size() > 40) got += "...";
  return "expected '#VRML V2.0 utf8' or '#X3D V4.0 utf8' header, got '" + got + "'";
}

void parseInto(std::string_view bytes, const std::string& url, Context& ctx, int externDepth,
               Scene& scene, TextOrigin* origin) {
  const ParseLimits& limits = ctx.options.limits;
  std::string inflated;
  try {
    if (base::isGzip(bytes)) {
      gunzipInto(bytes, url, limits.maxInputBytes, inflated);
      bytes = inflated;
    }
  } catch (const ParseError& e) {
    scene.diagnostics.items.push_back(e.diagnostic);
    return;
  }
  if (bytes.size() > limits.maxInputBytes) {
    scene.diagnostics.error({url, 0, 0}, "input of " + std::to_string(bytes.size()) +
                                             " bytes exceeds ParseLimits::maxInputBytes");
    return;
  }
  // glTF 2.0 (GLB, or a JSON document that is no X3D): built into X3D nodes.
  if (gltf::isGltf(bytes)) {
    gltf::importGltf(bytes, url, gltfImportOptions(ctx.options), scene);
    return;
  }
  // X3D's XML encoding (the first byte that is no space or BOM is '<'): plain statements
  // built from their elements, the others translated into Classic VRML text and parsed,
  // at the XML's locations (parser_xml_build.cpp).
  bool decided = false;
  if (looksLikeXml(bytes, decided)) {
    parseXmlInto(bytes, url, ctx, externDepth, scene);
    return;
  }
  // X3D's JSON encoding (the first such byte is '{'): translated the same way, whole.
  if (looksLikeJson(bytes, decided)) {
    std::string classic;
    JsonToClassic json(classic, url, limits.maxNesting);
    json.translate(bytes, scene);
    if (json.wroteHeader()) parseInto(classic, url, ctx, externDepth, scene, &json.origin());
    scene.x3d.encoding = "JSON";
    if (json.failed()) scene.diagnostics.items.push_back(json.fatalError());
    return;
  }
  // Header (clause 4.2.2): "#VRML V2.0 utf8" on the first line. A UTF-8 byte order mark
  // before it is tolerated.
  std::size_t start = bytes.starts_with("\xEF\xBB\xBF") ? 3 : 0;
  const std::size_t eol = bytes.find_first_of("\r\n", start);
  const std::string_view line =
      bytes.substr(start, eol == std::string_view::npos ? std::string_view::npos : eol - start);
  std::string version;
  std::string msg = headerProblem(line, version);
  if (!msg.empty()) {
    scene.diagnostics.error({url, 1, 1}, std::move(msg));
    return;
  }
  const bool wasX3d = ctx.x3d, wasVersion3 = ctx.x3dVersion3;
  const Context::Units wasUnits = ctx.units;
  ctx.units = {};
  ctx.x3d = !version.empty();
  ctx.x3dVersion3 = version.starts_with("3");
  if (ctx.x3d) {
    scene.x3d.version = version;
    scene.x3d.encoding = "Classic VRML";
  }
  Parser parser(bytes, url, eol == std::string_view::npos ? bytes.size() : eol, ctx,
                scene.diagnostics, externDepth, origin);
  parser.parseScene(scene);
  ctx.x3d = wasX3d;
  ctx.x3dVersion3 = wasVersion3;
  ctx.units = wasUnits;
}

}  // namespace gs::vrml::parsing

namespace gs::vrml {

Scene parseVrml(std::string_view bytes, const std::string& url, const ParseOptions& options) {
  Scene scene;
  scene.url = url;
  parsing::Context ctx(options);
  try {
    parsing::parseInto(bytes, url, ctx, 0, scene);
  } catch (const std::bad_alloc&) {
    scene.diagnostics.error({url, 0, 0}, "out of memory");
  }
  return scene;
}

Scene loadVrmlFile(const std::string& path, const ParseOptions& options) {
  std::string bytes, error;
  if (!parsing::readFile(path, options.limits.maxInputBytes, bytes, error)) {
    Scene scene;
    scene.url = path;
    scene.diagnostics.error({path, 0, 0}, error);
    return scene;
  }
  return parseVrml(bytes, path, options);
}

}  // namespace gs::vrml
