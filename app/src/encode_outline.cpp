// `ghostspace encode INPUT -o OUT.wrl --outline` (outline/outline_world.hpp).
#include <chrono>
#include <cstdio>
#include <fstream>

#include "app/commands.hpp"
#include "outline/outline_world.hpp"
#include "qnv/error.hpp"
#include "session/world.hpp"

namespace gs::app {

int runEncodeOutline(const Options& options) {
  const std::string& input = options.inputs.front();
  const std::string& output = options.encode.output;
  const auto t0 = std::chrono::steady_clock::now();
  const session::LoadedWorld world = session::loadWorld(input);
  for (const vrml::Diagnostic& d : world.scene->diagnostics.items)
    std::fprintf(stderr, "%s\n", d.format().c_str());
  if (!world.readable) return 1;
  outline::OutlineWorldSummary sum;
  std::string text;
  try {
    outline::OutlineOptions grouping;
    grouping.maxAngle = static_cast<float>(options.encode.maxAngle * 3.14159265358979 / 180.0);
    text = outline::writeOutlineWorld(world.scene, grouping, &sum);
  } catch (const qnv::InputError& error) {
    std::fprintf(stderr, "ghostspace: %s\n", error.what());
    return 1;
  }
  std::ofstream out(output, std::ios::binary | std::ios::trunc);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) {
    std::fprintf(stderr, "ghostspace: cannot write '%s'\n", output.c_str());
    return 1;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%s: %zu bytes, %zu triangles (%zu zero-area dropped)\n", input.c_str(), world.bytes,
              sum.triangles + sum.droppedTriangles, sum.droppedTriangles);
  std::printf(
      "%s: %zu bytes, %zu groups, %zu triangles, %zu outline vertices, %zu appearances; "
      "outlines in the first %zu bytes (%.1f%%); %.3f s\n",
      output.c_str(), sum.bytes, sum.groups, sum.triangles, sum.outlineVertices, sum.appearances,
      sum.outlineBytes,
      sum.bytes ? 100.0 * static_cast<double>(sum.outlineBytes) / static_cast<double>(sum.bytes)
                : 0.0,
      seconds);
  return 0;
}

}  // namespace gs::app
