// Private to render/: bookkeeping shared by the OSMesa, EGL and GLFW context implementations,
// and the off-screen contexts' constructors.
#pragma once

#include <memory>

namespace gs::render {
class GlContext;
}

namespace gs::render::detail {

/// True when glad's function pointers were last loaded for `context` (an opaque key).
bool glFunctionsLoadedFor(const void* context);
/// Records that glad's function pointers now belong to `context` (nullptr: unknown).
void setGlFunctionsLoadedFor(const void* context);

/// The OSMesa off-screen context (context_osmesa.cpp); createOffscreenContext's default.
std::unique_ptr<GlContext> createOsMesaContext(int width, int height, int samples);
/// The EGL off-screen context (context_egl.cpp), for GHOSTSPACE_GL=egl.
std::unique_ptr<GlContext> createEglContext(int width, int height, int samples);

}  // namespace gs::render::detail
