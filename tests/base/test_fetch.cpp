// base::Fetcher's shared rules (base/fetch.hpp): fetchLocally, localFileFor, LocalFetcher.
#include "base/fetch.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace gs::base;

namespace {
std::string tempFile(const std::string& name, const std::string& bytes) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path.string();
}
}  // namespace

TEST_CASE("fetchLocally reads local files and data: URLs, refuses what remote content names",
          "[base][fetch]") {
  const std::string path = tempFile("gs_fetch_local.txt", "hello");
  auto got = fetchLocally(path, "");
  REQUIRE(got);
  CHECK(got->ready());
  CHECK(got->bytes == "hello");
  got = fetchLocally("file://" + path, "/home/me/world.wrl");
  REQUIRE(got);
  CHECK(got->bytes == "hello");

  got = fetchLocally("data:text/plain;base64,aGk=", "http://h.org/w.wrl");
  REQUIRE(got);
  CHECK(got->ready());
  CHECK(got->bytes == "hi");

  // Content from the network never reads a local file.
  got = fetchLocally(path, "http://h.org/w.wrl");
  REQUIRE(got);
  CHECK(got->state == FetchState::refused);
  CHECK(got->bytes.empty());
  CHECK(got->error.find("may only reference http(s) URLs") != std::string::npos);

  got = fetchLocally("/nonexistent/gs/none.png", "");
  REQUIRE(got);
  CHECK(got->state == FetchState::failed);
  CHECK(got->error.find("/nonexistent/gs/none.png") != std::string::npos);

  // The network is not this function's.
  CHECK_FALSE(fetchLocally("http://h.org/t.png", "http://h.org/w.wrl"));
  std::remove(path.c_str());
}

TEST_CASE("localFileFor names the file a worker may read, under the same rules", "[base][fetch]") {
  std::string error;
  CHECK(localFileFor("file:///a/my%20b.wav", "/w/world.wrl", error) == "/a/my b.wav");
  CHECK(error.empty());
  CHECK(localFileFor("http://h.org/b.wav", "/w/world.wrl", error).empty());
  CHECK(error.empty());
  CHECK(localFileFor("data:audio/wav;base64,AAAA", "", error).empty());
  CHECK(error.empty());
  CHECK(localFileFor("/etc/passwd", "https://h.org/w.wrl", error).empty());
  CHECK_FALSE(error.empty());
}

TEST_CASE("LocalFetcher and fetcherOr: no network without a loader", "[base][fetch]") {
  LocalFetcher local;
  const Fetched remote = local.fetch("http://h.org/t.png", "", FetchMode::background);
  CHECK(remote.state == FetchState::failed);
  CHECK(remote.error ==
        "http://h.org/t.png: only local files can be read without a network "
        "loader");
  CHECK(fetcherOr(nullptr).fetch("data:,x", "", FetchMode::whole).bytes == "x");
  CallbackFetcher mine([](const std::string& url, const std::string&, FetchMode) {
    return fetchReady("served " + url);
  });
  CHECK(fetcherOr(&mine).fetch("a", "", FetchMode::whole).bytes == "served a");
}
