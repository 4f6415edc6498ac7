#include "reproduce/trajectory_checks.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace campo {
namespace {

// A drone flying east over a hill z_ground = 2 sin(pi x / 20) for x in [0, 20],
// 1.5 m above the ground: the altitude changes by 2 m, the height above
// ground not at all; the 2 m at either end are left out.
TEST(TerrainFollowing, FollowingFlightHasAFlatBandAndTheHillsChange) {
  std::vector<double> x, y, z, h;
  for (int i = 0; i <= 200; ++i) {
    const double xi = 0.1 * i;
    const double ground = 2.0 * std::sin(M_PI * xi / 20.0);
    x.push_back(xi);
    y.push_back(0.0);
    z.push_back(ground + 1.5);
    h.push_back(1.5);
  }
  const TerrainFollowing t = measure_terrain_following(x, y, z, h, 2.0);
  EXPECT_EQ(t.samples, 161);  // x in [2, 18]
  EXPECT_NEAR(t.altitude_max_m, 3.5, 1e-12);
  EXPECT_NEAR(t.altitude_min_m, 1.5 + 2.0 * std::sin(M_PI * 2.0 / 20.0), 1e-9);
  EXPECT_NEAR(t.band_m(), 0.0, 1e-12);
}

TEST(TerrainFollowing, LevelFlightHasTheHillAsItsBand) {
  std::vector<double> x, y, z, h;
  for (int i = 0; i <= 100; ++i) {
    x.push_back(0.0);
    y.push_back(0.2 * i);  // northward, 20 m
    const double ground = 0.1 * (i <= 50 ? i : 100 - i);  // a 5 m ridge
    z.push_back(6.0);
    h.push_back(6.0 - ground);
  }
  const TerrainFollowing t = measure_terrain_following(x, y, z, h, 0.0);
  EXPECT_EQ(t.samples, 101);
  EXPECT_DOUBLE_EQ(t.altitude_change_m(), 0.0);
  EXPECT_NEAR(t.band_m(), 5.0, 1e-12);
  EXPECT_NEAR(t.height_above_ground_min_m, 1.0, 1e-12);
}

TEST(TerrainFollowing, NothingFarFromTheEndsMeasuresNothing) {
  const std::vector<double> x{0.0, 0.5, 1.0}, y{0.0, 0.0, 0.0}, z{1.0, 2.0, 1.0}, h{1.0, 1.0, 1.0};
  const TerrainFollowing t = measure_terrain_following(x, y, z, h, 2.0);
  EXPECT_EQ(t.samples, 0);
  EXPECT_EQ(t.altitude_change_m(), 0.0);
}

TEST(DistanceToPolyline, NearestSegmentInteriorOrVertex) {
  const std::vector<Eigen::Vector2d> route{{0.0, 0.0}, {10.0, 0.0}, {10.0, 10.0}};
  EXPECT_DOUBLE_EQ(distance_to_polyline({5.0, 3.0}, route), 3.0);    // beside the first leg
  EXPECT_DOUBLE_EQ(distance_to_polyline({12.0, 5.0}, route), 2.0);   // beside the second
  EXPECT_DOUBLE_EQ(distance_to_polyline({13.0, -4.0}, route), 5.0);  // beyond the corner: 3-4-5 to the vertex
  EXPECT_DOUBLE_EQ(distance_to_polyline({-1.0, 0.0}, {{2.0, 0.0}}), 3.0);
  EXPECT_TRUE(std::isinf(distance_to_polyline({0.0, 0.0}, {})));
}

}  // namespace
}  // namespace campo
