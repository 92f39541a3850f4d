#pragma once
// Compile-time sizes for the per-element loops of the interior-point method.
//
// Every element cone of a ConeProgram has the same dimension t + 1 (5 for triangles mapped
// to the plane, 7 for triangles in space, 10 for tets), and every element the same n and m.
// The cone algebra (soc.h) and the element operators loop over these sizes; with the sizes
// known at compile time the compiler unrolls and vectorises those loops, which halves the
// cost of the passes over the cones that every Newton solve makes. The dispatchers below
// call f with std::integral_constant sizes for the common cases and with plain ints
// otherwise, so that one generic lambda body (`const int n = n_c;`) serves both.
#include <type_traits>

namespace strictmin::socp {

template <int V>
using Size = std::integral_constant<int, V>;

// f(n, m) for the image and domain dimension of the elements.
template <class F>
decltype(auto) with_element_sizes(int n, int m, F&& f) {
  if (n == 2 && m == 2) return f(Size<2>{}, Size<2>{});  // planar maps, parametrizations
  if (n == 3 && m == 3) return f(Size<3>{}, Size<3>{});  // tets
  if (n == 3 && m == 2) return f(Size<3>{}, Size<2>{});  // surfaces in space
  return f(n, m);
}

// f(d) for the dimension of the element cones.
template <class F>
decltype(auto) with_cone_dim(int d, F&& f) {
  if (d == 5) return f(Size<5>{});
  if (d == 10) return f(Size<10>{});
  if (d == 7) return f(Size<7>{});
  return f(d);
}

}  // namespace strictmin::socp
