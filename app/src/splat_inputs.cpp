#include "app/splat_inputs.hpp"

#include "app/commands.hpp"
#include "app/mesh_input.hpp"
#include "app/volume_input.hpp"
#include "qnv/encoder.hpp"
#include "qnv/error.hpp"
#include "render/traversal.hpp"

namespace gs::app {

bool isSplatInput(const std::string& path) {
  return isQnvFile(path) || isMeshFile(path) || isVolumeFile(path);
}

std::string splatWorldText(const std::string& path) {
  std::string escaped;
  for (char c : path) {
    if (c == '"' || c == '\\') escaped.push_back('\\');
    escaped.push_back(c);
  }
  return "#VRML V2.0 utf8\n# " + std::string("A QNV world made by ghostspace for one file.\n") +
         "NavigationInfo { type [\"EXAMINE\", \"ANY\"] }\n" +
         "QuantizedNormalVectors { url \"" + escaped + "\" }\n";
}

render::SplatLoader splatLoader() {
  return [](const std::string& url, std::string& error) -> std::shared_ptr<const render::SplatSet> {
    const std::string path = render::localPathOfUrl(url);
    if (path.empty()) {
      error = "cannot read " + url + ": only local files are supported here";
      return nullptr;
    }
    try {
      if (isVolumeFile(path)) return render::splatSetFromEncoded(qnv::encodeVolume(loadVolumeFile(path), {}));
      if (isMeshFile(path)) return render::splatSetFromEncoded(qnv::encodeSurface(loadMeshFile(path), {}));
    } catch (const qnv::InputError& e) {
      error = e.what();
      return nullptr;
    }
    return render::loadQnvFile(path, error);
  };
}

}  // namespace gs::app
