// The UDP ports of the loopback the DIS tests listen and send on.
#pragma once

#include <unistd.h>

namespace gs::test {

/// A UDP port of the loopback for one DIS test: `offset` (0..99) keeps the tests apart
/// (test_dis_nodes.cpp 0..19, test_dis_warfare.cpp 21..29, test_dis_network.cpp 41..49),
/// the process id keeps another test process's apart. 20000..41999 + 100 x offset.
inline int disTestPort(int offset) {
  return 20000 + static_cast<int>(::getpid() % 20000) + 100 * offset;
}

}  // namespace gs::test
