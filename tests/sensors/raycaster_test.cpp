#include "sensors/raycaster.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <deque>
#include <memory>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "campo/pose.hpp"
#include "campo/random.hpp"
#include "campo/world.hpp"
#include "sensors/fan_kernels.hpp"
#include "tests/sensors/seam_points.hpp"
#include "tests/test_units.hpp"

namespace campo {
namespace {

using namespace campo::test_units;
constexpr double kInf = std::numeric_limits<double>::infinity();

Shape make_shape(ShapeType type, const Eigen::Vector3d& position,
                 const Eigen::Vector3d& rpy_deg = Eigen::Vector3d::Zero()) {
  Shape s;
  s.type = type;
  s.pose = to_isometry(Pose{position, rpy_deg});
  return s;
}

Shape cuboid(const Eigen::Vector3d& position, const Eigen::Vector3d& size,
             const Eigen::Vector3d& rpy_deg = Eigen::Vector3d::Zero()) {
  Shape s = make_shape(ShapeType::cuboid, position, rpy_deg);
  s.size_m = size;
  return s;
}

Shape round_shape(ShapeType type, const Eigen::Vector3d& position, double radius, double height,
                  const Eigen::Vector3d& rpy_deg = Eigen::Vector3d::Zero()) {
  Shape s = make_shape(type, position, rpy_deg);
  s.radius_m = radius;
  s.height_m = height;
  return s;
}

// A heightfield whose vertex (c, r) has height f(x, y) at its local position.
template <class F>
Shape heightfield(int cols, int rows, double spacing, const Eigen::Vector3d& position,
                  double yaw_deg, F f) {
  auto grid = std::make_shared<HeightGrid>();
  grid->cols = cols;
  grid->rows = rows;
  grid->spacing_x_m = spacing;
  grid->spacing_y_m = spacing;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      grid->heights_m.push_back(
          f((c - 0.5 * (cols - 1)) * spacing, (r - 0.5 * (rows - 1)) * spacing));
    }
  }
  Shape s = make_shape(ShapeType::heightfield, position, Eigen::Vector3d(0, 0, yaw_deg));
  s.terrain = grid;
  return s;
}

// Every test runs with both methods: Embree ray by ray, and the fan (each
// cast() of world directions becomes a fan from its origin).
class RayCasterTest : public ::testing::TestWithParam<CastMethod> {};

INSTANTIATE_TEST_SUITE_P(Methods, RayCasterTest, ::testing::Values(CastMethod::embree, CastMethod::fan),
                         [](const auto& info) { return info.param == CastMethod::fan ? "fan" : "embree"; });

RayHit cast_one(const RayCaster& caster, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                float min_range = 0.0f, float max_range = 100.0f) {
  const Eigen::Vector3f d = dir.normalized().cast<float>();
  RayHit hit{};
  caster.cast(origin, std::span<const Eigen::Vector3f>(&d, 1), min_range, max_range,
              std::span<RayHit>(&hit, 1));
  return hit;
}

Eigen::Vector3d random_unit(Rng& rng) {
  // Uniform on the sphere: uniform z and azimuth.
  const double z = rng.uniform(-1.0, 1.0);
  const double phi = rng.uniform(0.0, 2.0 * std::numbers::pi);
  const double s = std::sqrt(1.0 - z * z);
  return {s * std::cos(phi), s * std::sin(phi), z};
}

// Independent reference: true where a point (in the shape's frame) lies inside
// the solid grown by `pad` metres (shrunk when negative); below the surface
// for planes and heightfields.
bool inside_local(const Shape& s, const Eigen::Vector3d& p, double pad = 0.0) {
  const double hz = 0.5 * s.height_m;
  switch (s.type) {
    case ShapeType::cuboid:
      return (p.cwiseAbs().array() <= (0.5 * s.size_m).array() + pad).all();
    case ShapeType::sphere:
      return p.norm() <= s.radius_m + pad;
    case ShapeType::cylinder:
      return std::abs(p.z()) <= hz + pad && p.head<2>().norm() <= s.radius_m + pad;
    case ShapeType::cone: {
      // A normal offset of pad moves the slanted side sideways by pad * sqrt(1 + k^2).
      const double k = s.radius_m / (2.0 * hz);
      return std::abs(p.z()) <= hz + pad &&
             p.head<2>().norm() <= k * (hz - p.z()) + pad * std::sqrt(1.0 + k * k);
    }
    case ShapeType::plane:
      return p.z() <= pad;
    case ShapeType::heightfield: {
      const auto h = s.terrain->height_at(p.x(), p.y());
      return h && p.z() <= *h + pad;
    }
    case ShapeType::mesh:  // not used here: mesh_raycast_test.cpp compares meshes with these primitives
      return false;
  }
  return false;
}

bool inside(const Shape& s, const Eigen::Vector3d& world, double pad = 0.0) {
  return inside_local(s, s.pose.inverse() * world, pad);
}

// First t in [0, t_max] where `is_in(origin + t dir)` turns true: marching in
// `step` then bisection to 1e-7 m. nullopt if it never does.
template <class Pred>
std::optional<double> first_crossing(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                     double t_max, double step, Pred is_in) {
  double lo = 0.0;
  for (double t = step; t <= t_max + step; t += step) {
    if (is_in(origin + std::min(t, t_max) * dir)) {
      double hi = std::min(t, t_max);
      while (hi - lo > 1e-7) {
        const double mid = 0.5 * (lo + hi);
        (is_in(origin + mid * dir) ? hi : lo) = mid;
      }
      return hi;
    }
    lo = t;
  }
  return std::nullopt;
}

TEST_P(RayCasterTest, TiltedPlaneRangeIsDistanceOverCosine) {
  Scene scene;
  scene.shapes.push_back(make_shape(ShapeType::plane, {1.0, -2.0, -3.0}, {12.0, -20.0, 30.0}));
  const RayCaster caster(scene, GetParam());
  const Eigen::Vector3d origin(0.5, 0.25, 1.0);
  const Eigen::Vector3d n = scene.shapes[0].pose.linear().col(2);
  const double distance = n.dot(origin - scene.shapes[0].pose.translation());
  ASSERT_GT(distance, 0.0);
  Rng rng(7);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d d = random_unit(rng);
    const RayHit hit = cast_one(caster, origin, d);
    // cos of the angle between the ray and the perpendicular to the plane.
    const double cos_angle = -n.dot(d);
    const double expected = cos_angle > 0.0 ? distance / cos_angle : kInf;
    if (expected <= 100.0) {
      ++hits;
      ASSERT_EQ(hit.shape, 0) << "ray " << i;
      EXPECT_NEAR(hit.distance_m, expected, kMm) << "ray " << i;
    } else {
      EXPECT_EQ(hit.shape, RayHit::kNoShape) << "ray " << i;
      EXPECT_TRUE(std::isinf(hit.distance_m)) << "ray " << i;
    }
  }
  EXPECT_GT(hits, 800);
}

TEST_P(RayCasterTest, SphereMatchesClosedFormRaySphereIntersection) {
  Scene scene;
  const Eigen::Vector3d c(40.0, 10.0, 5.0);
  const double r = 1.3;
  scene.shapes.push_back(round_shape(ShapeType::sphere, c, r, 0.0));
  const RayCaster caster(scene, GetParam());
  const Eigen::Vector3d origin(0.1, -0.2, 0.3);
  Rng rng(11);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d target = c + 1.5 * r * random_unit(rng);
    const Eigen::Vector3d d = (target - origin).normalized();
    // |o + t d - c|^2 = r^2, nearer root.
    const Eigen::Vector3d oc = origin - c;
    const double b = d.dot(oc);
    const double disc = b * b - (oc.squaredNorm() - r * r);
    const RayHit hit = cast_one(caster, origin, d);
    if (disc >= 0.0) {
      ++hits;
      ASSERT_EQ(hit.shape, 0) << "ray " << i;
      EXPECT_NEAR(hit.distance_m, -b - std::sqrt(disc), kMm) << "ray " << i;
    } else {
      EXPECT_EQ(hit.shape, RayHit::kNoShape) << "ray " << i;
    }
  }
  EXPECT_GT(hits, 500);
}

TEST_P(RayCasterTest, CuboidFacesAtKnownDistances) {
  Scene scene;
  scene.shapes.push_back(cuboid({5.0, 0.0, 0.0}, {2.0, 4.0, 6.0}));
  // A box turned 30 deg about z, its near face 3 m from the origin along its normal.
  const Eigen::Vector3d normal(std::cos(std::numbers::pi / 6), std::sin(std::numbers::pi / 6), 0.0);
  scene.shapes.push_back(cuboid(-(3.0 + 0.5) * normal, {1.0, 2.0, 2.0}, {0.0, 0.0, 30.0}));
  const RayCaster caster(scene, GetParam());
  for (double y = -1.9; y <= 1.9; y += 0.38) {
    for (double z = -2.9; z <= 2.9; z += 0.58) {
      const RayHit hit = cast_one(caster, {0.0, y, z}, Eigen::Vector3d::UnitX());
      EXPECT_EQ(hit.shape, 0);
      EXPECT_NEAR(hit.distance_m, 4.0, kMm) << y << " " << z;
    }
  }
  // Along the turned box's face normal, at an angle a off it: 3 / cos(a).
  for (double a_deg = -15.0; a_deg <= 15.0; a_deg += 3.0) {
    const Eigen::Vector3d d =
        Eigen::AngleAxisd(a_deg * std::numbers::pi / 180.0, Eigen::Vector3d::UnitZ()) * -normal;
    const RayHit hit = cast_one(caster, Eigen::Vector3d::Zero(), d);
    EXPECT_EQ(hit.shape, 1);
    EXPECT_NEAR(hit.distance_m, 3.0 / std::cos(a_deg * std::numbers::pi / 180.0), kMm) << a_deg;
  }
}

TEST_P(RayCasterTest, CylinderSideAndCapsAtClosedFormDistances) {
  Scene scene;
  const double r = 0.5, h = 2.0;
  scene.shapes.push_back(round_shape(ShapeType::cylinder, {5.0, 0.0, 0.0}, r, h));
  const RayCaster caster(scene, GetParam());
  // Horizontal rays meet the side at x = 5 - sqrt(r^2 - y^2).
  for (double y = -0.49; y <= 0.49; y += 0.07) {
    for (double z = -0.95; z <= 0.95; z += 0.19) {
      const RayHit hit = cast_one(caster, {0.0, y, z}, Eigen::Vector3d::UnitX());
      EXPECT_EQ(hit.shape, 0);
      EXPECT_NEAR(hit.distance_m, 5.0 - std::sqrt(r * r - y * y), kMm) << y << " " << z;
    }
  }
  // Vertical rays meet the caps at z = +-h/2.
  for (double x = -0.45; x <= 0.45; x += 0.09) {
    const RayHit down = cast_one(caster, {5.0 + x, 0.1, 10.0}, -Eigen::Vector3d::UnitZ());
    const RayHit up = cast_one(caster, {5.0 + x, -0.1, -7.0}, Eigen::Vector3d::UnitZ());
    EXPECT_NEAR(down.distance_m, 10.0 - 0.5 * h, kMm) << x;
    EXPECT_NEAR(up.distance_m, 7.0 - 0.5 * h, kMm) << x;
  }
  // Just outside the radius: a miss.
  EXPECT_EQ(cast_one(caster, {0.0, 0.501, 0.0}, Eigen::Vector3d::UnitX()).shape, RayHit::kNoShape);
}

TEST_P(RayCasterTest, ConeSideAndBaseAtClosedFormDistancesWithApexUp) {
  Scene scene;
  const double r = 1.0, h = 2.0;
  scene.shapes.push_back(round_shape(ShapeType::cone, {5.0, 0.0, 0.0}, r, h));
  const RayCaster caster(scene, GetParam());
  // At height z the radius is r (h/2 - z) / h; horizontal rays meet it there.
  for (double z = -0.95; z <= 0.95; z += 0.1) {
    const double rz = r * (0.5 * h - z) / h;
    for (double f = -0.9; f <= 0.9; f += 0.3) {
      const double y = f * rz;
      const RayHit hit = cast_one(caster, {0.0, y, z}, Eigen::Vector3d::UnitX());
      EXPECT_EQ(hit.shape, 0);
      EXPECT_NEAR(hit.distance_m, 5.0 - std::sqrt(rz * rz - y * y), kMm) << y << " " << z;
    }
  }
  for (double rho = 0.05; rho < 0.95; rho += 0.1) {
    // From above, the side at the height where the radius is rho; from below, the base.
    const RayHit down = cast_one(caster, {5.0 + rho, 0.0, 10.0}, -Eigen::Vector3d::UnitZ());
    const RayHit up = cast_one(caster, {5.0, rho, -10.0}, Eigen::Vector3d::UnitZ());
    EXPECT_NEAR(down.distance_m, 10.0 - (0.5 * h - rho * h / r), kMm) << rho;
    EXPECT_NEAR(up.distance_m, 10.0 - 0.5 * h, kMm) << rho;
  }
  // Above the apex there is nothing (the cone equation's mirror image is not a surface).
  EXPECT_EQ(cast_one(caster, {0.0, 0.0, 1.5}, Eigen::Vector3d::UnitX()).shape, RayHit::kNoShape);
}

TEST_P(RayCasterTest, TurnedPrimitivesMatchAMarchingReference) {
  Scene scene;
  scene.shapes.push_back(cuboid({6.0, 1.0, 0.5}, {1.5, 0.8, 2.5}, {20.0, -35.0, 60.0}));
  scene.shapes.push_back(
      round_shape(ShapeType::cylinder, {-5.0, 4.0, 1.0}, 0.4, 3.0, {40.0, 15.0, 0.0}));
  scene.shapes.push_back(
      round_shape(ShapeType::cone, {2.0, -6.0, -1.0}, 1.2, 2.0, {-70.0, 10.0, 45.0}));
  scene.shapes.push_back(round_shape(ShapeType::sphere, {-3.0, -4.0, 2.0}, 0.9, 0.0));
  const RayCaster caster(scene, GetParam());
  std::vector<Eigen::Isometry3d> to_local;
  for (const Shape& s : scene.shapes) to_local.push_back(s.pose.inverse());
  const Eigen::Vector3d origin(0.2, -0.1, 0.3);
  Rng rng(5);
  for (std::size_t k = 0; k < scene.shapes.size(); ++k) {
    const Shape& s = scene.shapes[k];
    int hits = 0;
    for (int i = 0; i < 300; ++i) {
      const Eigen::Vector3d target = s.pose.translation() + 1.6 * random_unit(rng);
      const Eigen::Vector3d d = (target - origin).normalized();
      const auto expected = first_crossing(origin, d, 20.0, 5e-4, [&](const Eigen::Vector3d& p) {
        for (std::size_t j = 0; j < scene.shapes.size(); ++j) {
          if (inside_local(scene.shapes[j], to_local[j] * p)) return true;
        }
        return false;
      });
      const RayHit hit = cast_one(caster, origin, d, 0.0f, 20.0f);
      ASSERT_EQ(hit.shape != RayHit::kNoShape, expected.has_value())
          << to_string(s.type) << " ray " << i;
      if (expected) {
        ++hits;
        EXPECT_NEAR(hit.distance_m, *expected, kMm) << to_string(s.type) << " ray " << i;
      }
    }
    EXPECT_GT(hits, 50) << to_string(s.type);
  }
}

TEST_P(RayCasterTest, PlanarRampHeightfieldIsExact) {
  // z = 0.3 x - 0.2 y + 0.5 (local) is a plane, so the triangulation is exact.
  const double a = 0.3, b = -0.2, c = 0.5;
  Scene scene;
  scene.shapes.push_back(heightfield(41, 31, 0.5, {2.0, -1.0, 0.25}, 25.0,
                                     [&](double x, double y) { return a * x + b * y + c; }));
  const Shape& hf = scene.shapes[0];
  const RayCaster caster(scene, GetParam());
  const Eigen::Vector3d n = hf.pose.linear() * Eigen::Vector3d(-a, -b, 1.0).normalized();
  const Eigen::Vector3d on_plane = hf.pose * Eigen::Vector3d(0.0, 0.0, c);
  const Eigen::Vector3d origin(1.0, 0.5, 15.0);
  Rng rng(3);
  for (int i = 0; i < 2000; ++i) {
    // Aim at a point of the ramp; the ray can cross its plane only there.
    const double x = rng.uniform(-9.5, 9.5), y = rng.uniform(-7.0, 7.0);
    const Eigen::Vector3d target = hf.pose * Eigen::Vector3d(x, y, a * x + b * y + c);
    const Eigen::Vector3d d = (target - origin).normalized();
    const RayHit hit = cast_one(caster, origin, d);
    ASSERT_EQ(hit.shape, 0) << "ray " << i;
    EXPECT_NEAR(hit.distance_m, n.dot(on_plane - origin) / n.dot(d), kMm) << "ray " << i;
  }
}

TEST_P(RayCasterTest, CurvedHeightfieldMatchesBisectionOnHeightAt) {
  Scene scene;
  scene.shapes.push_back(heightfield(81, 61, 0.5, {0.5, -0.5, 0.2}, 20.0, [](double x, double y) {
    return std::sin(x / 5.0) + 0.3 * std::cos(y / 3.0);
  }));
  const Shape& hf = scene.shapes[0];
  const RayCaster caster(scene, GetParam());
  const Eigen::Isometry3d to_local = hf.pose.inverse();
  const auto below_surface = [&](const Eigen::Vector3d& world) {
    const Eigen::Vector3d p = to_local * world;
    const auto h = hf.terrain->height_at(p.x(), p.y());
    return h && p.z() <= *h;
  };
  const Eigen::Vector3d origin(1.0, 2.0, 3.0);
  Rng rng(9);
  int hits = 0;
  for (int i = 0; i < 1000; ++i) {
    const double az = rng.uniform(-std::numbers::pi, std::numbers::pi);
    const double el = rng.uniform(-60.0, -5.0) * std::numbers::pi / 180.0;
    const Eigen::Vector3d d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
    const auto expected = first_crossing(origin, d, 60.0, 2e-3, below_surface);
    const RayHit hit = cast_one(caster, origin, d, 0.0f, 60.0f);
    ASSERT_EQ(hit.shape != RayHit::kNoShape, expected.has_value()) << "ray " << i;
    if (expected) {
      ++hits;
      EXPECT_NEAR(hit.distance_m, *expected, kMm) << "ray " << i;
    }
  }
  EXPECT_GT(hits, 500);
}

TEST_P(RayCasterTest, HeightfieldHasNoCracksAtVerticesAndEdges) {
  // Rays aimed exactly at vertices, edge midpoints and cell diagonals of a
  // bumpy grid, straight down and slanted (steeply enough that no bump is in
  // the way): none may slip through.
  Rng bumps(21);
  Scene scene;
  scene.shapes.push_back(heightfield(33, 33, 0.25, {0.0, 0.0, 0.0}, 0.0,
                                     [&](double, double) { return bumps.uniform(-0.2, 0.2); }));
  const Shape& hf = scene.shapes[0];
  const HeightGrid& g = *hf.terrain;
  const RayCaster caster(scene, GetParam());
  const Eigen::Vector3d kSlanted[] = {{1.3, -0.7, 50.0}, {-2.1, 3.3, 40.0}, {0.05, 0.05, 10.0}};
  int rays = 0;
  // Interior points only: the outer boundary can be grazed legitimately.
  for (const Eigen::Vector3d& target : test_support::seam_points(g)) {
    const Eigen::Vector3d above(target.x(), target.y(), 5.0);
    for (const Eigen::Vector3d& origin : {above, kSlanted[0], kSlanted[1], kSlanted[2]}) {
      const RayHit hit = cast_one(caster, origin, target - origin, 0.0f, 60.0f);
      ASSERT_EQ(hit.shape, 0) << "at " << target.transpose() << " from " << origin.transpose();
      EXPECT_NEAR(hit.distance_m, (target - origin).norm(), kMm) << "at " << target.transpose();
      ++rays;
    }
  }
  EXPECT_EQ(rays, 31 * 31 * 4 * 4);
}

TEST_P(RayCasterTest, MinRangeSkipsNearSurfacesAndTheRayContinues) {
  Scene scene;
  scene.shapes.push_back(cuboid({0.03, 0.0, 0.0}, {0.02, 1.0, 1.0}));  // x in [0.02, 0.04]
  scene.shapes.push_back(cuboid({2.5, 0.0, 0.0}, {1.0, 1.0, 1.0}));    // x in [2, 3]
  const RayCaster caster(scene, GetParam());
  const Eigen::Vector3d o = Eigen::Vector3d::Zero();
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX();
  EXPECT_NEAR(cast_one(caster, o, x, 0.0f).distance_m, 0.02, 1e-6);
  EXPECT_EQ(cast_one(caster, o, x, 0.0f).shape, 0);
  // The plate's near face is skipped, its far face (0.04) is still ahead.
  EXPECT_NEAR(cast_one(caster, o, x, 0.03f).distance_m, 0.04, 1e-6);
  const RayHit past_plate = cast_one(caster, o, x, 0.05f);
  EXPECT_EQ(past_plate.shape, 1);
  EXPECT_NEAR(past_plate.distance_m, 2.0, 1e-6);
  // Starting the range inside the second box: its far face.
  EXPECT_NEAR(cast_one(caster, o, x, 2.5f).distance_m, 3.0, 1e-6);
}

TEST_P(RayCasterTest, MaxRangeTurnsFartherSurfacesIntoMisses) {
  Scene scene;
  scene.shapes.push_back(cuboid({10.5, 0.0, 0.0}, {1.0, 1.0, 1.0}));
  scene.shapes.push_back(make_shape(ShapeType::plane, {0.0, 0.0, -1.0}));
  const RayCaster caster(scene, GetParam());
  const RayHit miss =
      cast_one(caster, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 0.0f, 9.99f);
  EXPECT_EQ(miss.shape, RayHit::kNoShape);
  EXPECT_TRUE(std::isinf(miss.distance_m));
  EXPECT_NEAR(
      cast_one(caster, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 0.0f, 10.01f).distance_m,
      10.0, 1e-6);
  // The ground 1 m below, seen at 60 deg down: 1 / sin(60 deg) = 1.1547 m.
  const Eigen::Vector3d down(0.5, 0.0, -std::sqrt(3.0) / 2.0);
  EXPECT_EQ(cast_one(caster, Eigen::Vector3d::Zero(), down, 0.0f, 1.15f).shape, RayHit::kNoShape);
  EXPECT_EQ(cast_one(caster, Eigen::Vector3d::Zero(), down, 0.0f, 1.16f).shape, 1);
}

// An unbounded range: what is hit keeps its distance, what is missed stays a
// miss (no shape, infinite distance).
TEST_P(RayCasterTest, AnInfiniteMaxRangeStillReportsMissesAsMisses) {
  Scene scene;
  scene.shapes.push_back(round_shape(ShapeType::sphere, {5.0, 0.0, 0.0}, 1.0, 0.0));
  scene.shapes.push_back(cuboid({0.0, 30.0, 0.0}, {1.0, 1.0, 1.0}));
  const RayCaster caster(scene, GetParam());
  Rng rng(8);
  std::vector<Eigen::Vector3f> dirs;
  for (int i = 0; i < 600; ++i) dirs.push_back(random_unit(rng).cast<float>());
  dirs.push_back(Eigen::Vector3f::UnitX());
  dirs.push_back(Eigen::Vector3f::UnitY());
  std::vector<RayHit> hits(dirs.size());
  caster.cast(Eigen::Vector3d::Zero(), dirs, 0.0f, std::numeric_limits<float>::infinity(), hits);
  int missed = 0;
  for (const RayHit& h : hits) {
    if (h.shape == RayHit::kNoShape) {
      EXPECT_TRUE(std::isinf(h.distance_m));
      ++missed;
    } else {
      EXPECT_TRUE(std::isfinite(h.distance_m)) << "shape " << h.shape;
    }
  }
  EXPECT_GT(missed, 400);
  EXPECT_NEAR(hits[600].distance_m, 4.0, 1e-6);
  EXPECT_NEAR(hits[601].distance_m, 29.5, 1e-5);
}

// A ray in the plane of a box's face (a level scan from exactly the height of
// a box's top) hits the box's side: it is within the box's height range.
TEST_P(RayCasterTest, ARayInTheBoxsFacePlaneHitsTheBox) {
  Scene scene;
  scene.shapes.push_back(cuboid({5.0, 0.0, 0.15}, {1.0, 2.0, 0.3}));  // top face at z = 0.3
  const RayCaster caster(scene, GetParam());
  const RayHit hit = cast_one(caster, {0.0, 0.0, 0.3}, Eigen::Vector3d::UnitX(), 0.0f, 20.0f);
  EXPECT_EQ(hit.shape, 0);
  EXPECT_NEAR(hit.distance_m, 4.5, 1e-6);
  // Level rays fanned across it, as a planar LIDAR's: every one that points at the box hits it.
  std::vector<Eigen::Vector3f> dirs;
  for (int i = -20; i <= 20; ++i) {
    const double a = i * 0.01;
    dirs.emplace_back(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0.0f);
  }
  std::vector<RayHit> hits(dirs.size());
  caster.cast(Eigen::Vector3d(0.0, 0.0, 0.3), dirs, 0.0f, 20.0f, hits);
  for (const RayHit& h : hits) EXPECT_EQ(h.shape, 0);
}

TEST_P(RayCasterTest, NearestOfOverlappingShapesWinsAndIsNamed) {
  Scene scene;
  scene.shapes.push_back(make_shape(ShapeType::plane, {0.0, 0.0, 0.0}));  // 0
  scene.shapes.push_back(
      heightfield(11, 11, 1.0, {0.0, 0.0, 0.0}, 0.0, [](double, double) { return 0.5; }));  // 1
  scene.shapes.push_back(cuboid({5.0, 0.0, 1.0}, {1.0, 1.0, 1.0}));                         // 2
  scene.shapes.push_back(round_shape(ShapeType::sphere, {5.2, 0.0, 1.0}, 0.6, 0.0));        // 3
  scene.shapes.push_back(round_shape(ShapeType::cylinder, {-5.0, 0.0, 1.0}, 0.3, 2.0));     // 4
  const RayCaster caster(scene, GetParam());
  const Eigen::Vector3d o(0.0, 0.0, 1.0);
  // The sphere overlaps the box but starts behind its near face (4.6 > 4.5).
  EXPECT_EQ(cast_one(caster, o, Eigen::Vector3d::UnitX()).shape, 2);
  EXPECT_NEAR(cast_one(caster, o, Eigen::Vector3d::UnitX()).distance_m, 4.5, 1e-6);
  EXPECT_EQ(cast_one(caster, o, -Eigen::Vector3d::UnitX()).shape, 4);
  // Down: the heightfield (z = 0.5) hides the plane (z = 0) inside its footprint only.
  EXPECT_EQ(cast_one(caster, o, -Eigen::Vector3d::UnitZ()).shape, 1);
  EXPECT_NEAR(cast_one(caster, o, -Eigen::Vector3d::UnitZ()).distance_m, 0.5, 1e-6);
  EXPECT_EQ(cast_one(caster, {0.0, 7.0, 1.0}, -Eigen::Vector3d::UnitZ()).shape, 0);
  EXPECT_NEAR(cast_one(caster, {0.0, 7.0, 1.0}, -Eigen::Vector3d::UnitZ()).distance_m, 1.0, 1e-6);
  // Up: nothing.
  EXPECT_EQ(cast_one(caster, o, Eigen::Vector3d::UnitZ()).shape, RayHit::kNoShape);
}

TEST(RayCasterFan, KeepsTheNearestSurfaceAndBreaksTiesInOneFixedOrder) {
  // Planes are cast last but keep only strictly nearer hits, so a fan must
  // answer as if every surface were cast alone and the answers merged in the
  // order planes (in scene order), heightfields, primitives, each taking a
  // tie. Coincident surfaces make ties common: two planes and a flat
  // heightfield at z = 0, a box standing on them.
  if (!fan::kernels_available()) GTEST_SKIP() << "no AVX2 and FMA: no fan";
  std::vector<Shape> shapes;
  shapes.push_back(make_shape(ShapeType::plane, {0.0, 0.0, 0.0}));                                   // 0
  shapes.push_back(heightfield(21, 21, 0.5, {0.5, 0.3, 0.0}, 17.0, [](double, double) { return 0.0; }));  // 1
  shapes.push_back(make_shape(ShapeType::plane, {3.0, -2.0, 0.0}));                                  // 2
  shapes.push_back(cuboid({2.0, 0.5, 0.5}, {1.0, 2.0, 1.0}, {0.0, 0.0, 30.0}));                     // 3
  Scene scene;
  scene.shapes = shapes;
  const RayCaster caster(scene, CastMethod::fan);
  const std::array<int, 4> merge_order = {0, 2, 1, 3};
  std::deque<Scene> singles;  // each outlives its caster
  std::vector<std::unique_ptr<RayCaster>> alone;
  for (const Shape& shape : shapes) {
    singles.emplace_back().shapes = {shape};
    alone.push_back(std::make_unique<RayCaster>(singles.back(), CastMethod::fan));
  }
  Rng rng(37);
  std::vector<Eigen::Vector3f> dirs;
  for (int i = 0; i < 4000; ++i) {
    const Eigen::Vector3d d(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, -0.05));
    dirs.push_back(d.normalized().cast<float>());
  }
  const Eigen::Vector3d origin(0.1, -0.2, 1.7);
  std::vector<RayHit> hits(dirs.size()), one(dirs.size());
  caster.cast(origin, dirs, 0.05f, 20.0f, hits);
  std::vector<RayHit> expected(dirs.size(), RayHit{std::numeric_limits<float>::infinity(), RayHit::kNoShape});
  for (const int index : merge_order) {
    alone[static_cast<std::size_t>(index)]->cast(origin, dirs, 0.05f, 20.0f, one);
    for (std::size_t i = 0; i < dirs.size(); ++i) {
      if (one[i].shape != RayHit::kNoShape && one[i].distance_m <= expected[i].distance_m) {
        expected[i] = {one[i].distance_m, index};
      }
    }
  }
  int ties = 0;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    ASSERT_EQ(hits[i].shape, expected[i].shape) << "ray " << i;
    ASSERT_EQ(hits[i].distance_m, expected[i].distance_m) << "ray " << i;
  }
  // The planes' and the heightfield's ranges tie on most rays that meet the heightfield.
  alone[0]->cast(origin, dirs, 0.05f, 20.0f, one);
  std::vector<RayHit> terrain(dirs.size());
  alone[1]->cast(origin, dirs, 0.05f, 20.0f, terrain);
  for (std::size_t i = 0; i < dirs.size(); ++i) ties += terrain[i].shape != RayHit::kNoShape && terrain[i].distance_m == one[i].distance_m;
  EXPECT_GT(ties, 500);
}

TEST_P(RayCasterTest, SetTimeMovesMoversAlongTheirPaths) {
  Scene scene;
  scene.shapes.push_back(cuboid({20.5, 0.0, 0.0}, {1.0, 4.0, 4.0}));  // wall behind, x = 20
  Mover along;                                                        // moves away along the ray
  along.shape = cuboid({5.0, 0.0, 0.0}, {1.0, 1.0, 1.0});
  along.path_m = {{5.0, 0.0, 0.0}, {15.0, 0.0, 0.0}};
  along.speed_mps = 2.0;
  scene.movers.push_back(along);
  Mover across;  // crosses the ray at x = 3 later
  across.shape = round_shape(ShapeType::sphere, {3.0, -10.0, 0.0}, 0.5, 0.0);
  across.path_m = {{3.0, -10.0, 0.0}, {3.0, 10.0, 0.0}};
  across.speed_mps = 1.0;
  across.start_time_s = 10.0;
  scene.movers.push_back(across);
  RayCaster caster(scene, GetParam());
  const Eigen::Vector3d o = Eigen::Vector3d::Zero();
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX();
  EXPECT_EQ(cast_one(caster, o, x).shape, -1);
  EXPECT_NEAR(cast_one(caster, o, x).distance_m, 4.5, 1e-6);
  caster.set_poses(scripted_poses(scene, 2.0));
  EXPECT_NEAR(cast_one(caster, o, x).distance_m, 8.5, 1e-6);
  caster.set_poses(scripted_poses(scene, 20.0));  // first mover parked at x = 15, the sphere on the ray
  EXPECT_EQ(cast_one(caster, o, x).shape, -2);
  EXPECT_NEAR(cast_one(caster, o, x).distance_m, 2.5, 1e-6);
  caster.set_poses(scripted_poses(scene, 40.0));  // the sphere has gone by
  EXPECT_EQ(cast_one(caster, o, x).shape, -1);
  EXPECT_NEAR(cast_one(caster, o, x).distance_m, 14.5, 1e-6);
  // Off the movers' line the static wall is seen.
  EXPECT_EQ(cast_one(caster, {0.0, 1.5, 0.0}, x).shape, 0);
  caster.set_poses(scripted_poses(scene, 0.0));
  EXPECT_NEAR(cast_one(caster, o, x).distance_m, 4.5, 1e-6);
}

TEST_P(RayCasterTest, RejectsMoversThatAreNotPrimitives) {
  Scene scene;
  Mover m;
  m.shape = make_shape(ShapeType::plane, Eigen::Vector3d::Zero());
  m.shape.alias = "floor";
  m.path_m = {Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()};
  scene.movers.push_back(m);
  try {
    const RayCaster caster(scene, GetParam());
    FAIL() << "a plane mover was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("moving body 'floor' is a plane"), std::string::npos)
        << e.what();
  }
}

TEST_P(RayCasterTest, BatchCastEqualsOneRayAtATime) {
  Scene scene;
  scene.shapes.push_back(make_shape(ShapeType::plane, {0.0, 0.0, -1.0}));
  scene.shapes.push_back(cuboid({3.0, 0.0, 0.0}, {1.0, 1.0, 1.0}));
  scene.shapes.push_back(round_shape(ShapeType::cone, {0.0, 3.0, 0.0}, 0.5, 1.0));
  Mover m;
  m.shape = round_shape(ShapeType::cylinder, {-3.0, 0.0, 0.0}, 0.5, 1.0);
  m.path_m = {{-3.0, 0.0, 0.0}, {-3.0, -3.0, 0.0}};
  scene.movers.push_back(m);
  const RayCaster caster(scene, GetParam());
  Rng rng(1);
  std::vector<Eigen::Vector3f> dirs;
  for (int i = 0; i < 1000; ++i) dirs.push_back(random_unit(rng).cast<float>());
  std::vector<RayHit> batch(dirs.size());
  const Eigen::Vector3d o(0.1, 0.2, 0.3);
  caster.cast(o, dirs, 0.05f, 8.0f, batch);
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    RayHit one{};
    caster.cast(o, std::span<const Eigen::Vector3f>(&dirs[i], 1), 0.05f, 8.0f,
                std::span<RayHit>(&one, 1));
    ASSERT_EQ(batch[i].shape, one.shape) << i;
    ASSERT_EQ(batch[i].distance_m, one.distance_m) << i;
  }
}

// True when the segment passes within `band` of some shape's surface without
// going deeper than that into it: a ray that grazes an edge or a silhouette,
// where Bullet's convex ray test may round hit or miss either way.
bool grazes(const Scene& scene, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
            double t_max, double band) {
  for (const Shape& s : scene.shapes) {
    const Eigen::Isometry3d to_local = s.pose.inverse();
    const auto near = [&](const Eigen::Vector3d& p) { return inside_local(s, to_local * p, band); };
    const auto deep = [&](const Eigen::Vector3d& p) {
      return inside_local(s, to_local * p, -band);
    };
    if (first_crossing(origin, dir, t_max, 2e-3, near) &&
        !first_crossing(origin, dir, t_max, 2e-3, deep)) {
      return true;
    }
  }
  return false;
}

// Every shape type plus a heightfield, with the Bullet world built from the
// same Scene as the reference. Away from edges both must agree on hit or miss,
// on the shape and on the distance within 1 mm. Bullet's convex ray test
// (btSubsimplexConvexCast) stops at a squared distance of 1e-4, so it reports
// hits on rays that miss a primitive by up to a few centimetres; those rays
// are told apart with an independent reference and only counted.
TEST_P(RayCasterTest, AgreesWithBulletRayTest) {
  Scene scene;
  scene.shapes.push_back(make_shape(ShapeType::plane, {0.0, 0.0, -1.5}));
  scene.shapes.push_back(heightfield(61, 61, 0.5, {0.0, 0.0, 0.0}, 15.0, [](double x, double y) {
    return 0.6 * std::sin(x / 3.0) * std::cos(y / 4.0);
  }));
  scene.shapes.push_back(cuboid({3.0, 2.0, 1.5}, {1.2, 0.7, 2.0}, {10.0, 25.0, 40.0}));
  scene.shapes.push_back(cuboid({-6.0, 5.0, 0.5}, {3.0, 0.2, 1.0}));
  scene.shapes.push_back(
      round_shape(ShapeType::cylinder, {-3.0, 4.0, 1.5}, 0.4, 2.5, {20.0, 0.0, 0.0}));
  scene.shapes.push_back(round_shape(ShapeType::cylinder, {6.0, -2.0, 1.0}, 0.15, 3.0));
  scene.shapes.push_back(
      round_shape(ShapeType::cone, {5.0, -5.0, 1.0}, 0.8, 2.0, {0.0, -30.0, 10.0}));
  scene.shapes.push_back(round_shape(ShapeType::cone, {-5.0, -2.0, 1.5}, 1.0, 3.0));
  scene.shapes.push_back(round_shape(ShapeType::sphere, {-4.0, -6.0, 2.0}, 1.0, 0.0));
  scene.shapes.push_back(round_shape(ShapeType::sphere, {1.0, -3.0, 0.8}, 0.3, 0.0));
  const RayCaster caster(scene, GetParam());
  const World world(scene);
  Rng rng(2024);
  const double max_range = 25.0;
  const int rays = 6000;
  int hits = 0, grazing = 0, disagreements = 0;
  std::ostringstream first_disagreements;
  std::vector<int> hits_per_shape(scene.shapes.size(), 0);
  for (int i = 0; i < rays;) {
    const Eigen::Vector3d origin(rng.uniform(-8.0, 8.0), rng.uniform(-8.0, 8.0),
                                 rng.uniform(0.8, 4.0));
    bool in_solid = false;
    for (const Shape& s : scene.shapes) in_solid = in_solid || inside(s, origin);
    if (in_solid) continue;
    ++i;
    // Half the rays in random directions, half aimed near a random primitive
    // so every shape and its edges are well covered.
    const Shape& aim = scene.shapes[static_cast<std::size_t>(rng.uniform_int(2, 9))];
    const double reach = aim.type == ShapeType::cuboid
                             ? 0.5 * aim.size_m.norm()
                             : std::hypot(aim.radius_m, 0.5 * aim.height_m);
    const Eigen::Vector3d d =
        i % 2 ? random_unit(rng)
              : (aim.pose.translation() + 1.2 * reach * random_unit(rng) - origin).normalized();
    const RayHit hit = cast_one(caster, origin, d, 0.0f, static_cast<float>(max_range));
    const auto bullet = world.ray_test(origin, origin + max_range * d);
    const bool agree = (hit.shape != RayHit::kNoShape) == bullet.has_value() &&
                       (!bullet || (hit.shape == bullet->shape &&
                                    std::abs(hit.distance_m - bullet->distance_m) <= kMm));
    if (agree) {
      if (bullet) {
        ++hits;
        ++hits_per_shape[static_cast<std::size_t>(bullet->shape)];
      }
      continue;
    }
    const double farther = std::max(bullet ? bullet->distance_m : 0.0,
                                    std::isinf(hit.distance_m) ? 0.0 : double{hit.distance_m});
    if (grazes(scene, origin, d, std::min(max_range, farther + 0.1), 0.05)) {
      ++grazing;
      continue;
    }
    if (++disagreements <= 5) {
      first_disagreements << "\nray " << i << " from " << origin.transpose() << " along "
                          << d.transpose() << ": Embree " << hit.distance_m << " m on shape "
                          << hit.shape << ", Bullet " << (bullet ? bullet->distance_m : kInf)
                          << " m on shape " << (bullet ? bullet->shape : RayHit::kNoShape);
    }
  }
  EXPECT_EQ(disagreements, 0) << "first ones:" << first_disagreements.str();
  EXPECT_GT(hits, rays / 2);
  for (std::size_t k = 0; k < scene.shapes.size(); ++k) {
    EXPECT_GT(hits_per_shape[k], 25)
        << "shape " << k << " (" << to_string(scene.shapes[k].type) << ")";
  }
  EXPECT_LT(grazing, rays / 50);
}

}  // namespace
}  // namespace campo
