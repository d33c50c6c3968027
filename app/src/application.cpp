#include "app/application.hpp"

namespace gs::app {
int run(int, char**) { return 0; }
}  // namespace gs::app
