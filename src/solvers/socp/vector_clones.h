#pragma once
// STRICTMIN_VECTOR_CLONES before a function: on x86-64 with GCC it is compiled for AVX2 as
// well as the baseline, and the loader picks the variant the processor runs (the binary
// stays portable). For the memory-bound loops over a sparse factor (supernodal_solve.cpp,
// supernodal_factor.cpp). Off under AddressSanitizer and with other compilers.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
#define STRICTMIN_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define STRICTMIN_VECTOR_CLONES
#endif
