// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Whether this test is built with the sanitizers (tools/test --sanitize: -fsanitize=address,
// undefined), where a run of the program is 10 to 40 times slower than in the release build.
// CI runs the fast suite twice, plain and under the sanitizers, within 90 minutes on 2 cores:
// a test that repeats code paths another test of the suite also runs under the sanitizers
// (the same resume on another scene, the same signal with another thread count) skips there,
// naming the tests that cover it:
//   if (kUnderSanitizers) GTEST_SKIP() << kSkippedUnderSanitizers << "covered by ...";
namespace femdem::test {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kUnderSanitizers = true;
#else
inline constexpr bool kUnderSanitizers = false;
#endif
inline constexpr const char* kSkippedUnderSanitizers = "not run under the sanitizers: ";

}  // namespace femdem::test
