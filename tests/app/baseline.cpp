#include "baseline.hpp"

#include <catch2/catch.hpp>

#include <filesystem>

#include "process.hpp"
#include "render/image.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace gs::test {

std::string snapshot(const std::string& name, const std::vector<std::string>& args) {
  const fs::path actualDir = fs::path(GS_BINARY_DIR) / "render-actual";
  fs::create_directories(actualDir);
  const fs::path actual = actualDir / (name + ".png");
  std::vector<std::string> all = {"--snapshot", actual.string()};
  all.insert(all.end(), args.begin(), args.end());
  const auto r = runGhostspace(all);
  INFO("stderr: " << r.err);
  REQUIRE(r.exitCode == 0);
  return actual.string();
}

double fractionDiffering(const std::string& a, const std::string& b, int tolerance) {
  return render::compareImages(render::readPng(a), render::readPng(b), tolerance).fractionDiffering;
}

std::array<int, 3> centrePixel(const std::string& path) {
  const render::Image image = render::readPng(path);
  const std::size_t i =
      (static_cast<std::size_t>(image.height / 2) * static_cast<std::size_t>(image.width) +
       static_cast<std::size_t>(image.width / 2)) *
      4;
  return {image.rgba[i], image.rgba[i + 1], image.rgba[i + 2]};
}

void checkBaseline(const std::string& name, const std::vector<std::string>& args) {
  const std::string actual = snapshot(name, args);
  const fs::path baseline = sourceDir() / "tests/render/baselines" / (name + ".png");
  if (!fs::exists(baseline)) {
    FAIL("no baseline " << baseline.string() << "; the rendered image is " << actual
                        << ": look at it, and copy it there if it is right");
  }
  const auto d = render::compareImages(render::readPng(actual), render::readPng(baseline.string()),
                                       kChannelTolerance);
  INFO(name << ": " << d.fractionDiffering * 100 << "% of pixels differ, mean abs "
            << d.meanAbsolute << ", PSNR " << d.psnr << " dB; actual " << actual);
  CHECK(d.fractionDiffering <= kMaxFractionDiffering);
}

}  // namespace gs::test
