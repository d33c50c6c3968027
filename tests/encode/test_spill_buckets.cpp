// The out-of-core Gaussian encode's buckets (encode/src/spill_buckets.hpp): records by key
// held in a bounded buffer, spilled past it, taken back in ascending key in the order they
// came, whatever the spills; a damaged spill or a key out of order is refused.
#include <cstdint>
#include <filesystem>
#include <map>
#include <random>
#include <stdexcept>
#include <vector>

#include <catch2/catch.hpp>

#include "../../encode/src/spill_buckets.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using gs::encode::SpillBuckets;

TEST_CASE("spill buckets give back every key's records in the order they came", "[encode][ooc]") {
  gs::test::TempDir dir("spill_buckets");
  constexpr std::size_t kWords = 3;
  for (const std::uint64_t bound : {std::uint64_t{1} << 20, std::uint64_t{200}, std::uint64_t{1}}) {
    INFO("bound " << bound);
    SpillBuckets buckets(dir.path / "b.spill", bound, kWords, 5000);
    std::map<std::uint64_t, std::vector<std::uint32_t>> expected;
    std::mt19937 random(3);
    for (std::uint32_t i = 0; i < 5000; ++i) {
      // Keys spread over 64 bits (a node key puts its level in the top bits).
      const std::uint64_t key = (std::uint64_t{random() % 40} << 58) | (random() % 3);
      const std::uint32_t record[kWords] = {i, static_cast<std::uint32_t>(key), i * 7u};
      buckets.add(key, record, 1);
      expected[key].insert(expected[key].end(), record, record + kWords);
    }
    if (bound == 1) CHECK(buckets.spills() == 4999);  // one record a spill, the last held
    if (bound == std::uint64_t{1} << 20) CHECK(buckets.spills() == 0);
    std::vector<std::uint64_t> keys = buckets.keys();
    REQUIRE(keys.size() == expected.size());
    std::size_t n = 0;
    for (const auto& [key, records] : expected) {
      REQUIRE(keys[n++] == key);
      if (n % 5 == 3) continue;  // a key skipped is passed over
      CHECK(buckets.take(key) == records);
    }
    CHECK_THROWS_AS(buckets.take(keys.front()), std::logic_error);
  }
}

TEST_CASE("spill buckets refuse a damaged spill file", "[encode][ooc]") {
  gs::test::TempDir dir("spill_buckets_damaged");
  const fs::path path = dir.path / "d.spill";
  SpillBuckets buckets(path, 1, 1, 10);
  for (std::uint32_t i = 0; i < 4; ++i) buckets.add(i, &i, 1);
  REQUIRE(buckets.spills() >= 3);
  const auto keys = buckets.keys();
  CHECK(buckets.take(keys[0]) == std::vector<std::uint32_t>{0});
  // The last spill cut short: its run (its header read already) cannot be read back.
  fs::resize_file(path, fs::file_size(path) - 2);
  CHECK(buckets.take(keys[1]) == std::vector<std::uint32_t>{1});
  CHECK_THROWS_AS(buckets.take(keys[2]), gs::encode::SpillFailure);
}
