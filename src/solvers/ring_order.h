#pragma once
// The strict order (paper Section 4) restricted to one 1-ring: used by the relaxation to
// decide whether a vertex move is an improvement worth making.
#include <algorithm>

namespace strictmin::relax_detail {

// Whether new values `after` improve on `before` (n elements with areas w) in the
// area-weighted strict order, values closer than tau counting as equal: walking down the
// levels z of both vectors from the top, the first z where the areas of {D >= z - tau}
// differ decides, and the smaller area wins. Equal everywhere is no improvement.
// `order` is scratch for 2n indices. Values are distortions (not squared).
inline bool ring_improves(const double* before, const double* after, const double* w, int n, double tau,
                          int* order) {
  // The first level, without sorting: it settles most calls.
  double z0 = 0, total = 0;
  for (int i = 0; i < n; ++i) {
    z0 = std::max(z0, std::max(before[i], after[i]));
    total += w[i];
  }
  const double area_eps = 1e-12 * total;
  double first_b = 0, first_a = 0;
  for (int i = 0; i < n; ++i) {
    if (before[i] >= z0 - tau) first_b += w[i];
    if (after[i] >= z0 - tau) first_a += w[i];
  }
  if (first_a < first_b - area_eps) return true;
  if (first_a > first_b + area_eps) return false;
  int* ob = order;
  int* oa = order + n;
  for (int i = 0; i < n; ++i) ob[i] = oa[i] = i;
  std::sort(ob, ob + n, [&](int i, int j) { return before[i] > before[j]; });
  std::sort(oa, oa + n, [&](int i, int j) { return after[i] > after[j]; });
  int ib = 0, ia = 0;          // elements counted so far in each vector
  double area_b = 0, area_a = 0;
  while (ib < n || ia < n) {
    // Next level: the larger of the two vectors' next values.
    const double z = std::max(ib < n ? before[ob[ib]] : -1.0, ia < n ? after[oa[ia]] : -1.0);
    while (ib < n && before[ob[ib]] >= z - tau) area_b += w[ob[ib++]];
    while (ia < n && after[oa[ia]] >= z - tau) area_a += w[oa[ia++]];
    if (area_a < area_b - area_eps) return true;
    if (area_a > area_b + area_eps) return false;
  }
  return false;
}

}  // namespace strictmin::relax_detail
