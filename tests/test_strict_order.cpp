// The strict order of paper Section 4 on hand-made distortion vectors.
#include <gtest/gtest.h>

#include "strictmin/report/strict_order.h"

using namespace strictmin;

namespace {

Eigen::VectorXd vec(std::initializer_list<double> v) {
  Eigen::VectorXd out(v.size());
  int i = 0;
  for (double x : v) out(i++) = x;
  return out;
}

TEST(StrictOrder, LowerMaximumWins) {
  const Eigen::VectorXd w = Eigen::VectorXd::Ones(3);
  const auto c = compare_strict(vec({0.5, 0.1, 0.1}), vec({0.6, 0.0, 0.0}), w);
  EXPECT_EQ(c.order, StrictOrder::Less);
  EXPECT_EQ(c.level, 0);
  EXPECT_EQ(compare_strict(vec({0.6, 0.0, 0.0}), vec({0.5, 0.1, 0.1}), w).order, StrictOrder::Greater);
}

TEST(StrictOrder, SameMaximumSmallerAreaWins) {
  // Both reach 0.5; a on one element of area 1, b on two elements of area 1 + 2.
  const Eigen::VectorXd w = vec({1, 2, 3});
  const auto c = compare_strict(vec({0.5, 0.4, 0.4}), vec({0.5, 0.5, 0.1}), w);
  EXPECT_EQ(c.order, StrictOrder::Less);
  EXPECT_DOUBLE_EQ(c.area_a, 1.0);
  EXPECT_DOUBLE_EQ(c.area_b, 3.0);
}

TEST(StrictOrder, AreaWeightedNotCounted) {
  // a has the top value on two small elements (area 2), b on one large one (area 5):
  // a is less distorting although it has more elements at the top.
  const Eigen::VectorXd w = vec({1, 1, 5});
  EXPECT_EQ(compare_strict(vec({0.9, 0.9, 0.1}), vec({0.1, 0.1, 0.9}), w).order, StrictOrder::Less);
}

TEST(StrictOrder, SecondLevelDecides) {
  const Eigen::VectorXd w = Eigen::VectorXd::Ones(4);
  const auto c = compare_strict(vec({1.0, 0.7, 0.2, 0.2}), vec({0.2, 1.0, 0.8, 0.1}), w);
  EXPECT_EQ(c.order, StrictOrder::Less);
  EXPECT_EQ(c.level, 1);
  EXPECT_DOUBLE_EQ(c.value_a, 0.7);
  EXPECT_DOUBLE_EQ(c.value_b, 0.8);
}

TEST(StrictOrder, PermutationsAreEquivalentAndToleranceApplies) {
  const Eigen::VectorXd w = Eigen::VectorXd::Ones(4);
  EXPECT_EQ(compare_strict(vec({0.3, 0.2, 0.1, 0.0}), vec({0.0, 0.1, 0.2, 0.3}), w).order, StrictOrder::Equivalent);
  EXPECT_EQ(compare_strict(vec({0.3 + 1e-9, 0.2}), vec({0.3, 0.2 - 1e-9}), Eigen::VectorXd::Ones(2), 1e-6).order,
            StrictOrder::Equivalent);
  EXPECT_EQ(compare_strict(vec({0.3 + 1e-3, 0.2}), vec({0.3, 0.2}), Eigen::VectorXd::Ones(2), 1e-6).order,
            StrictOrder::Greater);
}

TEST(StrictOrder, Levels) {
  const auto levels = distortion_levels(vec({0.1, 0.5, 0.5, 0.3, 0.5 - 1e-9}), vec({1, 2, 3, 4, 5}), 1e-6);
  ASSERT_EQ(levels.size(), 3u);
  EXPECT_DOUBLE_EQ(levels[0].value, 0.5);
  EXPECT_DOUBLE_EQ(levels[0].area, 10.0);
  EXPECT_EQ(levels[0].count, 3);
  EXPECT_DOUBLE_EQ(levels[1].value, 0.3);
  EXPECT_DOUBLE_EQ(levels[2].area, 1.0);
}

// Infinite maxima (a flipped element under qc / iso) tie with each other: inf - inf is NaN,
// which made each of two identical vectors "less distorting" than the other.
TEST(StrictOrder, InfiniteValuesTie) {
  const Eigen::VectorXd w = Eigen::VectorXd::Ones(3);
  const Eigen::VectorXd a = vec({INFINITY, 0.5, 0.1});
  EXPECT_EQ(compare_strict(a, a, w).order, StrictOrder::Equivalent);
  EXPECT_EQ(compare_strict(a, vec({INFINITY, 0.4, 0.1}), w).order, StrictOrder::Greater);
  EXPECT_EQ(compare_strict(vec({INFINITY, INFINITY, 0.1}), a, w).order, StrictOrder::Greater);
  const StrictComparison c = compare_strict(vec({0.3, 0.1, 0.0}), a, w);
  EXPECT_EQ(c.order, StrictOrder::Less);
  EXPECT_TRUE(c.by_value);
}

// A verdict says what decided it: values 1.1e-6 apart at a value tolerance of 1e-6 differ
// (by_value), and are not described as "both reach" one maximum.
TEST(StrictOrder, DecidedByValueOrByArea) {
  const Eigen::VectorXd w = Eigen::VectorXd::Ones(2);
  const StrictComparison values = compare_strict(vec({1.0824, 0.1}), vec({1.0824011, 0.1}), w, 1e-6);
  EXPECT_EQ(values.order, StrictOrder::Less);
  EXPECT_TRUE(values.by_value);
  const StrictComparison areas = compare_strict(vec({1.0, 0.1}), vec({1.0, 1.0}), w, 1e-6);
  EXPECT_EQ(areas.order, StrictOrder::Less);
  EXPECT_FALSE(areas.by_value);
  EXPECT_NE(describe(areas, "a", "b").find("covers area"), std::string::npos);
}

TEST(StrictOrder, Describe) {
  const Eigen::VectorXd w = Eigen::VectorXd::Ones(2);
  const auto c = compare_strict(vec({0.4, 0.1}), vec({0.5, 0.0}), w);
  EXPECT_NE(describe(c, "strict", "L2").find("strict is less distorting than L2"), std::string::npos);
}

}  // namespace
