# OpenGL loader generated at build time by Debian's python3-glad (glad 2). Every GL
# entry point is a function pointer loaded through the current context's own
# GetProcAddress (OSMesa or GLFW): libGL and libOSMesa both export gl* symbols, so a
# direct call could reach the wrong library (GUIDE.md section 5).
find_program(GLAD_EXECUTABLE glad REQUIRED)
set(GLAD_DIR ${CMAKE_BINARY_DIR}/glad)
add_custom_command(
  OUTPUT ${GLAD_DIR}/src/gl.c ${GLAD_DIR}/include/glad/gl.h
  COMMAND ${GLAD_EXECUTABLE} --api gl:core=4.5 --out-path ${GLAD_DIR} --reproducible --quiet c
  COMMENT "Generating the OpenGL 4.5 core loader with glad"
  VERBATIM)
add_library(glad_gl STATIC ${GLAD_DIR}/src/gl.c)
target_include_directories(glad_gl SYSTEM PUBLIC ${GLAD_DIR}/include)
set_target_properties(glad_gl PROPERTIES POSITION_INDEPENDENT_CODE ON)
