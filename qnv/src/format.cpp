#include "qnv/format.hpp"

static_assert(gs::qnv::kRecordBytes * 8 == 10 + 10 + 10 + 5 + 6 + 15 + 8);
