#pragma once
// The strict order on distortion vectors (paper Section 4). f is less distorting than g
// when, going down from the highest distortion level, the first level where they differ
// has a lower value in f, or the same value over a smaller area.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace strictmin {

// Elements whose values lie within `tolerance` of the level's top value, and their area.
struct DistortionLevel {
  double value = 0;  // the largest value of the level
  double area = 0;
  int count = 0;
};

// Levels in decreasing order. Values are grouped greedily from the top: a level holds the
// values in [top - tolerance, top].
std::vector<DistortionLevel> distortion_levels(const Eigen::VectorXd& distortion, const Eigen::VectorXd& weights,
                                               double tolerance);

enum class StrictOrder { Less, Equivalent, Greater };

struct StrictComparison {
  StrictOrder order = StrictOrder::Equivalent;  // of a relative to b
  int level = -1;            // index of the first level that differs (-1 if equivalent)
  double value_a = 0, value_b = 0;  // that level's values
  double area_a = 0, area_b = 0;    // and areas
  // Decided by the level's values (they differ by more than value_tolerance), not by the
  // areas at a common value: what a verdict should say.
  bool by_value = false;
};

// Compares a and b (same elements, same weights). Values closer than value_tolerance are
// equal; areas closer than area_tolerance * (total area) are equal. The comparison walks the
// area-above-level functions |H_z| = area of {D >= z} at the union of both vectors' level
// values, from the top.
StrictComparison compare_strict(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& weights,
                                double value_tolerance = 1e-6, double area_tolerance = 1e-9);

// "less distorting", "equivalent", "more distorting", with the level where they differ.
std::string describe(const StrictComparison& c, const std::string& name_a, const std::string& name_b);

}  // namespace strictmin
