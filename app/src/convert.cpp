// `ghostspace convert IN -o OUT`: a world from one encoding to another (encodings/writer.hpp,
// docs/x3d.md "Conversion").
#include "app/commands.hpp"
#include "encodings/writer.hpp"
#include "session/world.hpp"

#include <cstdio>
#include <fstream>

namespace gs::app {

int runConvert(const Options& options) {
  const std::string& input = options.inputs.front();
  const std::string& output = options.convertOutput;
  const auto encoding = vrml::encodingForPath(output);
  if (!encoding) {
    std::fprintf(stderr, "ghostspace: convert: %s: OUT must end with .wrl, .x3dv, .x3d or .x3dj\n",
                 output.c_str());
    return 2;
  }
  const session::LoadedWorld w = session::loadWorld(input);
  for (const auto& d : w.scene->diagnostics.items)
    std::fprintf(stderr, "ghostspace: %s\n", d.format().c_str());
  if (!w.readable) return 1;

  const vrml::WriteResult r = vrml::writeScene(*w.scene, vrml::WriteOptions{*encoding});
  for (const auto& d : r.diagnostics.items)
    std::fprintf(stderr, "ghostspace: %s\n", d.format().c_str());
  std::ofstream out(output, std::ios::binary);
  out.write(r.text.data(), static_cast<std::streamsize>(r.text.size()));
  out.close();
  if (!out) {
    std::fprintf(stderr, "ghostspace: convert: cannot write %s\n", output.c_str());
    return 1;
  }
  std::printf("%s -> %s (%s, %zu bytes): %zu root nodes, %zu PROTOs, %zu ROUTEs, %zu warnings\n",
              input.c_str(), output.c_str(), std::string(vrml::encodingName(*encoding)).c_str(),
              r.text.size(), w.scene->rootNodes.size(), w.scene->protos.size(),
              w.scene->routes.size(), r.diagnostics.items.size());
  return w.scene->diagnostics.hasErrors() ? 1 : 0;
}

}  // namespace gs::app
