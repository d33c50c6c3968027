// Shared helpers for the test suites: where the project and the corpus are.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace gs::test {

/// The project's source folder (holds assets/ and tests/).
std::filesystem::path sourceDir();
/// ../shared/corpus beside the project; may not exist.
std::filesystem::path corpusDir();
/// True when the corpus folder `sub` (e.g. "vrml/kicad") exists; otherwise calls
/// Catch's WARN with a message naming it, so the caller can `return` (skip).
bool haveCorpus(const std::string& sub);
/// Every regular file under `dir` whose name ends with `suffix`, sorted.
std::vector<std::filesystem::path> filesWithSuffix(const std::filesystem::path& dir,
                                                   const std::string& suffix);

}  // namespace gs::test
