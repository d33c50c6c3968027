#include "session/world.hpp"

#include "base/file.hpp"
#include "encodings/parser.hpp"
#include "formats/input_kind.hpp"
#include "qnv/error.hpp"
#include "session/splat_inputs.hpp"

#include <cctype>
#include <chrono>
#include <filesystem>
#include <unordered_set>
#include <vector>

namespace gs::session {

std::string unsupportedFormat(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return {};  // a tileset folder, or an error later
  if (formats::classifyFile(path) != formats::InputKind::unknown) return {};
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::string shown;  // printable ASCII only
  for (char c : extension.substr(0, 16))
    if (c > 0x20 && c < 0x7f) shown += c;
  return "unsupported format" + (shown.empty() ? std::string() : " (" + shown + ")") +
         ": not a VRML97 or X3D world, a mesh (.ply .obj .glb .gltf), a volume (.nrrd .nhdr "
         ".nii .dcm .tif .vdb), a QNV stream or tileset, or a Gaussian splatting scene (.ply .spz "
         ".sog "
         ".splat); README.md lists the formats";
}

LoadedWorld loadWorld(const std::string& input) {
  LoadedWorld w;
  const auto t0 = std::chrono::steady_clock::now();
  std::string path = input;
  std::string bytes, error;
  // A folder that holds a DICOM series or TIFF slices opens as its volume; its
  // name without the trailing '/' so that the world made for it resolves to it.
  std::error_code ec;
  const bool folder =
      std::filesystem::is_directory(path, ec) && formats::isVolume(formats::classifyFile(path));
  while (folder && path.size() > 1 && path.back() == '/') path.pop_back();
  if (!folder && !base::readFile(path, bytes, error)) {
    w.scene = std::make_shared<vrml::Scene>();
    w.scene->url = path;
    w.scene->diagnostics.error({path, 0, 0}, error);
  } else {
    w.readable = true;
    w.bytes = bytes.size();
    // A stream, mesh or volume opens as a world made for it (session/splat_inputs.hpp).
    std::string text;
    if (const std::string why = unsupportedFormat(path); !why.empty()) {
      w.readable = false;
      w.scene = std::make_shared<vrml::Scene>();
      w.scene->url = path;
      w.scene->diagnostics.error({path, 0, 0}, why);
    } else if (isSplatInput(path)) {
      try {
        text = worldTextFor(path);
      } catch (const qnv::InputError& e) {
        w.readable = false;
        w.scene = std::make_shared<vrml::Scene>();
        w.scene->url = path;
        w.scene->diagnostics.error({path, 0, 0}, e.what());
      }
    }
    if (w.readable)
      w.scene = std::make_shared<vrml::Scene>(vrml::parseVrml(text.empty() ? bytes : text, path));
  }
  w.parseSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return w;
}

std::map<std::string, std::size_t> countNodesByType(const vrml::Scene& scene) {
  std::map<std::string, std::size_t> counts;
  std::unordered_set<const vrml::Node*> seen;
  std::vector<const vrml::Node*> stack;
  for (const auto& n : scene.rootNodes)
    if (n) stack.push_back(n.get());
  while (!stack.empty()) {
    const vrml::Node* n = stack.back();
    stack.pop_back();
    if (!seen.insert(n).second) continue;
    ++counts[n->typeName()];
    // A PROTO instance also counts as what the world declares it to be (clause 4.8).
    if (const std::string& proto = n->protoName(); !proto.empty()) ++counts[proto + " (PROTO)"];
    for (std::size_t i = 0; i < n->fieldCount(); ++i) {
      const vrml::FieldValue& v = n->fieldAt(i);
      if (v.type() == vrml::FieldType::SFNode) {
        if (const auto& c = v.get<vrml::FieldType::SFNode>()) stack.push_back(c.get());
      } else if (v.type() == vrml::FieldType::MFNode) {
        for (const auto& c : v.get<vrml::FieldType::MFNode>())
          if (c) stack.push_back(c.get());
      }
    }
  }
  return counts;
}

}  // namespace gs::session
