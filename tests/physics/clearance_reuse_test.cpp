// ClearanceQuery reuses the answer of the vehicle's last search of static
// obstacles and ground when its bodies have not moved (bit for bit) since:
// over random walks in the bundled scenes, queried as the closed loop queries
// (after each physics step below the minima so far, at each control tick with
// no obstacle cutoff), its answers equal bit for bit those of a query that
// searches every time, and those of a query that has never searched before.
#include "physics/clearance.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include "campo/scene_loader.hpp"
#include "tests/physics/placed_vehicle.hpp"

namespace campo {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

// Registers with `q` what World registers: the children of the static
// compounds, the movers and dynamic shapes, the ground.
void register_world(const Scene& scene, World& world, ClearanceQuery& q) {
  const btCollisionObjectArray& objects = world.bullet().getCollisionObjectArray();
  int next_static = 0;
  for (int i = 0; i < objects.size(); ++i) {
    const btCollisionObject* body = objects[i];
    const int tag = body->getUserIndex();
    if (is_vehicle_tag(tag)) continue;
    if (tag >= 0) {
      const Shape& shape = scene.shapes.at(static_cast<std::size_t>(tag));
      if (shape.type == ShapeType::plane || shape.type == ShapeType::heightfield) {
        q.add_ground(*body, shape.terrain.get());
      } else if (!shape.is_static) {
        q.add_moving_obstacle(*body, tag);
      }
    } else if (tag > -1000000) {  // a mover
      q.add_moving_obstacle(*body, tag);
    } else {  // a compound of static obstacles: ids need only differ from one another here
      const auto* compound = static_cast<const btCompoundShape*>(body->getCollisionShape());
      std::vector<int> ids;
      for (int c = 0; c < compound->getNumChildShapes(); ++c) {
        ids.push_back(next_static);
        q.add_static_obstacle(*static_cast<const btConvexShape*>(compound->getChildShape(c)),
                              body->getWorldTransform() * compound->getChildTransform(c), next_static++);
      }
      q.add_static_compound(*body, ids);
    }
  }
}

// The minima the closed loop keeps (metrics' ClearanceMinima): each query
// after a physics step only needs to find what is nearer.
struct Minima {
  double obstacle_m = kInf, ground_m = kInf;
  void update(const Clearance& c) {
    obstacle_m = std::min(obstacle_m, c.obstacle_m);
    ground_m = std::min(ground_m, c.ground_m);
  }
  double obstacle_cutoff() const { return std::max(obstacle_m, 1e-6); }
  double ground_cutoff() const { return std::max(ground_m, 1e-6); }
};

void expect_same(const Clearance& a, const Clearance& b, const std::string& where) {
  EXPECT_EQ(bits(a.obstacle_m), bits(b.obstacle_m)) << where << ": " << a.obstacle_m << " vs " << b.obstacle_m;
  EXPECT_EQ(a.obstacle, b.obstacle) << where;
  EXPECT_EQ(bits(a.ground_m), bits(b.ground_m)) << where << ": " << a.ground_m << " vs " << b.ground_m;
  EXPECT_EQ(a.contact, b.contact) << where;
}

// Walks the vehicle's bodies (moved together, rigidly) through `steps` poses
// around `centre`: small moves toward and away from obstacles, now and then a
// jump (into an obstacle sometimes), now and then no move at all.
void walk_and_compare(const std::string& name, const btVector3& centre, double spread_m, int steps) {
  const Scene scene = load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/" + name + ".json");
  test::PlacedVehicle placed(scene);
  World& world = placed.world;
  ClearanceQuery reusing, searching;
  searching.set_reuse(false);
  register_world(scene, world, reusing);
  register_world(scene, world, searching);

  std::vector<btCollisionObject*> parts;
  std::vector<btTransform> start;  // each part relative to the first
  const btCollisionObjectArray& objects = world.bullet().getCollisionObjectArray();
  for (int i = 0; i < objects.size(); ++i) {
    if (is_vehicle_tag(objects[i]->getUserIndex())) parts.push_back(objects[i]);
  }
  ASSERT_FALSE(parts.empty());
  const btTransform base = parts.front()->getWorldTransform();
  for (btCollisionObject* p : parts) start.push_back(base.inverse() * p->getWorldTransform());

  std::mt19937_64 rng(20261128);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  btTransform pose = base;
  Minima minima;
  for (int k = 0; k < steps; ++k) {
    const double roll = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
    if (roll < 0.03) {  // a jump anywhere around the centre
      pose.setOrigin(centre + btVector3(unit(rng), unit(rng), 0.3 * unit(rng)) * spread_m);
      pose.setRotation(btQuaternion(btVector3(0.1 * unit(rng), 0.1 * unit(rng), 1).normalized(), 3.2 * unit(rng)));
    } else if (roll < 0.9) {  // a step of up to 3 cm, turning a little
      pose.setOrigin(pose.getOrigin() + btVector3(unit(rng), unit(rng), unit(rng)) * 0.03);
      pose.setRotation(pose.getRotation() * btQuaternion(btVector3(0, 0, 1), 0.01 * unit(rng)));
    }  // else: not moved
    for (std::size_t i = 0; i < parts.size(); ++i) parts[i]->setWorldTransform(pose * start[i]);
    const std::string at = name + " step " + std::to_string(k);
    // After a physics step: below the minima so far.
    const double obstacle_cutoff = minima.obstacle_cutoff(), ground_cutoff = minima.ground_cutoff();
    const Clearance a = reusing.measure(world.bullet(), 0, obstacle_cutoff, ground_cutoff);
    const Clearance b = searching.measure(world.bullet(), 0, obstacle_cutoff, ground_cutoff);
    expect_same(a, b, at);
    minima.update(a);
    if (k % 4 == 0) {  // a control tick, the world as the step left it: every obstacle, however far
      const Clearance c = reusing.measure(world.bullet(), 0, kInf, minima.ground_cutoff());
      const Clearance d = searching.measure(world.bullet(), 0, kInf, minima.ground_cutoff());
      expect_same(c, d, at + " (control tick)");
      // Apart, the answer is that of a query that never searched before (no hint, floor or memo).
      // (Overlapping, the depth is that of the first overlapping pair the search meets: the search's own.)
      ClearanceQuery fresh;
      register_world(scene, world, fresh);
      const Clearance e = fresh.measure(world.bullet(), 0, kInf, minima.ground_cutoff());
      if (c.obstacle_m > 0.0) {
        EXPECT_EQ(bits(c.obstacle_m), bits(e.obstacle_m)) << at << " (fresh query)";
        EXPECT_EQ(c.obstacle, e.obstacle) << at << " (fresh query)";
      }
      if (c.ground_m > 0.0) EXPECT_EQ(bits(c.ground_m), bits(e.ground_m)) << at << " (fresh query)";
      minima.update(c);
    }
    if (::testing::Test::HasFailure()) return;
  }
  // The walk came near things: the comparison was not only of +infinity.
  EXPECT_LT(minima.obstacle_m, 0.5);
  EXPECT_LT(minima.ground_m, 1.0);
}

TEST(ClearanceReuse, QuadrotorAmongTreesOnTerrainAnswersAsSearchingEveryTime) {
  walk_and_compare("trees_rolling_terrain", btVector3(-6.0, 0.0, 1.5), 6.0, 4000);
}

TEST(ClearanceReuse, RoverInTheVineyardAnswersAsSearchingEveryTime) {
  walk_and_compare("vineyard", btVector3(0.0, 0.0, 0.3), 10.0, 4000);
}

}  // namespace
}  // namespace campo

namespace campo {
namespace {

// Terrain of z = sin(x / 5): the two triangles of a cell, and the cells of a
// column, lie in one plane (equal lower bounds, the most even ties).
TEST(ClearanceReuse, QuadrotorOverPlanarCellsAmongBuildingsAnswersAsSearchingEveryTime) {
  walk_and_compare("obstacle_field", btVector3(34.0, 58.0, 1.2), 8.0, 4000);
}

}  // namespace
}  // namespace campo
