#pragma once
// Marks for a file of vectorised loops (compiled with -fno-trapping-math, see core/fast_exp.h):
// TR_VECTOR_CLONES builds a function twice on x86-64 GNU/Linux, for AVX2 and for the baseline,
// chosen when the program loads (GCC and Clang target_clones; not under AddressSanitizer, whose
// start-up the loader's choice would precede). ISO C++ mode contracts no multiply-add, so both
// compute the same numbers. What such a function calls must be inlined into it
// (TR_FORCE_INLINE; TR_FORCE_INLINE_LAMBDA after a lambda's parameters), or it runs the
// baseline's code.

#if defined(__SANITIZE_ADDRESS__)  // GCC
#define TR_ADDRESS_SANITIZER 1
#elif defined(__has_feature)  // Clang
#if __has_feature(address_sanitizer)
#define TR_ADDRESS_SANITIZER 1
#endif
#endif

#if defined(__x86_64__) && defined(__linux__) && !defined(TR_ADDRESS_SANITIZER)
#define TR_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define TR_VECTOR_CLONES
#endif
#define TR_FORCE_INLINE [[gnu::always_inline]] inline
#define TR_FORCE_INLINE_LAMBDA __attribute__((always_inline))
