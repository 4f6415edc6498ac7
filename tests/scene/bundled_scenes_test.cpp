// The bundled scenes match the experiments of SPEC §8.
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "campo/scene_loader.hpp"
#include "scene/generators.hpp"

namespace campo {
namespace {

Scene bundled(const std::string& name) {
  return load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/" + name + ".json");
}

struct Block {
  int row_first, row_last, col_first, col_last;
  double height_m;
};

// The generated box covering a block of 1.5 m cells (row 1 south, column 1 west).
const Shape* find_block(const Scene& scene, const Block& b) {
  const double s = 1.5;
  const Eigen::Vector2d lo((b.col_first - 1) * s, (b.row_first - 1) * s), hi(b.col_last * s, b.row_last * s);
  for (const Shape& shape : scene.shapes) {
    if (shape.type != ShapeType::cuboid) continue;
    const Eigen::Vector2d c = shape.pose.translation().head<2>(), half = 0.5 * shape.size_m.head<2>();
    if ((c - half - lo).norm() < 1e-9 && (c + half - hi).norm() < 1e-9) return &shape;
  }
  return nullptr;
}

// The 001 scenes: every block of the SPEC table is there, with its top
// height_m above the highest ground below it (terrain z = sin(x/5)).
void expect_blocks(const Scene& scene, const std::vector<Block>& blocks) {
  std::size_t boxes = 0;
  for (const Shape& shape : scene.shapes) boxes += shape.type == ShapeType::cuboid;
  EXPECT_EQ(boxes, blocks.size());
  for (const Block& b : blocks) {
    const Shape* shape = find_block(scene, b);
    ASSERT_NE(shape, nullptr) << "rows " << b.row_first << "-" << b.row_last << " cols " << b.col_first;
    const double x0 = (b.col_first - 1) * 1.5, x1 = b.col_last * 1.5;
    double ground_max = -1.0;
    for (double x = x0; x <= x1 + 1e-9; x += 0.75) ground_max = std::max(ground_max, std::sin(x / 5));
    const double top = shape->pose.translation().z() + 0.5 * shape->size_m.z();
    EXPECT_NEAR(top, ground_max + b.height_m, 1e-6);
  }
}

// Mission waypoints in (row, col, altitude above ground): within half a
// cell of the cell's centre in x and y (the scenes give 001's geodetic
// waypoints, which land up to 0.69 m off the centres), at the altitude above
// the ground under the waypoint.
void expect_route(const Scene& scene, const std::vector<std::array<double, 3>>& route) {
  const auto& mission = scene.vehicles.at(0).mission;
  ASSERT_EQ(mission.size(), route.size());
  for (std::size_t i = 0; i < route.size(); ++i) {
    const double x = (route[i][1] - 0.5) * 1.5, y = (route[i][0] - 0.5) * 1.5;
    const Eigen::Vector3d& p = mission[i].position_m;
    EXPECT_LT(std::abs(p.x() - x), 0.75) << i;
    EXPECT_LT(std::abs(p.y() - y), 0.75) << i;
    // The terrain is sampled every 0.75 m: between vertices linear interpolation
    // is within 0.75^2 / 8 / 25 = 2.8 mm of sin(x/5).
    EXPECT_NEAR(p.z(), std::sin(p.x() / 5) + route[i][2], 3e-3) << i;
  }
}

// A waypoint of 001's route tables (latitude and longitude in degrees,
// altitude above ground in metres) and the cell of the SPEC's route it stands for.
struct TableWaypoint {
  double latitude_deg, longitude_deg, agl_m;
  int row, col;
};

// 001 §4.2.3 converts the tables' latitude/longitude to graph nodes from its
// north-west reference point (40.82233, 14.70328) on a sphere of
// R = 6371000 m without cos(latitude): coox = round(deg2rad(lon - lon_ref) R
// / 1.5), cooy = round(deg2rad(lat_ref - lat) R / 1.5). The tables' cells
// count rows northward from the south edge (SPEC §8): row = 100 - cooy,
// column = coox. Every waypoint of the table, through the scene's
// geo_reference, lands in the SPEC's cell within half a cell of its centre,
// and the scene's mission holds exactly these waypoints.
void expect_geodetic_table(const Scene& scene, const std::vector<TableWaypoint>& table) {
  const GeoReference& ref = scene.world.geo_reference;
  EXPECT_DOUBLE_EQ(ref.latitude_deg, 40.82233);
  EXPECT_DOUBLE_EQ(ref.longitude_deg, 14.70328);
  EXPECT_EQ(ref.projection, GeoProjection::sphere_no_coslat);
  const auto& mission = scene.vehicles.at(0).mission;
  ASSERT_EQ(mission.size(), table.size());
  const double r = 6371000.0, deg = std::numbers::pi / 180.0;
  for (std::size_t i = 0; i < table.size(); ++i) {
    const TableWaypoint& w = table[i];
    SCOPED_TRACE(i);
    // The seed's own node formulas.
    EXPECT_EQ(std::lround((w.longitude_deg - 14.70328) * deg * r / 1.5), w.col);
    EXPECT_EQ(100 - std::lround((40.82233 - w.latitude_deg) * deg * r / 1.5), w.row);
    // The scene's conversion: the same cell, near its centre.
    const Eigen::Vector3d p = geodetic_to_local(ref, w.latitude_deg, w.longitude_deg, 0.0);
    EXPECT_EQ(static_cast<int>(std::floor(p.y() / 1.5)) + 1, w.row);
    EXPECT_EQ(static_cast<int>(std::floor(p.x() / 1.5)) + 1, w.col);
    EXPECT_LE(std::abs(p.x() - (w.col - 0.5) * 1.5), 0.75);
    EXPECT_LE(std::abs(p.y() - (w.row - 0.5) * 1.5), 0.75);
    EXPECT_NEAR(mission[i].position_m.x(), p.x(), 1e-9);
    EXPECT_NEAR(mission[i].position_m.y(), p.y(), 1e-9);
    EXPECT_NEAR(mission[i].position_m.z(), std::sin(p.x() / 5) + w.agl_m, 3e-3);  // the sampled terrain (above)
  }
}

TEST(BundledScenes, ObstacleFieldMatchesTheSeedTable) {
  const Scene scene = bundled("obstacle_field");
  expect_blocks(scene, {{35, 35, 16, 18, 30}, {40, 45, 25, 30, 15}, {55, 56, 15, 18, 35}, {77, 80, 40, 41, 35},
                        {49, 50, 46, 49, 35}, {49, 50, 52, 55, 35}, {30, 31, 50, 51, 35}, {65, 100, 5, 30, 10}});
  expect_route(scene, {{1, 16, 42}, {76, 16, 42}, {76, 46, 42}, {24, 46, 42}, {24, 46, 28}, {24, 16, 28},
                       {76, 16, 28}, {76, 46, 28}, {24, 46, 28}});
  EXPECT_EQ(scene.vehicles[0].sensors.at(0).range.preset, "leddar_vu8");
  // Tabella 5.2.
  expect_geodetic_table(scene, {{40.8210, 14.7035, 42, 1, 16}, {40.8220, 14.7035, 42, 76, 16},
                                {40.8220, 14.7039, 42, 76, 46}, {40.8213, 14.7039, 42, 24, 46},
                                {40.8213, 14.7039, 28, 24, 46}, {40.8213, 14.7035, 28, 24, 16},
                                {40.8220, 14.7035, 28, 76, 16}, {40.8220, 14.7039, 28, 76, 46},
                                {40.8213, 14.7039, 28, 24, 46}});
  // The slot of 001 §5.1 is a gate of the mission: columns 50-51 of rows 49-50, below the blocks' 35 m.
  const auto& gates = scene.vehicles[0].gates;
  ASSERT_EQ(gates.size(), 1u);
  EXPECT_EQ(gates[0].name, "slot");
  EXPECT_TRUE(gates[0].area_m.min().isApprox(Eigen::Vector2d(73.5, 72.0)));
  EXPECT_TRUE(gates[0].area_m.max().isApprox(Eigen::Vector2d(76.5, 75.0)));
  EXPECT_EQ(gates[0].max_agl_m, 35.0);
}

TEST(BundledScenes, ZigzagMatchesTheSeedTable) {
  const Scene scene = bundled("zigzag");
  expect_blocks(scene, {{24, 27, 16, 28, 35}, {39, 42, 6, 18, 35}, {54, 57, 16, 28, 35}, {69, 72, 6, 18, 35}});
  expect_route(scene, {{1, 16, 42}, {76, 16, 42}, {76, 16, 28}, {1, 16, 28}});
  // Tabella 5.4.
  expect_geodetic_table(scene, {{40.8210, 14.7035, 42, 1, 16}, {40.8220, 14.7035, 42, 76, 16},
                                {40.8220, 14.7035, 28, 76, 16}, {40.8210, 14.7035, 28, 1, 16}});
}

TEST(BundledScenes, WallMatchesTheSeedTable) {
  const Scene scene = bundled("wall");
  expect_blocks(scene, {{20, 22, 1, 100, 30}});  // Tabella 5.5: rows 20-22, columns 1-100, 30 m
  expect_route(scene, {{1, 16, 42}, {31, 16, 42}, {31, 16, 28}, {1, 16, 28}});
  // Tabella 5.6.
  expect_geodetic_table(scene, {{40.8210, 14.7035, 42, 1, 16}, {40.8214, 14.7035, 42, 31, 16},
                                {40.8214, 14.7035, 28, 31, 16}, {40.8210, 14.7035, 28, 1, 16}});
}

TEST(BundledScenes, TreesStartAndGoalAre23_27MetresApart) {
  const Scene scene = bundled("trees_rolling_terrain");
  const Eigen::Vector3d start = scene.vehicles.at(0).pose.translation();
  const Eigen::Vector3d goal = scene.vehicles[0].mission.back().position_m;
  EXPECT_NEAR((goal - start).head<2>().norm(), 23.27, 1e-9);
  // Both 1.6 m above the ground beneath them; a hill of over 1.5 m rises between (Fig. 5.5).
  EXPECT_NEAR(start.z() - *scene.ground_height(start.x(), start.y()), 1.6, 1e-9);
  EXPECT_NEAR(goal.z() - *scene.ground_height(goal.x(), goal.y()), 1.6, 1e-9);
  double highest = -INFINITY;
  for (double t = 0.0; t <= 1.0; t += 0.01) {
    const Eigen::Vector3d p = start + t * (goal - start);
    highest = std::max(highest, *scene.ground_height(p.x(), p.y()));
  }
  EXPECT_GT(highest - *scene.ground_height(start.x(), start.y()), 1.5);
  EXPECT_EQ(scene.vehicles[0].sensors.at(0).range.preset, "scanner3d");
  int trunks = 0;
  for (const Shape& s : scene.shapes) {
    if (s.type != ShapeType::cylinder) continue;
    ++trunks;
    // Trunks stand on the rolling terrain.
    const Eigen::Vector3d c = s.pose.translation();
    const double ground = *scene.ground_height(c.x(), c.y());
    EXPECT_LT(c.z() - 0.5 * s.height_m, ground);
    EXPECT_GT(c.z() + 0.5 * s.height_m, ground + 1.0);
  }
  EXPECT_EQ(trunks, 20);
}

TEST(BundledScenes, TwoBarriersBlockTheStraightLineButLeaveAGap) {
  const Scene scene = bundled("two_barriers");
  const Eigen::Vector3d start = scene.vehicles.at(0).pose.translation();
  const Eigen::Vector3d goal = scene.vehicles[0].mission.back().position_m;
  const auto blocked = [&](double y) {
    for (const Shape& s : scene.shapes) {
      if (s.type != ShapeType::cuboid) continue;
      const double c = s.pose.translation().y(), half = 0.5 * s.size_m.y();
      if (y > c - half && y < c + half) return true;
    }
    return false;
  };
  EXPECT_TRUE(blocked(start.y()));
  EXPECT_TRUE(blocked(goal.y()));
  // A gap at least 1.5 m wide exists between the barriers.
  int free_run = 0, best = 0;
  for (double y = -10.0; y <= 10.0; y += 0.01) {
    free_run = blocked(y) ? 0 : free_run + 1;
    if (y > -4.0 && y < 8.0) best = std::max(best, free_run);
  }
  EXPECT_GE(best * 0.01, 1.5);
}

TEST(BundledScenes, VineyardHasRowsFenceObstaclesAndAMovingPerson) {
  const Scene scene = bundled("vineyard");
  int canopies = 0, fences = 0, obstacles = 0;
  for (const Shape& s : scene.shapes) {
    canopies += s.alias.find("/canopy") != std::string::npos;
    fences += s.alias.find("/fence/") != std::string::npos;
    obstacles += s.alias.find("/obstacle") != std::string::npos;
  }
  EXPECT_EQ(canopies, 20);
  EXPECT_EQ(fences, 4);
  EXPECT_EQ(obstacles, 12);
  ASSERT_EQ(scene.movers.size(), 1u);
  // The person crosses the rover's first inter-row (x = 0) from left to right.
  const Mover& m = scene.movers[0];
  EXPECT_LT(m.path_m[0].x(), 0.0);
  EXPECT_GT(m.path_m[1].x(), 0.0);
  EXPECT_EQ(scene.vehicles.at(0).type, VehicleType::rover);
  EXPECT_EQ(scene.vehicles[0].sensors.at(0).range.preset, "planar180");
  for (const Waypoint& wp : scene.vehicles[0].mission) EXPECT_TRUE(wp.heading_deg.has_value());
}

}  // namespace
}  // namespace campo
