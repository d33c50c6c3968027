// Which sanitizers this translation unit is compiled with, for the code that must allow for
// them (larger stack frames, allocations a longjmp skips). GCC says so with
// __SANITIZE_ADDRESS__, clang with __has_feature.
#pragma once

// GS_ADDRESS_SANITIZER: defined (as 1) under AddressSanitizer, GCC's or clang's.
#if defined(__SANITIZE_ADDRESS__)
#define GS_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GS_ADDRESS_SANITIZER 1
#endif
#endif

// GS_LEAK_SANITIZER: defined (as 1) where LeakSanitizer runs: with AddressSanitizer, or
// alone (clang's -fsanitize=leak).
#if defined(GS_ADDRESS_SANITIZER)
#define GS_LEAK_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(leak_sanitizer)
#define GS_LEAK_SANITIZER 1
#endif
#endif
