// QNV: Quantized Normal Vectors (Nagasawa, "Beyond VRML", sections 2 and 3.6). The codec
// arrives with its own issue; this header pins the record size the paper fixes.
#pragma once

#include <cstddef>

namespace gs::qnv {

/// Bytes per QNV record: X, Y, Z 10 bits each, Theta 5, Phi 6, A 15, C 8 (paper fig. 6).
inline constexpr std::size_t kRecordBytes = 8;

}  // namespace gs::qnv
