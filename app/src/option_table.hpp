// The ghostspace command line declared once (README.md, "Command line"): one row per
// option (name, value, where it goes, help), from which application.cpp registers every
// option with CLI11 (--help shows each default from the field's initial value) and
// --help-markdown prints README.md's option table. Private to app/src.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <variant>

#include "app/options.hpp"

namespace gs::app {

/// What the command line fills: Options, and the texts that are parsed after CLI11 ran
/// (their initial values are the defaults --help shows, taken from Options).
struct Arguments {
  Arguments();
  Options options;
  std::string size;                     // --size WxH
  std::string lod;                      // --lod F[,F...]
  std::string layout;                   // --layout NAME
  std::string mode;                     // --mode NAME
  std::string splatPath;                // --splat-path NAME
  std::string textureQuality = "high";  // --texture-quality low|medium|high
  std::string shading = "phong";        // --shading phong|gouraud
  std::string time;                     // --time T|T0:DT:N
  std::string snapshotAt;
  double scriptMegabytes = 0.0;  // --script-memory-limit MB
  bool noScripts = false;
  bool noProgress = false;        // ghostspace --no-progress
  bool encodeNoProgress = false;  // ghostspace encode --no-progress
  bool helpMarkdown = false;      // --help-markdown
};

/// Where an option's value goes.
using Field = std::variant<bool& (*)(Arguments&), int& (*)(Arguments&), unsigned& (*)(Arguments&),
                           std::uint64_t& (*)(Arguments&), double& (*)(Arguments&),
                           std::string& (*)(Arguments&)>;

/// The command an option belongs to.
enum class OptionScope { main, info, encode, convert, builtIn };

struct OptionSpec {
  OptionScope scope;
  const char* names;      // CLI11's: "--snapshot", "-o,--output"
  const char* valueName;  // "OUT.png"; "" for a flag
  Field field;            // unused for builtIn rows (--help, --version: CLI11's own)
  const char* help;       // --help and README.md
  const char* more = "";  // README.md only: what does not fit a terminal line
  /// The default shown: nullptr takes the field's initial value, "" shows none.
  const char* shownDefault = nullptr;
  std::optional<CLI::Validator> check = std::nullopt;
  const char* excludes = nullptr;  // an option of the same command it cannot go with
};

/// Every option, in the order --help and README.md list them.
std::span<const OptionSpec> optionTable();

/// Registers every row of `scope` on `app`, bound to `arguments`.
void registerOptions(OptionScope scope, CLI::App& app, Arguments& arguments);

/// README.md's option table (Markdown), printed by --help-markdown.
std::string optionsMarkdown();

}  // namespace gs::app
