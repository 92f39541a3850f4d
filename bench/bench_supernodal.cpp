// The sparse factorisation and substitutions of the L-infinity solver's normal equations, in
// isolation: a planar n x n grid of vertices with a 2 x 2 block per adjacent pair (the
// pattern of the normal matrix of a planar map; n = 158 is one half of the 100k-triangle
// problem as SplitCholesky sees it), nested-dissection ordered by CHOLMOD (METIS), analysed
// once. Each benchmark repeats one operation on the same factor:
//   Factorize: the numeric factorisation (supernodal_factor.h);
//   Solve:     one right-hand side, forward and backward substitution;
//   Forward, Backward: one substitution each (one right-hand side);
//   Solve2:    two right-hand sides with one pass over the factor.
// Counters: dofs, nnz(L), and for the substitutions the factor bytes read per second.
#include <benchmark/benchmark.h>

#include <Eigen/SparseCore>
#include <random>
#include <vector>

#include "solvers/socp/supernodal_cholesky.h"

using strictmin::socp::SupernodalCholesky;

namespace {

// Upper triangle of a grid matrix with 2 x 2 blocks: vertex (i, j) couples to its right,
// upper and upper-right neighbours (a triangulated grid), diagonally dominant.
Eigen::SparseMatrix<double> grid_matrix(int n) {
  std::vector<Eigen::Triplet<double>> t;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto id = [n](int i, int j) { return i * n + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int v = id(i, j);
      for (int r = 0; r < 2; ++r)
        for (int c = r; c < 2; ++c) t.emplace_back(2 * v + r, 2 * v + c, r == c ? 40.0 : 1.0);
      const int nbr[3][2] = {{i, j + 1}, {i + 1, j}, {i + 1, j + 1}};
      for (const auto& q : nbr) {
        if (q[0] >= n || q[1] >= n) continue;
        const int w = id(q[0], q[1]);
        for (int r = 0; r < 2; ++r)
          for (int c = 0; c < 2; ++c) t.emplace_back(2 * v + r, 2 * w + c, u(rng));
      }
    }
  Eigen::SparseMatrix<double> a(2 * n * n, 2 * n * n);
  a.setFromTriplets(t.begin(), t.end());
  a.makeCompressed();
  return a;
}

struct Fixture {
  Eigen::SparseMatrix<double> a;
  SupernodalCholesky chol{SupernodalCholesky::Ordering::Cholmod};
  explicit Fixture(int n) : a(grid_matrix(n)) {
    if (!chol.analyze(a) || !chol.factorize(a.valuePtr())) throw std::runtime_error("grid matrix not factorised");
  }
};

void set_counters(benchmark::State& state, const Fixture& f, int passes) {
  state.counters["dofs"] = static_cast<double>(f.a.rows());
  state.counters["nnzL"] = f.chol.nonzeros();
  state.counters["supernodes"] = static_cast<double>(f.chol.factor().nsuper);
  if (passes > 0)
    state.counters["factor_bytes_per_s"] = benchmark::Counter(
        passes * 8.0 * f.chol.nonzeros(), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_Factorize(benchmark::State& state) {
  Fixture f(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(f.chol.factorize(f.a.valuePtr()));
  set_counters(state, f, 0);
}

void BM_Solve(benchmark::State& state) {
  Fixture f(static_cast<int>(state.range(0)));
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(f.a.rows());
  Eigen::VectorXd x(f.a.rows());
  for (auto _ : state) {
    f.chol.solve(b.data(), x.data());
    benchmark::DoNotOptimize(x.data());
  }
  set_counters(state, f, 2);
}

// One pass each way, to tell the two apart.
void substitution(benchmark::State& state, bool forward) {
  Fixture f(static_cast<int>(state.range(0)));
  Eigen::VectorXd y = Eigen::VectorXd::Ones(f.a.rows());
  for (auto _ : state) {
    forward ? f.chol.forward_in_place(y.data()) : f.chol.backward_in_place(y.data());
    y.setOnes();
  }
  set_counters(state, f, 1);
}
void BM_Forward(benchmark::State& state) { substitution(state, true); }
void BM_Backward(benchmark::State& state) { substitution(state, false); }

void BM_Solve2(benchmark::State& state) {
  Fixture f(static_cast<int>(state.range(0)));
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(f.a.rows());
  Eigen::VectorXd x0(f.a.rows()), x1(f.a.rows());
  for (auto _ : state) {
    f.chol.solve2(b.data(), b.data(), x0.data(), x1.data());
    benchmark::DoNotOptimize(x0.data());
  }
  set_counters(state, f, 2);
}

}  // namespace

BENCHMARK(BM_Factorize)->Arg(158)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Solve)->Arg(158)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Forward)->Arg(158)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Backward)->Arg(158)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Solve2)->Arg(158)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
