// base::IsolatedProcess (base/isolated_process.hpp): frames arrive in order, and every way
// a child can fail (an exception, a crash, too much memory, silence, an oversized frame)
// reaches the caller as an IsolationError that says which.
#include <catch2/catch.hpp>

#include <csignal>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include "base/isolated_process.hpp"

using Catch::Matchers::Contains;
using gs::base::FrameWriter;
using gs::base::IsolatedProcess;
using gs::base::IsolationError;
using gs::base::IsolationLimits;

TEST_CASE("an isolated child's frames arrive in order and whole", "[isolated]") {
  const std::string big(3 << 20, 'q');  // larger than a pipe's buffer
  IsolatedProcess p(
      [&](FrameWriter& out) {
        out.write("first");
        out.write(big);
        out.write("");
      },
      {});
  CHECK(p.next(100) == "first");
  CHECK(p.next(big.size()) == big);
  CHECK(p.next(100).empty());
  CHECK_THROWS_WITH(p.next(100), Contains("ended without an answer"));
}

TEST_CASE("what an isolated child throws reaches the caller after its frames", "[isolated]") {
  IsolatedProcess p(
      [](FrameWriter& out) {
        out.write("part");
        throw std::runtime_error("grid 'density' has no active voxels");
      },
      {});
  CHECK(p.next(100) == "part");
  CHECK_THROWS_WITH(p.next(100), "grid 'density' has no active voxels");
}

TEST_CASE("an isolated child that crashes, grows or falls silent is an error", "[isolated]") {
  SECTION("a crash") {
    IsolatedProcess p([](FrameWriter&) { std::raise(SIGSEGV); }, {});
    CHECK_THROWS_WITH(p.next(100), Contains("the reader ended by signal"));
  }
  SECTION("more memory than its limit") {
    IsolationLimits limits;
    limits.memoryBytes = std::uint64_t{16} << 20;
    IsolatedProcess p(
        [](FrameWriter& out) {
          std::vector<char> v(std::size_t{256} << 20, 1);
          out.write(std::string(1, v[12345]));
        },
        limits);
    // ran out of its 16 MiB of memory (std::bad_alloc), or a sanitizer's report and abort
    try {
      (void)p.next(100);
      FAIL("the child's allocation succeeded");
    } catch (const IsolationError& e) {
      const std::string what = e.what();
      CHECK((what.find("ran out of its 16 MiB of memory") != std::string::npos ||
             what.find("ended by signal") != std::string::npos));
    }
  }
  SECTION("silence") {
    IsolationLimits limits;
    limits.idleSeconds = 1;
    IsolatedProcess p([](FrameWriter&) { ::sleep(30); }, limits);
    CHECK_THROWS_WITH(p.next(100), "the reader sent nothing for 1 s and was stopped");
  }
  SECTION("a frame larger than asked for") {
    IsolatedProcess p([](FrameWriter& out) { out.write(std::string(1000, 'x')); }, {});
    CHECK_THROWS_WITH(p.next(10), Contains("sent a frame of 1000 bytes, more than 10"));
  }
}

TEST_CASE("the memory budget grows with the input within the machine", "[isolated]") {
  const std::uint64_t gib = std::uint64_t{1} << 30;
  CHECK(gs::base::isolationMemoryFor(0) == gib);
  CHECK(gs::base::isolationMemoryFor(std::uint64_t{1} << 20) >= gib);
  CHECK(gs::base::isolationMemoryFor(std::uint64_t{1} << 50) < (std::uint64_t{1} << 50));
}
