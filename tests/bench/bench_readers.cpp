// Reader throughput in MB/s of file bytes (issue 42: each reader beside the NRRD
// reader's, on the same machine): volumes through session::loadVolumeFile (NRRD, NIfTI,
// DICOM files, series folders and DICOMDIRs through GDCM),
// splat scenes and point clouds through splats::readGaussians (LAS, SPZ, PLY, ...). Each
// file is read from memory (the file's bytes loaded first, not timed) ROUNDS times; the
// best round is printed. Volumes are read from their file (the loader opens it itself),
// so their figure includes the file system and gzip, and their bytes are those of their
// samples as stored (voxels times the sample type's size), not of the (detached) header.
//
//   bench_readers [--rounds N] FILE...
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "base/file.hpp"
#include "formats/input_kind.hpp"
#include "session/volume_input.hpp"
#include "splats/readers.hpp"

using namespace gs;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
  int rounds = 5;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--rounds") == 0 && i + 1 < argc)
      rounds = std::max(1, std::atoi(argv[++i]));
    else
      files.emplace_back(argv[i]);
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: bench_readers [--rounds N] FILE...\n");
    return 2;
  }
  std::printf("%-48s %12s %10s %10s %10s\n", "file", "bytes", "elements", "best s", "MB/s");
  for (const std::string& file : files) {
    std::string bytes, error;
    const bool volume = formats::isVolume(formats::classifyFile(file));  // maybe a folder
    if (!volume && !base::readFile(file, bytes, error, std::size_t{8} << 30)) {
      std::fprintf(stderr, "bench_readers: %s\n", error.c_str());
      return 1;
    }
    double best = 1e30;
    std::size_t elements = 0, measured = bytes.size();
    for (int r = 0; r < rounds; ++r) {
      const auto t0 = Clock::now();
      if (volume) {
        const qnv::Volume v = session::loadVolumeFile(file);
        elements = v.voxelCount();
        measured = v.voxelCount() * qnv::scalarBytes(v.sourceType);  // the samples' bytes
      } else {
        elements = splats::readGaussians(bytes, file, {}).size();
      }
      best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
    }
    std::printf("%-48s %12zu %10zu %10.4f %10.1f\n", file.c_str(), measured, elements, best,
                static_cast<double>(measured) / 1e6 / best);
  }
  return 0;
}
