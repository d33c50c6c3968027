#include "app/application.hpp"

#include "app/commands.hpp"
#include "app/options.hpp"

#include <CLI/CLI.hpp>

#include <charconv>
#include <cstdio>
#include <exception>
#include <string>

#ifndef GS_VERSION
#define GS_VERSION "0.0.0"
#endif

namespace gs::app {

bool parseSize(const std::string& text, int& width, int& height) {
  const auto x = text.find('x');
  if (x == std::string::npos) return false;
  auto parseSide = [](const char* b, const char* e, int& out) {
    auto [p, ec] = std::from_chars(b, e, out);
    return ec == std::errc() && p == e && out >= 1 && out <= 16384;
  };
  const char* s = text.data();
  return parseSide(s, s + x, width) && parseSide(s + x + 1, s + text.size(), height);
}

namespace {

constexpr const char* kDescription =
    "GhostSpace " GS_VERSION
    ": an extended VRML97 browser for remote visualization of large 3D data.\n"
    "Opens VRML97 worlds (.wrl, .wrl.gz, .wrz) in a window, or renders them headless.";

struct Parsed {
  Options options;
  int exitCode = -1;  // >= 0: stop with this code (help, version, usage error)
};

Parsed parseArguments(int argc, char** argv) {
  Parsed r;
  Options& o = r.options;
  CLI::App cli{kDescription, "ghostspace"};
  cli.set_version_flag("--version", std::string("ghostspace ") + GS_VERSION);
  cli.footer(
      "Examples:\n"
      "  ghostspace world.wrl                          open a window\n"
      "  ghostspace --snapshot out.png --size 640x480 world.wrl\n"
      "  ghostspace info world.wrl                     print what was read");
  std::string size;
  cli.add_option("--snapshot", o.snapshotPath,
                 "Render INPUT off-screen (no display needed) from its bound Viewpoint and "
                 "write a PNG to this path")
      ->type_name("OUT.png");
  cli.add_option("--size", size, "Image or window size in pixels, e.g. 800x600")->type_name("WxH");
  cli.add_option("--frames", o.frames, "Close the window after this many frames (testing)")
      ->check(CLI::NonNegativeNumber);
  cli.add_option("INPUT", o.inputs, "VRML97 worlds to open (.wrl, .wrl.gz, .wrz)");

  CLI::App* info = cli.add_subcommand("info",
                                      "Print what was read from INPUT: node counts, "
                                      "triangles, bounding box, diagnostics, parse time");
  std::vector<std::string> infoInputs;
  info->add_option("INPUT", infoInputs, "VRML97 world")->required();

  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(cli.help().c_str(), stdout);
    r.exitCode = 0;
    return r;
  } catch (const CLI::CallForVersion&) {
    std::printf("ghostspace %s\n", GS_VERSION);
    r.exitCode = 0;
    return r;
  } catch (const CLI::ExtrasError& e) {
    std::fprintf(stderr, "ghostspace: %s\n", e.what());
    r.exitCode = 2;
    return r;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "ghostspace: %s (see --help)\n", e.what());
    r.exitCode = 2;
    return r;
  }
  if (!size.empty() && !parseSize(size, o.width, o.height)) {
    std::fprintf(stderr, "ghostspace: --size: expected WxH such as 800x600, got '%s'\n",
                 size.c_str());
    r.exitCode = 2;
    return r;
  }
  if (info->parsed()) {
    o.command = Command::info;
    o.inputs = infoInputs;
  } else if (!o.snapshotPath.empty()) {
    o.command = Command::snapshot;
    if (o.inputs.size() != 1) {
      std::fprintf(stderr, "ghostspace: --snapshot needs exactly one INPUT, got %zu\n",
                   o.inputs.size());
      r.exitCode = 2;
    }
  }
  return r;
}

}  // namespace

int run(int argc, char** argv) {
  Parsed p = parseArguments(argc, argv);
  if (p.exitCode >= 0) return p.exitCode;
  try {
    switch (p.options.command) {
      case Command::info:
        return runInfo(p.options);
      case Command::snapshot:
        return runSnapshot(p.options);
      case Command::window:
        return runWindow(p.options);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ghostspace: %s\n", e.what());
    return 1;
  }
  return 1;
}

}  // namespace gs::app
