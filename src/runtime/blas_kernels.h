// The dense kernels under CHOLMOD's supernodal factorizations.
//
// Debian 12's OpenBLAS (0.3.21) picks its kernels from the processor's model number. On a
// model it does not know (e.g. a Xeon with AVX-512 FP16) it falls back to its generic Prescott
// (SSE3) kernels, which run the dense blocks of our factorizations at about half speed
// (docs/performance.md, section 1). OPENBLAS_CORETYPE, read when OpenBLAS loads, overrides the
// choice. These functions find that case and set it for the programs of the project.
#pragma once

#include <string>

namespace strictmin::runtime {

// The kernel set the loaded OpenBLAS runs ("Prescott", "SkylakeX", ...); empty when the
// BLAS is not OpenBLAS.
std::string openblas_core();

// The kernel set to ask OpenBLAS for: "SkylakeX" when this processor has AVX-512 (F, CD, BW,
// DQ, VL), "Haswell" when it has AVX2 and FMA; nullptr when OpenBLAS did not fall back to
// Prescott, when the processor has neither, or when OPENBLAS_CORETYPE is already set (even
// to an empty string: the user's choice stands).
const char* better_openblas_core();

// When better_openblas_core() names a kernel set: sets OPENBLAS_CORETYPE to it and replaces
// the process by a fresh run of the same program with the same arguments (/proc/self/exe),
// so that OpenBLAS loads with it. Returns only when it did not re-execute (also under
// valgrind, which would not follow the new run). Call it first in
// main(), before any output or input; argv as main() received it.
void rerun_with_better_blas_kernels(char** argv);

}  // namespace strictmin::runtime
