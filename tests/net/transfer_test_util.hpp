// Helpers for the net/ tests: run a transfer to its end with a deadline, make test bytes,
// a temporary folder.
#pragma once

#include "net/loader.hpp"
#include "net/transfer.hpp"
#include "test_support.hpp"

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace gs::test {

/// What a transfer delivered and how it ended.
struct TransferResult {
  std::string bytes;           // everything take() returned
  net::TransferStatus status;  // the final status
  double seconds = 0.0;        // from startTransfer to the end
  int deliveries = 0;          // take() calls that returned bytes
  bool timedOut = false;       // still running at the deadline (then cancelled)
};

/// Pumps `loader` until every stream and fetch settled or `timeout` seconds passed;
/// whether it settled.
inline bool settle(net::Loader& loader, double timeout = 10.0) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
  while (!loader.settled() && std::chrono::steady_clock::now() < end) {
    loader.pump();
    loader.wait(0.01);
  }
  return loader.settled();
}

/// Drives `t` to its end, taking bytes as they arrive; cancels it after `timeout` s.
inline TransferResult drain(net::Transfer& t, double timeout = 20.0) {
  using Clock = std::chrono::steady_clock;
  TransferResult r;
  const auto start = Clock::now();
  for (;;) {
    t.wait(0.05);
    if (t.take(r.bytes) > 0) ++r.deliveries;
    const net::TransferStatus s = t.status();
    if (s.finished()) {
      if (t.take(r.bytes) > 0) ++r.deliveries;
      break;
    }
    if (std::chrono::duration<double>(Clock::now() - start).count() > timeout) {
      r.timedOut = true;
      t.cancel();
      break;
    }
  }
  r.status = t.status();
  r.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return r;
}

/// Starts `request` and drains it (see drain()).
inline TransferResult fetch(net::FetchRequest request, double timeout = 20.0) {
  const auto t = net::startTransfer(std::move(request));
  return drain(*t, timeout);
}

/// `n` deterministic bytes that do not compress (every byte value occurs).
inline std::string noiseBytes(std::size_t n, std::uint32_t seed = 1) {
  std::string s(n, '\0');
  std::uint32_t x = seed * 2654435761u + 1;
  for (char& c : s) {
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    c = static_cast<char>(x & 0xff);
  }
  return s;
}

/// About `n` bytes of VRML text (compresses well), each line different.
inline std::string vrmlText(std::size_t n) {
  std::string s = "#VRML V2.0 utf8\nShape { geometry IndexedFaceSet { coord Coordinate { point [\n";
  for (int i = 0; s.size() < n; ++i)
    s += "  " + std::to_string(i) + " " + std::to_string(i * 7 % 101) + " 0.5,\n";
  return s + "] } } }\n";
}

}  // namespace gs::test
