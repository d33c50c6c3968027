// `ghostspace info SCENE`: a 3D Gaussian splatting scene file (docs/splats.md, "Formats"):
// its format, splats, SH degree, colour space, bounds, scales and opacities.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <string>

#include "app/commands.hpp"
#include "base/fetch.hpp"
#include "base/file.hpp"
#include "session/splat_inputs.hpp"
#include "splats/readers.hpp"

namespace gs::app {

namespace {

const char* formatName(splats::SplatFormat f) {
  switch (f) {
    case splats::SplatFormat::ply:
      return "3D Gaussian splatting PLY (INRIA)";
    case splats::SplatFormat::compressedPly:
      return "PlayCanvas compressed PLY";
    case splats::SplatFormat::splat:
      return ".splat (32 bytes a splat)";
    case splats::SplatFormat::spz:
      return "Niantic SPZ";
    case splats::SplatFormat::sog:
      return "PlayCanvas SOG bundle";
    case splats::SplatFormat::sogMeta:
      return "PlayCanvas SOG (meta.json and WebP images)";
    case splats::SplatFormat::gltf:
      return "glTF KHR_gaussian_splatting";
    case splats::SplatFormat::las:
      return "LAS point cloud (as Gaussians)";
    case splats::SplatFormat::qnv:
      return "QNV Gaussian stream";
    case splats::SplatFormat::unknown:
      break;
  }
  return "unknown";
}

/// What the info says of a scene, gathered a batch at a time.
struct SceneStatistics {
  std::uint64_t splats = 0;
  int shDegree = 0;
  splats::ColorSpace colorSpace = splats::ColorSpace::srgb;
  glm::vec3 low{std::numeric_limits<float>::infinity()};
  glm::vec3 high{-std::numeric_limits<float>::infinity()};
  float smallest = std::numeric_limits<float>::infinity(), largest = 0.0f;  // largest axis
  double opacity = 0.0;                                                     // sum
  std::uint64_t invisible = 0;  // opacity below 1/255: nothing drawn

  void add(const splats::GaussianCloud& c) {
    shDegree = c.shDegree;
    colorSpace = c.colorSpace;
    for (std::size_t i = 0; i < c.size(); ++i) {
      low = glm::min(low, c.positions[i]);
      high = glm::max(high, c.positions[i]);
      const glm::vec3 s = c.scales[i];
      const float axis = std::max({s.x, s.y, s.z});
      smallest = std::min(smallest, axis);
      largest = std::max(largest, axis);
      opacity += c.opacities[i];
      invisible += c.opacities[i] < 1.0f / 255.0f;
    }
    splats += c.size();
  }
};

}  // namespace

int runGaussianInfo(const std::string& path) {
  const auto start = std::chrono::steady_clock::now();
  std::string head, error;
  {
    std::ifstream in(path, std::ios::binary);
    head.resize(std::size_t{1} << 20);
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(std::max<std::streamsize>(0, in.gcount())));
  }
  SceneStatistics s;
  try {
    base::LocalFetcher fetcher;  // SOG's images and a .gltf's buffers beside it
    const splats::SideFileReader sideFiles = session::sideFileReader(fetcher, path);
    std::unique_ptr<splats::GaussianBatchReader> reader;
    try {
      reader = splats::openGaussianBatches(path, sideFiles);
    } catch (const splats::NotPiecewiseError&) {
    }
    if (reader) {  // a batch at a time: a scene larger than memory is described too
      splats::GaussianCloud batch;
      while (reader->read(batch, 65536) > 0) s.add(batch);
    } else {
      std::string bytes;
      if (!base::readFile(path, bytes, error, std::size_t{16} << 30)) {
        std::fprintf(stderr, "ghostspace: %s\n", error.c_str());
        return 1;
      }
      s.add(splats::readGaussians(bytes, path, sideFiles));
    }
  } catch (const std::exception& e) {  // FormatError, or a library's own
    std::fprintf(stderr, "ghostspace: %s\n", e.what());
    return 1;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  const splats::SplatFormat format = splats::detectSplatFormat(head, path);
  std::printf("%s: %s\n", path.c_str(), formatName(format));
  std::printf("  splats      %llu, SH degree %d, colours %s\n",
              static_cast<unsigned long long>(s.splats), s.shDegree,
              s.colorSpace == splats::ColorSpace::linear ? "linear Rec. 709" : "sRGB");
  if (s.splats > 0) {
    std::printf("  bounds      %g %g %g .. %g %g %g (the reader's axes)\n", s.low.x, s.low.y,
                s.low.z, s.high.x, s.high.y, s.high.z);
    std::printf("  scales      largest axis %g .. %g\n", s.smallest, s.largest);
    std::printf("  opacity     mean %.3f, %llu splats below 1/255\n",
                s.opacity / static_cast<double>(s.splats),
                static_cast<unsigned long long>(s.invisible));
  }
  if (!ec && s.splats > 0 && format != splats::SplatFormat::sogMeta)  // not its images
    std::printf("  bytes       %llu, %.1f a splat\n", static_cast<unsigned long long>(bytes),
                static_cast<double>(bytes) / static_cast<double>(s.splats));
  std::printf("  read time   %.3f s\n", seconds);
  return 0;
}

}  // namespace gs::app
