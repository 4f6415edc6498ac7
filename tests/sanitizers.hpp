#pragma once
// CAMPO_TEST_UNDER_ASAN is defined when this test program is built with
// AddressSanitizer: GCC says so with __SANITIZE_ADDRESS__, clang (the
// sanitized build of .ci/run) with __has_feature(address_sanitizer).
#if defined(__SANITIZE_ADDRESS__)
#define CAMPO_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CAMPO_TEST_UNDER_ASAN 1
#endif
#endif
