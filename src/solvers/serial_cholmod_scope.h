#pragma once
// The threads of CHOLMOD and of the BLAS under it, held to one while our own solves run
// (private: the supernodal factorization, the interior-point method's KKT solves). Defined
// in sparse_cholesky.cpp.

namespace strictmin {

// While alive, keeps CHOLMOD's own OpenMP loops and OpenBLAS on one thread each.
// - Debian's CHOLMOD runs a few loops of its supernodal factorisation with a compiled-in 4
//   OpenMP threads (CHOLMOD_OMP_NUM_THREADS, no run-time control): on 2 cores that
//   oversubscribes, and on our normal equations (supernodes mostly 2 columns wide) the
//   fork/join and spinning cost more than the loops (100k square: 0.23 -> 0.15-0.20 s per
//   factorisation). OpenMP's max-active-levels is set to 0 for the calling thread.
// - OpenBLAS's own threads (by default one per core) fight with ours (TBB, the two halves
//   of SplitCholesky) for the same cores: 50k square, default threads against one, under
//   load: 30-36 s against 17-22 s wall, 3-4 s against 0.9 s system time. OpenBLAS is set to
//   one thread for the process while any scope is alive (a count: nested and concurrent
//   scopes are fine) and restored when the last one ends.
// Both are found at run time (dlsym) and are no-ops when absent.
class SerialCholmodScope {
 public:
  SerialCholmodScope();
  ~SerialCholmodScope();
  SerialCholmodScope(const SerialCholmodScope&) = delete;
  SerialCholmodScope& operator=(const SerialCholmodScope&) = delete;

 private:
  int saved_ = -1;
};

}  // namespace strictmin
