# Debian's libimgui-dev ships Dear ImGui 1.86 as a static library without backends; the
# GLFW and OpenGL3 backends are compiled from its examples folder.
set(IMGUI_BACKENDS_DIR /usr/share/doc/libimgui-dev/examples/backends)
add_library(imgui_backends STATIC
  ${IMGUI_BACKENDS_DIR}/imgui_impl_glfw.cpp
  ${IMGUI_BACKENDS_DIR}/imgui_impl_opengl3.cpp)
# Its two files define the same GL loader names differently: never one unity batch.
set_target_properties(imgui_backends PROPERTIES UNITY_BUILD OFF)
target_include_directories(imgui_backends SYSTEM PUBLIC /usr/include/imgui /usr/include/imgui/backends)
target_link_libraries(imgui_backends PUBLIC PkgConfig::IMGUI glfw ${CMAKE_DL_LIBS})
# Third-party code: ImGui 1.86's gl3w loader indexes its function table past the declared
# array bound (a union trick UBSan flags); it is not ours to change, so no UBSan here.
if(GS_SANITIZE)
  target_compile_options(imgui_backends PRIVATE -fno-sanitize=undefined)
endif()
