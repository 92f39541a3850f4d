// Linked into every benchmark program: before main(), and after OpenBLAS has loaded, a
// program whose OpenBLAS fell back to its generic kernels on this processor runs again with
// the right ones (src/runtime/blas_kernels.h), as the strictmin command does. The benchmarks
// then time what a user of the command gets. glibc passes main's arguments to constructors.
#include "runtime/blas_kernels.h"

__attribute__((constructor)) static void blas_kernels_at_start(int, char** argv, char**) {
  strictmin::runtime::rerun_with_better_blas_kernels(argv);
}
