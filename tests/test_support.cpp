#include "test_support.hpp"

#include <stdlib.h>
#include <zlib.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>

namespace gs::test {

std::filesystem::path sourceDir() {
  return GS_SOURCE_DIR;
}

std::filesystem::path corpusDir() {
  return GS_CORPUS_DIR;
}

bool fixturesRequired() {
  const char* ci = std::getenv("CI");
  if (ci != nullptr) {
    const std::string v = ci;
    if (!v.empty() && v != "0" && v != "false") return true;
  }
  const char* all = std::getenv("GS_REQUIRE_ALL");
  return all != nullptr && std::string(all) == "1";
}

void missingFixture(const std::string& reason) {
  if (fixturesRequired()) {
    FAIL_CHECK("missing fixture: " << reason << " (CI or GS_REQUIRE_ALL=1 requires every fixture)");
    return;
  }
  WARN("SKIPPED: " << reason);
  std::cout << "GS_SKIP: " << reason << std::endl;
}

std::string fixtureProgram(const char* envName, const char* defaultPath) {
  const char* v = std::getenv(envName);
  return v != nullptr && *v != '\0' ? std::string(v) : std::string(defaultPath);
}

bool haveCorpus(const std::string& sub) {
  const auto dir = corpusDir() / sub;
  if (std::filesystem::is_directory(dir)) return true;
  missingFixture("corpus folder " + dir.string() + " is absent (see README: ../shared/corpus)");
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

std::string readBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void fillPseudoRandom(std::string& bytes, std::size_t from, std::uint32_t seed) {
  for (std::size_t i = from; i < bytes.size(); ++i) {
    seed = seed * 1664525u + 1013904223u;
    bytes[i] = static_cast<char>(seed >> 24);
  }
}

std::string gzip(const std::string& text) {
  z_stream zs{};
  REQUIRE(deflateInit2(&zs, 6, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY) == Z_OK);
  std::string out(deflateBound(&zs, static_cast<uLong>(text.size())) + 64, '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  zs.avail_in = static_cast<uInt>(text.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = static_cast<uInt>(out.size());
  REQUIRE(deflate(&zs, Z_FINISH) == Z_STREAM_END);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

TempDir::TempDir(const std::string& tag) {
  std::string tmpl = (std::filesystem::temp_directory_path() / ("gs-" + tag + "-XXXXXX")).string();
  REQUIRE(::mkdtemp(tmpl.data()) != nullptr);
  path = tmpl;
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path, ec);
}

std::string TempDir::write(const std::string& name, const std::string& bytes) const {
  const auto p = path / name;
  std::filesystem::create_directories(p.parent_path());
  std::ofstream out(p, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  REQUIRE(out.good());
  return p.string();
}

}  // namespace gs::test
