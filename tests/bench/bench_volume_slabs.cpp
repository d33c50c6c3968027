// Out-of-core volumes (docs/out-of-core.md): writes a synthetic int16 volume from an
// analytic field (spheres, a torus and hashed noise) once to disk as a raw NRRD at each
// size, then streams it through the slab reader and the gradient step
// (qnv::forEachVolumeVector) under a memory bound, and prints voxels/s and the peak
// memory (VmHWM of /proc/self/status) per size. Each size runs in its own child process,
// so every peak is that size's own.
//
//   bench_volume_slabs [--sizes 256,512] [--big] [--memory MB] [--threads N]
//                      [--dir PATH] [--keep]
//
// --big adds 1024^3 (a 2 GiB file) when the disk holds it with 4 GiB to spare. --memory
// (default 512) is the gradient step's bound (qnv::slabSlicesForMemory). The files go
// to --dir (default: bench-volumes/ in the working folder) and are removed unless
// --keep. The data are read back from the page cache when memory allows: the figures
// are those of the decoding and the gradients, not of a disk.
#include <sys/statvfs.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "formats/volume_slabs.hpp"
#include "qnv/volume_slabs.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Peak resident memory of this process in MiB (VmHWM), -1 when unknown.
double peakMiB() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::atof(line.c_str() + 6) / 1024.0;
  return -1.0;
}

std::uint32_t hash(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

// The field at (x, y, z) of an n^3 grid: three solid spheres of different densities, a
// torus, and +-8 of noise, as a CT-like int16.
std::int16_t field(std::uint32_t x, std::uint32_t y, std::uint32_t z, std::uint32_t n) {
  const float s = 1.0f / static_cast<float>(n);
  const float px = x * s, py = y * s, pz = z * s;
  auto sphere = [&](float cx, float cy, float cz, float r) {
    const float d =
        std::sqrt((px - cx) * (px - cx) + (py - cy) * (py - cy) + (pz - cz) * (pz - cz));
    return d < r ? 1.0f : 0.0f;
  };
  float v = 600.0f * sphere(0.5f, 0.5f, 0.5f, 0.42f) + 900.0f * sphere(0.35f, 0.4f, 0.45f, 0.12f) +
            1400.0f * sphere(0.62f, 0.58f, 0.55f, 0.08f);
  const float ring = std::sqrt((px - 0.5f) * (px - 0.5f) + (py - 0.5f) * (py - 0.5f)) - 0.3f;
  if (ring * ring + (pz - 0.5f) * (pz - 0.5f) < 0.04f * 0.04f) v += 1000.0f;
  const std::uint32_t h = hash(x * 73856093U ^ y * 19349663U ^ z * 83492791U);
  v += static_cast<float>(static_cast<int>(h % 17) - 8);
  return static_cast<std::int16_t>(v);
}

// Writes the n^3 volume as an attached raw NRRD, slice by slice (memory: one slice).
void writeVolume(const std::string& path, std::uint32_t n) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) {
    std::fprintf(stderr, "bench_volume_slabs: cannot write %s\n", path.c_str());
    std::exit(1);
  }
  std::fprintf(f,
               "NRRD0004\ntype: short\ndimension: 3\nsizes: %u %u %u\nendian: little\n"
               "encoding: raw\nspacings: 1 1 1\n\n",
               n, n, n);
  std::vector<std::int16_t> slice(std::size_t{n} * n);
  for (std::uint32_t z = 0; z < n; ++z) {
    for (std::uint32_t y = 0; y < n; ++y)
      for (std::uint32_t x = 0; x < n; ++x) slice[x + std::size_t{n} * y] = field(x, y, z, n);
    if (std::fwrite(slice.data(), sizeof(std::int16_t), slice.size(), f) != slice.size()) {
      std::fprintf(stderr, "bench_volume_slabs: short write to %s\n", path.c_str());
      std::exit(1);
    }
  }
  std::fclose(f);
}

struct Options {
  std::vector<std::uint32_t> sizes{256, 512};
  bool big = false;
  std::uint64_t memoryMiB = 512;
  unsigned threads = 0;
  std::string dir = "bench-volumes";
  bool keep = false;
};

// The child's work: stream one file, print one line.
int streamOne(const std::string& path, std::uint32_t n, const Options& o) {
  const auto t0 = Clock::now();
  auto reader = gs::formats::openVolumeSlabs(path);
  gs::qnv::VolumeVectorOptions options;
  options.memoryBytes = o.memoryMiB << 20;
  options.threads = o.threads;
  const std::uint32_t slab = gs::qnv::slabSlicesForMemory(reader->info(), options.memoryBytes);
  const auto tRange = Clock::now();
  options.valueRange = gs::qnv::volumeValueRange(*reader, slab);
  const double rangeSeconds = since(tRange);
  const auto tVectors = Clock::now();
  double magnitudeSum = 0.0;
  const gs::qnv::VolumeVectorSummary s = gs::qnv::forEachVolumeVector(
      *reader, 0, n, options, [&](std::span<const gs::qnv::VolumeVector> v) {
        for (const auto& x : v) magnitudeSum += x.magnitude;
      });
  const double vectorSeconds = since(tVectors);
  const double total = since(t0);
  const double voxels = static_cast<double>(s.voxels);
  std::printf(
      "%5u^3 %9.1f MiB file | slab %4u slices | range pass %6.2f s | gradient pass %7.2f s"
      " %7.1f M voxels/s | %10llu vectors (%.1f%%) | total %7.2f s %6.1f M voxels/s |"
      " peak %7.1f MiB (sum %.3g)\n",
      n, voxels * 2 / 1048576.0, s.slabSlices, rangeSeconds, vectorSeconds,
      voxels / vectorSeconds / 1e6, static_cast<unsigned long long>(s.vectors),
      100.0 * static_cast<double>(s.vectors) / voxels, total, voxels / total / 1e6, peakMiB(),
      magnitudeSum);
  std::fflush(stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "bench_volume_slabs: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--sizes") {
      o.sizes.clear();
      const std::string list = next();
      for (std::size_t p = 0; p < list.size();) {
        const std::size_t comma = list.find(',', p);
        o.sizes.push_back(static_cast<std::uint32_t>(std::stoul(list.substr(p, comma - p))));
        p = comma == std::string::npos ? list.size() : comma + 1;
      }
    } else if (a == "--big") {
      o.big = true;
    } else if (a == "--memory") {
      o.memoryMiB = std::stoull(next());
    } else if (a == "--threads") {
      o.threads = static_cast<unsigned>(std::stoul(next()));
    } else if (a == "--dir") {
      o.dir = next();
    } else if (a == "--keep") {
      o.keep = true;
    } else {
      std::fprintf(stderr,
                   "usage: bench_volume_slabs [--sizes 256,512] [--big] [--memory MB] "
                   "[--threads N] [--dir PATH] [--keep]\n");
      return 2;
    }
  }
  std::filesystem::create_directories(o.dir);
  if (o.big) {
    struct statvfs fs {};
    const std::uint64_t need = (std::uint64_t{2} << 30) + (std::uint64_t{4} << 30);
    if (statvfs(o.dir.c_str(), &fs) == 0 && std::uint64_t{fs.f_bavail} * fs.f_frsize >= need)
      o.sizes.push_back(1024);
    else
      std::printf("--big: skipping 1024^3, less than 6 GiB free in %s\n", o.dir.c_str());
  }
  std::printf("bench_volume_slabs: memory bound %llu MiB, %u threads (%u cores)\n",
              static_cast<unsigned long long>(o.memoryMiB),
              o.threads ? o.threads : std::thread::hardware_concurrency(),
              std::thread::hardware_concurrency());
  for (std::uint32_t n : o.sizes) {
    const std::string path = o.dir + "/synthetic_" + std::to_string(n) + ".nrrd";
    std::error_code ec;
    if (!std::filesystem::exists(path, ec) ||
        std::filesystem::file_size(path, ec) < std::uint64_t{n} * n * n * 2) {
      const auto t0 = Clock::now();
      writeVolume(path, n);
      std::printf("%5u^3 written to %s in %.1f s\n", n, path.c_str(), since(t0));
      std::fflush(stdout);
    }
    const pid_t child = fork();
    if (child == 0) {
      try {
        _exit(streamOne(path, n, o));
      } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_volume_slabs: %s\n", e.what());
        _exit(1);
      }
    }
    int status = 0;
    waitpid(child, &status, 0);
    if (!o.keep) std::filesystem::remove(path, ec);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return 1;
  }
  return 0;
}
