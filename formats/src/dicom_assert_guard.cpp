// GDCM's assertions, made errors (formats/src/dicom_internal.hpp, runGdcmGuarded). Debian
// builds GDCM with assertions on, and some of them fire on malformed files (CI's fuzz_dicom
// found two: gdcm::Attribute<0028,0100>::SetFromDataSet and ImageHelper::GetSpacingValue on
// a mutated CT_small): left alone, a hostile file would abort the program. This file
// defines __assert_fail, which the executable exports to the shared libraries it links (it
// interposes glibc's, as a malloc linked into an executable does): inside runGdcmGuarded it
// jumps back out of GDCM, elsewhere it does what glibc's does (print, abort).
#include "dicom_internal.hpp"

#include "base/sanitizers.hpp"

#include <csetjmp>
#include <cstdio>
#include <cstdlib>

// LeakSanitizer (the sanitizer and fuzz builds): what GDCM allocated in the frames a jump
// skipped is never freed; it is not reported as a leak.
#ifdef GS_LEAK_SANITIZER
#include <sanitizer/lsan_interface.h>
#endif

namespace gs::formats::detail {
namespace {

thread_local sigjmp_buf* tGdcmAssertJump = nullptr;

}  // namespace

bool runGdcmGuarded(void (*step)(void*), void* argument) {
  sigjmp_buf jump;
  sigjmp_buf* const outer = tGdcmAssertJump;
#ifdef GS_LEAK_SANITIZER
  __lsan_disable();  // allocations until __lsan_enable are never reported
#endif
  if (sigsetjmp(jump, 0) != 0) {
    tGdcmAssertJump = outer;
#ifdef GS_LEAK_SANITIZER
    __lsan_enable();
#endif
    return false;
  }
  tGdcmAssertJump = &jump;
  step(argument);
  tGdcmAssertJump = outer;
#ifdef GS_LEAK_SANITIZER
  __lsan_enable();
#endif
  return true;
}

void leakGdcmObject([[maybe_unused]] const void* object) {
#ifdef GS_LEAK_SANITIZER
  __lsan_ignore_object(object);
#endif
}

}  // namespace gs::formats::detail

// (The GNU attribute, as glibc's <assert.h> declares it: a unity batch may have seen that
// declaration first.)
extern "C" __attribute__((__noreturn__)) void __assert_fail(const char* assertion, const char* file,
                                                            unsigned int line,
                                                            const char* function) noexcept {
  if (sigjmp_buf* const jump = gs::formats::detail::tGdcmAssertJump) siglongjmp(*jump, 1);
  std::fprintf(stderr, "%s:%u: %s: Assertion `%s' failed.\n", file, line,
               function != nullptr ? function : "?", assertion);
  std::abort();
}
