// formats::openVdbBytes on any bytes: OpenVDB's io::Stream (grid descriptors, metadata,
// transforms, tree topology, zip and blosc buffers) in the child process that bounds its
// memory (base/isolated_process.hpp), level sets turned into fog, and the frames the child
// sends checked by the caller. Grids are read whole when their box is small (2^18 voxels),
// so that an input cannot ask this harness for a time-out's worth of background voxels;
// a child that takes 4 s for a frame is stopped (an error, not a finding).
#include "formats/vdb_reader.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gs::fuzz::expectingErrors([&] {
    // 256 MiB to grow, and 4 s for each frame: under libFuzzer's 10 s time-out.
    const auto reader = gs::formats::openVdbBytes(std::string(gs::fuzz::view(data, size)),
                                                  "fuzz.vdb", "", {std::uint64_t{256} << 20, 4});
    if (reader->info().voxelCount() <= (std::uint64_t{1} << 18))
      (void)gs::qnv::readWholeVolume(*reader);
  });
  return 0;
}
