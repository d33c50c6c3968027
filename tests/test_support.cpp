#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>

namespace gs::test {

std::filesystem::path sourceDir() {
  return GS_SOURCE_DIR;
}

std::filesystem::path corpusDir() {
  return GS_CORPUS_DIR;
}

bool haveCorpus(const std::string& sub) {
  const auto dir = corpusDir() / sub;
  if (std::filesystem::is_directory(dir)) return true;
  WARN("SKIPPED: corpus folder " << dir.string() << " is absent");
  return false;
}

std::vector<std::filesystem::path> filesWithSuffix(const std::filesystem::path& dir,
                                                   const std::string& suffix) {
  std::vector<std::filesystem::path> out;
  if (!std::filesystem::is_directory(dir)) return out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (e.is_regular_file() && name.size() >= suffix.size() &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace gs::test
