// Private to render/: bookkeeping shared by the OSMesa and GLFW context implementations.
#pragma once

namespace gs::render::detail {

/// True when glad's function pointers were last loaded for `context` (an opaque key).
bool glFunctionsLoadedFor(const void* context);
/// Records that glad's function pointers now belong to `context` (nullptr: unknown).
void setGlFunctionsLoadedFor(const void* context);

}  // namespace gs::render::detail
