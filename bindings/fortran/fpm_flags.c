/* SPDX-License-Identifier: Apache-2.0 */
/*
 * fpm_flags.c — compiled by fpm only (fpm.toml: the library's source-dir is
 * bindings/fortran, where libisect-src links to libisect/src; the Makefile,
 * meson and CMake never compile this file).
 *
 * fpm reads no C flags from a dependency's manifest: the project that
 * depends on libisect passes them, for every C file it compiles,
 *
 *     fpm build --c-flag "-std=c99 -ffp-contract=off"     (or FPM_CFLAGS)
 *
 * libisect's exact predicates and error-free transformations are written for
 * plain IEEE operations; a compiler-fused a*b+c changes their rounding.
 * GCC fuses by default in its GNU modes (-ffp-contract=fast), and the AVX2
 * lanes are compiled for FMA, so a build without these flags would give
 * wrong answers, not an error. This unit makes it an error for GCC: -std=c99
 * (an ISO mode, __STRICT_ANSI__) turns its contraction off. Other compilers
 * cannot be checked here; pass -ffp-contract=off (clang) or the equivalent.
 */
#if defined(__GNUC__) && !defined(__clang__) && !defined(__STRICT_ANSI__)
#error "libisect under fpm needs: fpm build --c-flag \"-std=c99 -ffp-contract=off\" (see fpm.toml)"
#endif

/* ISO C wants a declaration in every translation unit. */
typedef int isect_fpm_flags_checked;
