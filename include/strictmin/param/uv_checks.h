#pragma once
// Checks of a parametrization X (#V by 2) of a triangle mesh: flipped triangles, whether the
// boundary polygon overlaps itself, and the normalization every initial map gets.
#include <Eigen/Core>
#include <vector>

namespace strictmin {

// Twice the signed area of triangle f in the map.
double signed_uv_area2(const Eigen::MatrixXi& F, const Eigen::MatrixXd& X, int f);

// Triangles whose signed area is not of the majority's sign (zero area counts as flipped).
int count_flips(const Eigen::MatrixXi& F, const Eigen::MatrixXd& X);

// True when two non-adjacent edges of the closed polygon X[loop] touch or cross (a uniform
// grid over the polygon's bounding box: about linear time for evenly sized edges).
bool polygon_self_intersects(const Eigen::MatrixXd& X, const std::vector<int>& loop);

// Makes the majority of triangles counter-clockwise (mirrors u if needed) and scales about
// the centroid so that the total unsigned map area equals `surface_area`: ARAP compares J
// with rotations, so it is scale sensitive and the start must have the surface's size.
void orient_and_scale(const Eigen::MatrixXi& F, Eigen::MatrixXd& X, double surface_area);

}  // namespace strictmin
