// The route measures of the run record (metrics/route_metrics.hpp), against
// hand-computed values.
#include "metrics/route_metrics.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace campo {
namespace {

using V = Eigen::Vector3d;

TEST(RouteMetrics, PolylineLengthSumsTheSegments) {
  EXPECT_DOUBLE_EQ(polyline_length_m(std::vector<V>{}), 0.0);
  EXPECT_DOUBLE_EQ(polyline_length_m(std::vector<V>{V(1, 2, 3)}), 0.0);
  // 3-4-5 in the plane, then 12 straight up.
  EXPECT_DOUBLE_EQ(polyline_length_m(std::vector<V>{V(0, 0, 0), V(3, 4, 0), V(3, 4, 12)}), 17.0);
}

TEST(RouteMetrics, LateralOffsetIsTheHorizontalDistanceFromTheLegLine) {
  // A leg due south along x = 10: the offset is |x - 10|, whatever the height or how far along.
  EXPECT_DOUBLE_EQ(lateral_offset_m(V(7, 50, 30), V(10, 40, 0), V(10, 0, 0)), 3.0);
  EXPECT_DOUBLE_EQ(lateral_offset_m(V(10, -20, 99), V(10, 40, 0), V(10, 0, 0)), 0.0);
  // A diagonal leg: (0, 2) is sqrt2 from the line y = x.
  EXPECT_NEAR(lateral_offset_m(V(0, 2, 0), V(0, 0, 0), V(5, 5, 0)), std::sqrt(2.0), 1e-12);
  // A vertical leg: the distance to its foot.
  EXPECT_DOUBLE_EQ(lateral_offset_m(V(3, 4, 0), V(0, 0, 0), V(0, 0, 10)), 5.0);
}

// A leg south along x = 0 at 28 m that meets a wall: flying 6 m west along
// it before climbing to 40 m counts 6 m; climbing at once counts what the
// vehicle drifted before topping the climb.
TEST(RouteMetrics, LateralBeforeClimbCountsTheSidewaysFlightBeforeTheTop) {
  const V from(0, 40, 28), to(0, 0, 28);
  const std::vector<V> along_wall{from, V(0, 30, 28), V(-3, 30, 28), V(-6, 30, 28), V(-6, 30, 35), V(-6, 30, 40),
                                  V(-6, 25, 40), V(-2, 20, 29), V(0, 0, 28)};
  EXPECT_DOUBLE_EQ(*lateral_before_climb_m(along_wall, from, to), 6.0);
  const std::vector<V> straight_over{from, V(0.5, 30, 28), V(1.0, 29, 34), V(1.2, 28, 39), V(4, 20, 40),
                                     V(0, 0, 28)};
  // Topped at 39 m (within 2 m of the peak of 40 m): the 1.2 m at the top is not counted.
  EXPECT_DOUBLE_EQ(*lateral_before_climb_m(straight_over, from, to), 1.0);
  // No climb above max(from, to) + 2 m: no value, however far it went sideways.
  const std::vector<V> flat{from, V(-20, 20, 29.9), V(0, 0, 28)};
  EXPECT_FALSE(lateral_before_climb_m(flat, from, to).has_value());
  EXPECT_FALSE(lateral_before_climb_m(std::vector<V>{}, from, to).has_value());
  // The threshold is a parameter: 1 m makes the 29.9 m point a climb topped at once.
  EXPECT_DOUBLE_EQ(*lateral_before_climb_m(flat, from, to, 1.0), 0.0);
}

TEST(RouteMetrics, FirstInsideFindsTheFirstPointInTheAreaBelowTheCeiling) {
  const Eigen::AlignedBox2d slot(Eigen::Vector2d(73.5, 72.0), Eigen::Vector2d(76.5, 75.0));
  const std::vector<V> points{V(69, 80, 70), V(75, 73, 70), V(75, 73.5, 55), V(76.5, 75, 30), V(80, 60, 30)};
  const std::vector<double> agl{42, 42, 28, 28, 28};
  EXPECT_EQ(*first_inside(points, agl, slot, std::nullopt), 1u);
  // Below 35 m above ground: the 42 m passes over the slot do not count; the edge is inside.
  EXPECT_EQ(*first_inside(points, agl, slot, 35.0), 2u);
  EXPECT_FALSE(first_inside(points, agl, slot, 20.0).has_value());
  // A missing height (NaN) never counts under a ceiling.
  const std::vector<double> unknown{NAN, NAN, NAN, NAN, NAN};
  EXPECT_FALSE(first_inside(points, unknown, slot, 35.0).has_value());
  EXPECT_FALSE(first_inside(std::vector<V>{V(0, 0, 0)}, agl, slot, std::nullopt).has_value());
}

}  // namespace
}  // namespace campo
