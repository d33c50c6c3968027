// antimatter15 .splat (readers.hpp): a headerless array of 32-byte records, float32
// x y z, float32 linear scales, uint8 R G B A, uint8 rotation w x y z mapped from -1..1.
// Decoded as splat-transform 3.7's readSplat does (the file's own axes, Transform.PLY;
// rotation byte b is b / 255 * 2 - 1; colour c is shDc = (c / 255 - 0.5) / kShC0).
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "base/byte_order.hpp"
#include "reader_support.hpp"

namespace gs::splats {

GaussianCloud readSplatGaussians(std::string_view bytes, std::string_view name) {
  constexpr std::size_t kRecord = 32;
  if (bytes.empty()) detail::fail(name, "expected at least one 32-byte splat, got 0 bytes");
  if (bytes.size() % kRecord != 0)
    detail::fail(name, "expected a multiple of 32 bytes, got " + std::to_string(bytes.size()));
  const std::size_t count = bytes.size() / kRecord;
  detail::checkCount(name, count, kRecord, bytes.size(), "splats");
  GaussianCloud cloud;
  detail::allocate(cloud, count, 0);
  for (std::size_t i = 0; i < count; ++i) {
    const char* r = bytes.data() + i * kRecord;
    auto f = [&](int k) { return base::loadFloatLe(r + 4 * k); };
    auto u = [&](int k) { return static_cast<float>(static_cast<std::uint8_t>(r[k])); };
    cloud.positions[i] = glm::vec3(f(0), f(1), f(2));
    cloud.scales[i] = glm::abs(glm::vec3(f(3), f(4), f(5)));  // covariance is sign-blind
    cloud.shDc[i] = (glm::vec3(u(24), u(25), u(26)) / 255.0f - 0.5f) / kShC0;
    cloud.opacities[i] = u(27) / 255.0f;
    auto q = [&](int k) { return u(k) / 255.0f * 2.0f - 1.0f; };
    cloud.rotations[i] = detail::unitQuat(q(28), q(29), q(30), q(31));
  }
  return cloud;
}

namespace {

/// A .splat read a batch of 32-byte rows at a time (each batch through readSplatGaussians).
class SplatBatches final : public GaussianBatchReader {
 public:
  explicit SplatBatches(const std::string& path) : file_(path) {
    if (file_.size() == 0 || file_.size() % kRecord != 0)
      detail::fail(path,
                   "expected a non-zero multiple of 32 bytes, got " + std::to_string(file_.size()));
    detail::checkCount(path, file_.size() / kRecord, kRecord, file_.size(), "splats");
  }
  std::uint64_t size() const override { return file_.size() / kRecord; }
  int shDegree() const override { return 0; }
  std::size_t rowBytes() const override { return kRecord; }
  std::size_t read(GaussianCloud& batch, std::size_t max) override {
    const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(max, size() - next_));
    if (n == 0) {
      batch = GaussianCloud{};
      return 0;
    }
    rows_.resize(n * kRecord);
    file_.read(next_ * kRecord, rows_.data(), rows_.size());
    next_ += n;
    batch = readSplatGaussians(rows_, file_.path());
    return n;
  }
  void rewind() override { next_ = 0; }

 private:
  static constexpr std::size_t kRecord = 32;
  detail::PieceFile file_;
  std::uint64_t next_ = 0;
  std::string rows_;
};

}  // namespace

std::unique_ptr<GaussianBatchReader> openSplatGaussianBatches(const std::string& path) {
  return std::make_unique<SplatBatches>(path);
}

}  // namespace gs::splats
