// Function multi-versioning for the linalg kernels whose loops vectorize (column updates, row
// rotations, the forward substitution): on x86-64 a kernel marked KERNEL_FOR_AVX2_TOO is compiled
// twice, for AVX2 and for the baseline, and the CPU picks one when the library loads (an ifunc).
// Neither copy contracts products and sums into fused multiply-adds (FMA is not part of the
// target), and each entry's operations are the same in the same order, so both copies give the
// same bits: answers do not depend on the machine. The helpers a marked kernel calls must be
// always_inline, else the AVX2 copy calls their baseline code (docs/benchmarks.md, "Parkour's
// factorization against a sparse Cholesky").
#pragma once

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define KERNEL_FOR_AVX2_TOO __attribute__((target_clones("avx2", "default")))
#else
#define KERNEL_FOR_AVX2_TOO
#endif

// GCC at -O2 vectorizes only loops that need no remainder loop after the vector one (its "very
// cheap" cost model); a kernel whose row loop does need one asks for the dynamic model. Each
// entry's operations stay the same, so the bits do too.
#if defined(__GNUC__) && !defined(__clang__)
#define KERNEL_VECTORIZED_WITH_REMAINDER __attribute__((optimize("vect-cost-model=dynamic")))
#else
#define KERNEL_VECTORIZED_WITH_REMAINDER
#endif
