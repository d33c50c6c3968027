// qnv::Volume helpers (qnv/volume.hpp).
#include "qnv/volume.hpp"

namespace gs::qnv {

std::size_t scalarBytes(ScalarType type) {
  switch (type) {
    case ScalarType::int8:
    case ScalarType::uint8:
      return 1;
    case ScalarType::int16:
    case ScalarType::uint16:
      return 2;
    case ScalarType::int32:
    case ScalarType::uint32:
    case ScalarType::float32:
      return 4;
    case ScalarType::int64:
    case ScalarType::uint64:
    case ScalarType::float64:
      return 8;
  }
  return 1;
}

}  // namespace gs::qnv
