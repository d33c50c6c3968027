#include "app/auto_lod.hpp"

#include <algorithm>
#include <cmath>

namespace gs::app {

std::uint64_t autoLodBudget(std::uint64_t userBudget, double splatRate, double targetSeconds) {
  double cap = static_cast<double>(kFirstFrameVectors);
  if (splatRate > 0.0 && std::isfinite(splatRate) && targetSeconds > 0.0)
    cap = std::max(splatRate * 2.0 * targetSeconds, static_cast<double>(kMinAutoVectors));
  const auto capped = static_cast<std::uint64_t>(std::min(cap, 1e15));
  return userBudget > 0 ? std::min(userBudget, capped) : capped;
}

double autoLodRatio(double targetSeconds, double takenSeconds) {
  if (!(takenSeconds > 0.0) || !(targetSeconds > 0.0)) return 1.0;
  const double ratio = targetSeconds / takenSeconds;
  if (ratio < 0.5) return std::max(ratio, 1.0 / 64.0);
  return std::clamp(std::sqrt(ratio), 0.5, 2.0);
}

}  // namespace gs::app
