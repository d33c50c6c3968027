// Baseline image checks shared by the render tests (docs/rendering-tests.md): the real
// binary renders with --snapshot, and the PNG is compared with tests/render/baselines.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace gs::test {

/// Maximum fraction of differing pixels for a baseline to pass, and the per-channel
/// tolerance (of 255) under which a pixel does not differ.
inline constexpr double kMaxFractionDiffering = 0.01;
inline constexpr int kChannelTolerance = 16;

/// Renders `args` (ghostspace arguments without --snapshot; the input last) to
/// build/render-actual/NAME.png and returns its path; REQUIREs exit code 0.
std::string snapshot(const std::string& name, const std::vector<std::string>& args);

/// Fraction of pixels of image `a` that differ from image `b` (PNG paths) by more than
/// `tolerance` (of 255) in some channel.
double fractionDiffering(const std::string& a, const std::string& b,
                         int tolerance = kChannelTolerance);

/// The centre pixel of the PNG at `path`: {red, green, blue}, 0..255.
std::array<int, 3> centrePixel(const std::string& path);

/// Renders and compares with tests/render/baselines/NAME.png under the metric above. A
/// missing baseline fails and leaves the rendered image to be looked at and copied in.
void checkBaseline(const std::string& name, const std::vector<std::string>& args);

}  // namespace gs::test
