#include "runtime/clock.hpp"

#include <chrono>

namespace gs::runtime {

double wallClockSeconds() {
  using namespace std::chrono;
  return duration<double>(system_clock::now().time_since_epoch()).count();
}

}  // namespace gs::runtime
