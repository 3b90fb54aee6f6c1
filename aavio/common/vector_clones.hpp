#pragma once
/// AAVIO_AVX2_CLONES marks a function whose loops vectorise: on x86-64 with GCC it gets an AVX2
/// clone chosen at load time (ifunc) beside the baseline one. Only for element-wise loops and
/// sums in a fixed order: without FMA contraction (-std=c++20 keeps -ffp-contract=off) and without
/// -ffast-math the clone computes the same values bit for bit, so results do not depend on the CPU.

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define AAVIO_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define AAVIO_AVX2_CLONES
#endif
