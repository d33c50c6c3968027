# Duktape (ECMAScript engine for the Script node, runtime/src/script_ecmascript*.cpp),
# built from Debian's duktape-dev source (/usr/share/duktape) because the packaged
# libduktape.so lacks the hooks a sandbox needs. The configuration is Debian's
# duk_config.h with these changes, written into the build folder at configure time:
#   - DUK_USE_INTERRUPT_COUNTER + DUK_USE_EXEC_TIMEOUT_CHECK: a Script call that runs past
#     its time budget is stopped (gs_duk_exec_timeout_check in script_ecmascript.cpp);
#   - DUK_USE_NATIVE_STACK_CHECK: deep C recursion (getters calling getters, nested
#     source, regular expressions) ends with a RangeError before the thread's stack runs
#     out (gs_duk_native_stack_check);
#   - DUK_USE_CPP_EXCEPTIONS: duktape.c is compiled as C++ and errors are C++ exceptions,
#     so an error thrown through our native functions runs their destructors (longjmp
#     would skip them);
#   - the regular-expression step limit is 1e7 instead of 1e9 (a catastrophic
#     backtracking pattern ends in well under a second; no interrupt runs inside it);
#   - the compiler's recursion also checks the native stack (below).
# Third-party code: no gs_warnings, warnings off.
set(GS_DUKTAPE_SOURCE_DIR /usr/share/duktape CACHE PATH "Duktape source (duktape.c, duk_config.h)")
set(_duk_out ${CMAKE_BINARY_DIR}/duktape)
file(MAKE_DIRECTORY ${_duk_out})
if(NOT EXISTS ${GS_DUKTAPE_SOURCE_DIR}/duktape.c)
  message(FATAL_ERROR "Duktape source not found in ${GS_DUKTAPE_SOURCE_DIR} (install duktape-dev)")
endif()

file(READ ${GS_DUKTAPE_SOURCE_DIR}/duk_config.h _duk_config)
foreach(_pair
    "#undef DUK_USE_INTERRUPT_COUNTER|#define DUK_USE_INTERRUPT_COUNTER"
    "#undef DUK_USE_EXEC_TIMEOUT_CHECK|#define DUK_USE_EXEC_TIMEOUT_CHECK(udata) gs_duk_exec_timeout_check(udata)"
    "#undef DUK_USE_NATIVE_STACK_CHECK|#define DUK_USE_NATIVE_STACK_CHECK() gs_duk_native_stack_check()"
    "#undef DUK_USE_CPP_EXCEPTIONS|#define DUK_USE_CPP_EXCEPTIONS")
  string(REPLACE "|" ";" _parts "${_pair}")
  list(GET _parts 0 _from)
  list(GET _parts 1 _to)
  string(FIND "${_duk_config}" "${_from}\n" _at)
  if(_at EQUAL -1)
    message(FATAL_ERROR "Duktape config: '${_from}' not found in duk_config.h")
  endif()
  string(REPLACE "${_from}\n" "${_to}\n" _duk_config "${_duk_config}")
endforeach()
string(APPEND _duk_config "
/* GhostSpace sandbox hooks (runtime/src/script_ecmascript.cpp). */
int gs_duk_exec_timeout_check(void *udata);
int gs_duk_native_stack_check(void);
")
file(WRITE ${_duk_out}/duk_config.h.tmp "${_duk_config}")
configure_file(${_duk_out}/duk_config.h.tmp ${_duk_out}/duk_config.h COPYONLY)
configure_file(${GS_DUKTAPE_SOURCE_DIR}/duktape.h ${_duk_out}/duktape.h COPYONLY)

file(READ ${GS_DUKTAPE_SOURCE_DIR}/duktape.c _duk_source)
string(FIND "${_duk_source}" "#define DUK_RE_EXECUTE_STEPS_LIMIT 1000000000L" _at)
if(_at EQUAL -1)
  message(FATAL_ERROR "Duktape source: DUK_RE_EXECUTE_STEPS_LIMIT not found")
endif()
string(REPLACE "#define DUK_RE_EXECUTE_STEPS_LIMIT 1000000000L"
               "#define DUK_RE_EXECUTE_STEPS_LIMIT 10000000L" _duk_source "${_duk_source}")
# The compiler's recursion (nested expressions and statements) checks the native stack too,
# not only its depth limit (2500): a build with larger frames (clang's sanitizers with
# libFuzzer's coverage: 100,000 nested parentheses overflowed 8 MiB) ends with a RangeError.
set(_duk_from "DUK_LOCAL void duk__comp_recursion_increase(duk_compiler_ctx *comp_ctx) {\n\tDUK_ASSERT(comp_ctx != NULL);\n")
string(FIND "${_duk_source}" "${_duk_from}" _at)
if(_at EQUAL -1)
  message(FATAL_ERROR "Duktape source: duk__comp_recursion_increase not found")
endif()
string(REPLACE "${_duk_from}" "${_duk_from}\tduk_native_stack_check(comp_ctx->thr);\n"
               _duk_source "${_duk_source}")
file(WRITE ${_duk_out}/duktape.cpp.tmp "${_duk_source}")
configure_file(${_duk_out}/duktape.cpp.tmp ${_duk_out}/duktape.cpp COPYONLY)
unset(_duk_source)
unset(_duk_config)

add_library(gs_duktape STATIC ${_duk_out}/duktape.cpp)
target_include_directories(gs_duktape SYSTEM PUBLIC ${_duk_out})
target_compile_options(gs_duktape PRIVATE -w)
set_target_properties(gs_duktape PROPERTIES CXX_STANDARD 11 POSITION_INDEPENDENT_CODE ON)
target_link_libraries(gs_duktape PRIVATE m)
