// Shared helpers for the test suites: where the project and the corpus are, temporary
// folders, gzip data.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace gs::test {

/// The project's source folder (holds assets/ and tests/).
std::filesystem::path sourceDir();
/// ../shared/corpus beside the project; may not exist.
std::filesystem::path corpusDir();
/// True when every fixture must be present: the environment sets CI (to anything but
/// "", "0" or "false"; CI systems set CI=true) or GS_REQUIRE_ALL=1.
bool fixturesRequired();

/// Reports that a fixture a test needs (nginx, Xvfb, the corpus, a tool) is missing;
/// `reason` names it and how to get it. When fixturesRequired(), the running test fails
/// with "missing fixture: REASON" (a non-aborting Catch failure). Otherwise the test is
/// skipped: a line "GS_SKIP: REASON" goes to stdout, which ctest's
/// SKIP_REGULAR_EXPRESSION (set on every discovered test) reports as "Skipped", not
/// "Passed". Either way the caller then returns.
void missingFixture(const std::string& reason);

/// The program of a fixture: the environment variable `envName` when set (so a test of
/// the rule above can point it at a missing file, e.g. GS_NGINX=/nonexistent), else
/// `defaultPath`.
std::string fixtureProgram(const char* envName, const char* defaultPath);

/// True when the corpus folder `sub` (e.g. "vrml/kicad") exists; otherwise reports it with
/// missingFixture() so the caller can `return`.
bool haveCorpus(const std::string& sub);
/// Every regular file under `dir` whose name ends with `suffix`, sorted.
std::vector<std::filesystem::path> filesWithSuffix(const std::filesystem::path& dir,
                                                   const std::string& suffix);

/// The bytes of the file at `path`; empty when it cannot be read.
std::string readBytes(const std::filesystem::path& path);

/// `text` compressed as one gzip member (RFC 1952, zlib level 6).
std::string gzip(const std::string& text);

/// `bytes` from byte `from` on replaced by the bytes of a linear congruential generator
/// seeded with `seed` (Numerical Recipes' constants): data that vary as a capture's SH do,
/// the same on every machine. Used on bunny_small_v3.spz's decompressed bytes, whose SH
/// (from 16 + 3000 x 20 on) are all zero.
void fillPseudoRandom(std::string& bytes, std::size_t from, std::uint32_t seed);

/// A fresh folder under the system's temporary folder ("gs-TAG-XXXXXX", made by mkdtemp),
/// removed with everything in it on destruction.
class TempDir {
 public:
  explicit TempDir(const std::string& tag = "test");
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  /// Writes `bytes` to path / `name` (folders made as needed); returns the full path.
  std::string write(const std::string& name, const std::string& bytes) const;

  std::filesystem::path path;
};

}  // namespace gs::test
