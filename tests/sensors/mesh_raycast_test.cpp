// Mesh shapes in the ray caster: a mesh of a cuboid or a cylinder gives the
// ranges of the analytic primitive (the independent truth), placed, turned,
// scaled or moved; a closed mesh lets no ray through its shared edges and
// vertices; the depth camera sees a mesh as it sees the primitive.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <utility>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "campo/pose.hpp"
#include "campo/random.hpp"
#include "campo/range_sensor_config.hpp"
#include "scene/scene_mesh.hpp"
#include "sensors/depth_camera.hpp"
#include "sensors/fan_kernels.hpp"
#include "sensors/lidar.hpp"
#include "sensors/ray_fan.hpp"
#include "sensors/raycaster.hpp"
#include "tests/triangle_meshes.hpp"
#include "tests/test_units.hpp"

namespace campo {
namespace {

using test_support::cuboid_mesh;
using test_support::cylinder_mesh;
using test_support::icosphere_mesh;
using test_support::mesh_shape;

using namespace campo::test_units;
constexpr float kMinRange_m = 0.05f, kMaxRange_m = 10.0f;

Eigen::Isometry3d pose(const Eigen::Vector3d& position, const Eigen::Vector3d& rpy_deg = Eigen::Vector3d::Zero()) {
  return to_isometry(Pose{position, rpy_deg});
}

Shape cuboid(const Eigen::Isometry3d& at, const Eigen::Vector3d& size) {
  Shape s;
  s.type = ShapeType::cuboid;
  s.pose = at;
  s.size_m = size;
  return s;
}

Shape cylinder(const Eigen::Isometry3d& at, double r, double h) {
  Shape s;
  s.type = ShapeType::cylinder;
  s.pose = at;
  s.radius_m = r;
  s.height_m = h;
  return s;
}

Scene scene_of(std::vector<Shape> shapes) {
  Scene scene;
  scene.shapes = std::move(shapes);
  return scene;
}

// The methods a caster may be built with here: Embree ray by ray, automatic
// (by fan for a scan this large, when the CPU has the kernels), and the fan forced.
std::vector<CastMethod> methods() {
  std::vector<CastMethod> out{CastMethod::embree, CastMethod::automatic};
  if (fan::kernels_available()) out.push_back(CastMethod::fan);
  return out;
}

std::string name(CastMethod m) {
  return m == CastMethod::embree ? "embree" : m == CastMethod::fan ? "fan" : "automatic";
}

// A scanner3d-like grid (90 x 90 deg, 128 x 128 beams) in the sensor frame.
std::vector<Eigen::Vector3f> scanner_beams() {
  RangeSensorConfig config = *sensor_preset("scanner3d");
  config.cols = config.rows = 128;
  std::vector<Eigen::Vector3f> beams;
  for (const Beam& b : lidar_beams(config)) beams.push_back(beam_direction(b));
  return beams;
}

// Sensor poses around a shape near `centre`: outside at several distances and
// sides, turned so the grid covers the shape, and one inside it.
std::vector<Eigen::Isometry3d> sensor_poses(const Eigen::Vector3d& centre) {
  std::vector<Eigen::Isometry3d> poses;
  const double yaws[] = {0.0, 37.0, 90.0, 151.0, 200.0, 271.0, 333.0};
  for (int i = 0; i < 7; ++i) {
    const double yaw = yaws[i];
    const double distance = 1.6 + 0.7 * i;
    const double height = -0.9 + 0.3 * i;
    const double a = yaw * std::numbers::pi / 180.0;
    const Eigen::Vector3d at = centre - distance * Eigen::Vector3d(std::cos(a), std::sin(a), 0.0) +
                               Eigen::Vector3d(0.0, 0.0, height);
    // Looking back at the centre, rolled a little so no beam grid lines up with a face.
    const Eigen::Vector3d to = centre - at;
    const double pitch = -std::atan2(to.z(), to.head<2>().norm()) * 180.0 / std::numbers::pi;
    poses.push_back(pose(at, {7.0 * i - 10.0, pitch + 3.0, yaw + 2.5}));
  }
  poses.push_back(pose(centre + Eigen::Vector3d(0.05, -0.08, 0.11), {12.0, -20.0, 40.0}));
  return poses;
}

struct MeshAgreement {
  int compared = 0;     // rays that hit in both scenes
  int misses = 0;       // rays that missed in both
  int disagreeing = 0;  // hit in one scene only, or ranges more than 1 mm apart, not excused
  int excused = 0;      // disagreeing where the shapes differ (grazing a faceted silhouette)
  double worst_m = 0.0; // largest range difference over the compared rays not excused
};

// Casts every pose's scan in the mesh scene and the primitive scene; rays for
// which `excuse(pose, direction)` holds may disagree (counted apart).
template <class Excuse>
MeshAgreement compare_scans(const Scene& mesh_scene, const Scene& primitive_scene, CastMethod method,
                        const std::vector<Eigen::Isometry3d>& poses, Excuse excuse) {
  const RayCaster mesh_caster(mesh_scene, method);
  const RayCaster primitive_caster(primitive_scene, CastMethod::embree);
  const std::vector<Eigen::Vector3f> beams = scanner_beams();
  const RayFan fan(beams);
  std::vector<RayHit> a(beams.size()), b(beams.size());
  MeshAgreement out;
  for (const Eigen::Isometry3d& p : poses) {
    mesh_caster.cast(p, fan, kMinRange_m, kMaxRange_m, a);
    primitive_caster.cast(p, fan, kMinRange_m, kMaxRange_m, b);
    for (std::size_t i = 0; i < beams.size(); ++i) {
      const bool hit_a = a[i].shape != RayHit::kNoShape, hit_b = b[i].shape != RayHit::kNoShape;
      if (!hit_a && !hit_b) {
        ++out.misses;
        continue;
      }
      const double diff = hit_a && hit_b ? std::abs(double{a[i].distance_m} - b[i].distance_m)
                                         : std::numeric_limits<double>::infinity();
      if (diff <= kMm) {
        ++out.compared;
        out.worst_m = std::max(out.worst_m, diff);
      } else if (excuse(p, (p.linear() * beams[i].cast<double>()).eval())) {
        ++out.excused;
      } else {
        ++out.disagreeing;
      }
    }
  }
  return out;
}

const auto kNoExcuse = [](const Eigen::Isometry3d&, const Eigen::Vector3d&) { return false; };

TEST(MeshRaycast, UnitCubeMeshGivesTheCuboidsRangesFromEveryPose) {
  const Eigen::Isometry3d at = pose({4.0, -2.0, 1.0});
  const Scene meshes = scene_of({mesh_shape(cuboid_mesh(), at)});
  const Scene primitives = scene_of({cuboid(at, Eigen::Vector3d::Ones())});
  for (const CastMethod method : methods()) {
    SCOPED_TRACE(name(method));
    const MeshAgreement r = compare_scans(meshes, primitives, method, sensor_poses(at.translation()), kNoExcuse);
    EXPECT_EQ(r.disagreeing, 0);
    EXPECT_GT(r.compared, 20000);  // the grid sees the cube from every pose
    EXPECT_GT(r.misses, 20000);    // ... and past it
    EXPECT_LT(r.worst_m, 1e-5);    // both exact: only float rounding of the range apart
  }
}

// A ray grazes the 512-gon's silhouette where it passes the axis at more than
// r cos(pi/512) minus a margin (a side tangent), or crosses a cap's plane in the
// band between the polygon and the circle: there the facets and the cylinder
// may differ by more than a millimetre, legitimately.
bool grazes_cylinder(const Eigen::Isometry3d& cylinder_pose, double r, double h, const Eigen::Isometry3d& sensor,
                     const Eigen::Vector3d& dir_world) {
  const Eigen::Vector3d o = cylinder_pose.inverse() * sensor.translation();
  const Eigen::Vector3d d = cylinder_pose.linear().transpose() * dir_world;
  const double band = 1e-4;
  const Eigen::Vector2d d2 = d.head<2>();
  if (d2.squaredNorm() > 0.0) {
    const double t = -o.head<2>().dot(d2) / d2.squaredNorm();
    if ((o.head<2>() + t * d2).norm() > r - band) return true;
  }
  for (const double z : {-0.5 * h, 0.5 * h}) {
    if (d.z() == 0.0) continue;
    const double t = (z - o.z()) / d.z();
    if (std::abs((o + t * d).head<2>().norm() - r) < band) return true;
  }
  return false;
}

TEST(MeshRaycast, CylinderOf512SegmentsGivesTheCylindersRangesWithinAMillimetre) {
  // The facets lie within r (1 - cos(pi/512)) < 0.01 mm of the cylinder.
  const double r = 0.5, h = 1.0;
  EXPECT_LT(r * (1.0 - std::cos(std::numbers::pi / 512)), 1e-5);
  const Eigen::Isometry3d at = pose({-3.0, 5.0, 0.5});
  const Scene meshes = scene_of({mesh_shape(cylinder_mesh(r, h, 512), at)});
  const Scene primitives = scene_of({cylinder(at, r, h)});
  for (const CastMethod method : methods()) {
    SCOPED_TRACE(name(method));
    const MeshAgreement result = compare_scans(
        meshes, primitives, method, sensor_poses(at.translation()),
        [&](const Eigen::Isometry3d& sensor, const Eigen::Vector3d& d) { return grazes_cylinder(at, r, h, sensor, d); });
    EXPECT_EQ(result.disagreeing, 0);
    EXPECT_GT(result.compared, 15000);
    // Grazing rays are a sliver of the ones that hit: any more is a real difference.
    EXPECT_LE(result.excused, result.compared / 1000);
    EXPECT_LT(result.worst_m, kMm);
  }
}

TEST(MeshRaycast, TurnedAndScaledMeshesMatchTurnedPrimitives) {
  // The unit cube's vertices scaled to 2 x 0.5 x 1.5 m (a file's scale is in
  // vertices_m), and the cylinder's to r 0.8, h 2.4; both turned about every axis.
  const Eigen::Vector3d size(2.0, 0.5, 1.5);
  const Eigen::Isometry3d box_at = pose({2.0, 3.0, 1.0}, {20.0, -35.0, 60.0});
  const Scene box_meshes = scene_of({mesh_shape(cuboid_mesh(size), box_at)});
  const Scene boxes = scene_of({cuboid(box_at, size)});
  const double r = 0.8, h = 2.4;
  const Eigen::Isometry3d cylinder_at = pose({-1.0, 2.0, 0.0}, {-70.0, 25.0, 130.0});
  const Scene cylinder_meshes = scene_of({mesh_shape(cylinder_mesh(r, h, 512), cylinder_at)});
  const Scene cylinders = scene_of({cylinder(cylinder_at, r, h)});
  for (const CastMethod method : methods()) {
    SCOPED_TRACE(name(method));
    const MeshAgreement box = compare_scans(box_meshes, boxes, method, sensor_poses(box_at.translation()), kNoExcuse);
    EXPECT_EQ(box.disagreeing, 0);
    EXPECT_GT(box.compared, 20000);
    EXPECT_LT(box.worst_m, 1e-5);
    const MeshAgreement cyl = compare_scans(
        cylinder_meshes, cylinders, method, sensor_poses(cylinder_at.translation()),
        [&](const Eigen::Isometry3d& sensor, const Eigen::Vector3d& d) {
          return grazes_cylinder(cylinder_at, r, h, sensor, d);
        });
    EXPECT_EQ(cyl.disagreeing, 0);
    EXPECT_GT(cyl.compared, 20000);
    EXPECT_LE(cyl.excused, cyl.compared / 1000);
  }
}

TEST(MeshRaycast, DynamicMeshMovesWithSetPoses) {
  Shape moving = mesh_shape(cuboid_mesh(Eigen::Vector3d(1.0, 2.0, 0.5)), pose({0.0, 0.0, 0.0}));
  moving.is_static = false;
  moving.mass_kg = 3.0;
  const Scene meshes = scene_of({moving});
  const Eigen::Isometry3d moved = pose({5.0, 1.0, 0.7}, {0.0, 15.0, 40.0});
  const Scene primitive_there = scene_of({cuboid(moved, Eigen::Vector3d(1.0, 2.0, 0.5))});
  for (const CastMethod method : methods()) {
    SCOPED_TRACE(name(method));
    RayCaster caster(meshes, method);
    const std::vector<Eigen::Isometry3d> poses{moved};
    caster.set_poses(poses);
    const RayCaster reference(primitive_there, CastMethod::embree);
    const std::vector<Eigen::Vector3f> beams = scanner_beams();
    const RayFan fan(beams);
    std::vector<RayHit> a(beams.size()), b(beams.size());
    int hits = 0;
    for (const Eigen::Isometry3d& sensor : sensor_poses(moved.translation())) {
      caster.cast(sensor, fan, kMinRange_m, kMaxRange_m, a);
      reference.cast(sensor, fan, kMinRange_m, kMaxRange_m, b);
      for (std::size_t i = 0; i < beams.size(); ++i) {
        ASSERT_EQ(a[i].shape == RayHit::kNoShape, b[i].shape == RayHit::kNoShape) << "beam " << i;
        if (b[i].shape == RayHit::kNoShape) continue;
        ++hits;
        EXPECT_EQ(a[i].shape, 0);  // a dynamic shape is reported by its scene index
        ASSERT_NEAR(a[i].distance_m, b[i].distance_m, 1e-5) << "beam " << i;
      }
    }
    EXPECT_GT(hits, 20000);
    // Where it was at t = 0 there is nothing any more.
    const Eigen::Vector3f down(0.0f, 0.0f, -1.0f);
    RayHit hit{};
    caster.cast(Eigen::Vector3d(0.0, 0.0, 3.0), std::span<const Eigen::Vector3f>(&down, 1), 0.0f, 10.0f,
                std::span<RayHit>(&hit, 1));
    EXPECT_EQ(hit.shape, RayHit::kNoShape);
  }
}

// Directions from inside a closed icosphere: random ones, and the ones
// through every vertex and every edge's midpoint, where a ray meets two or
// more triangles on their shared boundary. Not one may get through.
TEST(MeshRaycast, ClosedIcosphereLetsNoRayOutEvenThroughSharedEdgesAndVertices) {
  const double radius = 2.0;
  const auto sphere = icosphere_mesh(radius, 4);  // 5120 triangles
  ASSERT_EQ(sphere->triangles.size(), 5120u);
  const Eigen::Vector3d centre(10.0, -7.0, 3.0);
  const Scene scene = scene_of({mesh_shape(sphere, pose(centre, {10.0, 20.0, 30.0}))});
  const Eigen::Matrix3d turn = pose(centre, {10.0, 20.0, 30.0}).linear();
  std::vector<Eigen::Vector3d> targets;  // world points on the surface
  for (const Eigen::Vector3d& v : sphere->vertices_m) targets.push_back(centre + turn * v);
  for (const auto& t : sphere->triangles) {
    for (int k = 0; k < 3; ++k) {
      targets.push_back(centre + turn * (0.5 * (sphere->vertices_m[t[k]] + sphere->vertices_m[t[(k + 1) % 3]])));
    }
  }
  Rng rng(35);
  std::vector<Eigen::Vector3d> origins{centre};
  for (int i = 0; i < 4; ++i) {
    origins.push_back(centre + Eigen::Vector3d(rng.uniform(-0.9, 0.9), rng.uniform(-0.9, 0.9), rng.uniform(-0.9, 0.9)));
  }
  // The inscribed polyhedron lies between the sphere and a sphere this much smaller.
  const double inner = radius * 0.99;
  for (const CastMethod method : methods()) {
    SCOPED_TRACE(name(method));
    const RayCaster caster(scene, method);
    std::size_t through = 0, cast = 0;
    for (const Eigen::Vector3d& origin : origins) {
      std::vector<Eigen::Vector3f> dirs;
      for (const Eigen::Vector3d& target : targets) dirs.push_back((target - origin).normalized().cast<float>());
      for (int i = 0; i < 50000; ++i) {
        const double z = rng.uniform(-1.0, 1.0), phi = rng.uniform(0.0, 2.0 * std::numbers::pi);
        const double s = std::sqrt(1.0 - z * z);
        dirs.emplace_back(static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)),
                          static_cast<float>(z));
      }
      std::vector<RayHit> hits(dirs.size());
      caster.cast(origin, dirs, 0.0f, 100.0f, hits);
      for (std::size_t i = 0; i < dirs.size(); ++i) {
        ++cast;
        const Eigen::Vector3d end = origin + double{hits[i].distance_m} * dirs[i].cast<double>();
        const double from_centre = (end - centre).norm();
        if (hits[i].shape != 0 || from_centre > radius + 1e-5 || from_centre < inner - 1e-5) ++through;
      }
    }
    EXPECT_EQ(through, 0u) << "of " << cast << " rays";
  }
}

TEST(MeshRaycast, ClosedMeshSeenFromOutsideStopsRaysOnItsNearSideWhicheverWayItIsWound) {
  // Seen from outside its bounds, a closed mesh's faces turned away are
  // skipped by a fan (fan::TriangleSoup::facing). The truth is the sphere the
  // icosphere is inscribed in: a ray missing the sphere misses, one meeting
  // the inner sphere (which the polyhedron holds) stops between the two
  // spheres' near crossings, and a ray aimed at a vertex or an edge's middle
  // on the near side stops on the surface no further than that point.
  const double radius = 2.0, inner = radius * std::cos(0.2);  // the faces' centres lie within 0.2 rad
  const auto outward = icosphere_mesh(radius, 3);
  auto inward = std::make_shared<TriangleMesh>(*outward);
  for (auto& t : inward->triangles) std::swap(t[1], t[2]);
  const Eigen::Vector3d centre(4.0, -3.0, 1.5);
  Rng rng(36);
  for (const auto& mesh : {std::shared_ptr<const TriangleMesh>(outward), std::shared_ptr<const TriangleMesh>(inward)}) {
    const MeshFacing facing = mesh_facing(*mesh);
    ASSERT_FALSE(facing.two_sided);
    EXPECT_EQ(facing.flip[0], mesh.get() == inward.get());
    const Scene scene = scene_of({mesh_shape(mesh, pose(centre, {10.0, 20.0, 30.0}))});
    const Eigen::Matrix3d turn = pose(centre, {10.0, 20.0, 30.0}).linear();
    for (const CastMethod method : methods()) {
      SCOPED_TRACE(name(method) + (mesh.get() == inward.get() ? " inward" : " outward"));
      const RayCaster caster(scene, method);
      int wrong = 0, aimed = 0, met = 0;
      for (int o = 0; o < 6; ++o) {
        // Outside the bounds (a cube of half-size 2 about the centre, turned).
        const Eigen::Vector3d away = Eigen::Vector3d(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0),
                                                     rng.uniform(-1.0, 1.0)).normalized();
        const Eigen::Vector3d origin = centre + (3.6 + o) * away;
        std::vector<Eigen::Vector3f> dirs;
        std::vector<double> target_range;  // for the aimed rays
        const auto aim = [&](const Eigen::Vector3d& local) {
          const Eigen::Vector3d target = centre + turn * local;
          // Well on the near side: 0.3 rad or more from grazing the sphere.
          if ((target - centre).normalized().dot((origin - target).normalized()) < std::sin(0.3)) return;
          dirs.push_back((target - origin).normalized().cast<float>());
          target_range.push_back((target - origin).norm());
        };
        for (const Eigen::Vector3d& v : mesh->vertices_m) aim(v);
        for (const auto& t : mesh->triangles) aim(0.5 * (mesh->vertices_m[t[0]] + mesh->vertices_m[t[1]]));
        const std::size_t aimed_count = dirs.size();
        const Eigen::Vector3d to_centre = (centre - origin).normalized();
        for (int i = 0; i < 20000; ++i) {
          const Eigen::Vector3d d =
              (to_centre + 0.6 * Eigen::Vector3d(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)))
                  .normalized();
          dirs.push_back(d.cast<float>());
        }
        std::vector<RayHit> hits(dirs.size());
        caster.cast(origin, dirs, 0.0f, 100.0f, hits);
        for (std::size_t i = 0; i < dirs.size(); ++i) {
          const Eigen::Vector3d d = dirs[i].cast<double>();
          const bool hit = hits[i].shape == 0;
          const Eigen::Vector3d end = origin + double{hits[i].distance_m} * d;
          const bool on_surface = hit && (end - centre).norm() <= radius + 1e-5 && (end - centre).norm() >= inner - 1e-5;
          if (i < aimed_count) {
            ++aimed;
            wrong += !on_surface || hits[i].distance_m > target_range[i] + 1e-5;
            continue;
          }
          // The near crossing of a sphere of radius r, or NaN when the ray misses it.
          const auto crossing = [&](double r) {
            const double b = d.dot(origin - centre), c = (origin - centre).squaredNorm() - r * r;
            return b * b - c >= 0.0 ? -b - std::sqrt(b * b - c) : std::numeric_limits<double>::quiet_NaN();
          };
          const double outer_t = crossing(radius), inner_t = crossing(inner);
          if (std::isnan(outer_t)) {
            wrong += hit;
          } else if (!std::isnan(inner_t)) {
            ++met;
            wrong += !on_surface || hits[i].distance_m < outer_t - 1e-5 || hits[i].distance_m > inner_t + 1e-5;
          } else {
            wrong += hit && !on_surface;  // between the spheres: a hit or a miss, on the surface
          }
        }
      }
      EXPECT_EQ(wrong, 0) << "of " << aimed << " aimed rays and 120000 others";
      EXPECT_GT(aimed, 1000);
      EXPECT_GT(met, 30000);
    }
  }
}

TEST(MeshRaycast, ManyMeshesAroundTheSensorGiveThePrimitivesRanges) {
  // 36 cubes sharing one mesh on a ring and a grid around the sensors: more
  // than a fan takes (automatic goes ray by ray), and the forced fan still agrees.
  std::vector<Shape> meshes, boxes;
  const auto cube = cuboid_mesh(Eigen::Vector3d(0.8, 0.6, 1.4));
  for (int i = 0; i < 36; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 36.0;
    const Eigen::Isometry3d at = pose({(3.0 + 0.1 * (i % 5)) * std::cos(a), (3.0 + 0.1 * (i % 5)) * std::sin(a),
                                       0.3 * (i % 3) - 0.3},
                                      {5.0 * i, 0.0, 10.0 * i});
    meshes.push_back(mesh_shape(cube, at));
    boxes.push_back(cuboid(at, Eigen::Vector3d(0.8, 0.6, 1.4)));
  }
  const Scene mesh_scene = scene_of(meshes), box_scene = scene_of(boxes);
  std::vector<Eigen::Isometry3d> poses;
  for (int k = 0; k < 6; ++k) poses.push_back(pose({0.2 * k - 0.5, 0.1 * k, 0.1}, {0.0, 10.0 * k - 20.0, 60.0 * k}));
  for (const CastMethod method : methods()) {
    SCOPED_TRACE(name(method));
    const MeshAgreement r = compare_scans(mesh_scene, box_scene, method, poses, kNoExcuse);
    EXPECT_EQ(r.disagreeing, 0);
    EXPECT_GT(r.compared, 20000);
    // The boxes' cast (Embree) turns each float beam into the world in float;
    // a fan turns the scene into the sensor frame in double instead. The
    // directions thus differ by a float rounding (~1e-7 rad), which moves a
    // hit 3 m away at a grazing angle a by 3e-7 m / sin(a): tens of
    // micrometres at one degree.
    EXPECT_LT(r.worst_m, method == CastMethod::embree ? 1e-5 : 1e-4);
  }
}

TEST(MeshRaycast, OpenMeshIsSeenFromBothSides) {
  // One square of two triangles, normal +z: rays from above and below both hit.
  TriangleMesh square;
  square.vertices_m = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  square.triangles = {{0, 1, 2}, {0, 2, 3}};
  const auto mesh = test_support::finished(std::move(square), false);
  const Scene scene = scene_of({mesh_shape(mesh, pose({0.0, 0.0, 2.0}))});
  for (const CastMethod method : methods()) {
    SCOPED_TRACE(name(method));
    const RayCaster caster(scene, method);
    const std::vector<Eigen::Vector3f> dirs{{0.0f, 0.0f, -1.0f}, {0.0f, 0.0f, 1.0f}, {0.6f, 0.0f, -0.8f}};
    const std::vector<Eigen::Vector3d> origins{{0.3, 0.2, 5.0}, {0.3, 0.2, -1.0}, {-1.5, 0.0, 4.0}};
    const double expected[] = {3.0, 3.0, 2.5};
    for (std::size_t i = 0; i < dirs.size(); ++i) {
      RayHit hit{};
      caster.cast(origins[i], std::span<const Eigen::Vector3f>(&dirs[i], 1), 0.0f, 100.0f, std::span<RayHit>(&hit, 1));
      EXPECT_EQ(hit.shape, 0) << i;
      EXPECT_NEAR(hit.distance_m, expected[i], 1e-6) << i;
    }
    // Past the edge: nothing.
    const Eigen::Vector3f down(0.0f, 0.0f, -1.0f);
    RayHit hit{};
    caster.cast(Eigen::Vector3d(1.01, 0.0, 5.0), std::span<const Eigen::Vector3f>(&down, 1), 0.0f, 100.0f,
                std::span<RayHit>(&hit, 1));
    EXPECT_EQ(hit.shape, RayHit::kNoShape);
  }
}

TEST(MeshRaycast, MinimumRangeSkipsTheNearSideOfAMesh) {
  // From outside, with a minimum range past the near face, the far face is reported (two-sided, as for primitives).
  const Scene meshes = scene_of({mesh_shape(cuboid_mesh(), pose({3.0, 0.0, 0.0}))});
  const Scene boxes = scene_of({cuboid(pose({3.0, 0.0, 0.0}), Eigen::Vector3d::Ones())});
  for (const CastMethod method : methods()) {
    SCOPED_TRACE(name(method));
    const RayCaster a(meshes, method), b(boxes, method);
    const Eigen::Vector3f dir = Eigen::Vector3f(1.0f, 0.05f, 0.02f).normalized();
    RayHit ha{}, hb{};
    a.cast(Eigen::Vector3d::Zero(), std::span<const Eigen::Vector3f>(&dir, 1), 3.0f, 10.0f, std::span<RayHit>(&ha, 1));
    b.cast(Eigen::Vector3d::Zero(), std::span<const Eigen::Vector3f>(&dir, 1), 3.0f, 10.0f, std::span<RayHit>(&hb, 1));
    EXPECT_EQ(ha.shape, 0);
    EXPECT_NEAR(ha.distance_m, hb.distance_m, 1e-5);
    EXPECT_GT(ha.distance_m, 3.4f);
  }
}

// The depth camera renders the mesh cube as it renders the cuboid primitive.
TEST(MeshRaycast, DepthCameraSeesTheMeshCubeAsThePrimitive) {
  const Eigen::Isometry3d at = pose({3.0, 0.4, -0.2}, {0.0, 0.0, 25.0});
  const Scene meshes = scene_of({mesh_shape(cuboid_mesh(Eigen::Vector3d(1.0, 1.5, 1.2)), at)});
  const Scene boxes = scene_of({cuboid(at, Eigen::Vector3d(1.0, 1.5, 1.2))});
  SensorDef def;
  def.alias = "camera";
  def.range = *sensor_preset("scanner3d");
  def.range.kind = RangeSensorKind::depth_camera;
  def.range.cols = def.range.rows = 96;
  std::unique_ptr<RangeSensor> mesh_camera, box_camera;
  try {
    mesh_camera = make_depth_camera(meshes, def);
    box_camera = make_depth_camera(boxes, def);
  } catch (const std::runtime_error& e) {
    GTEST_SKIP() << "no OSMesa context: " << e.what();
  }
  const Eigen::Isometry3d sensor = pose({0.0, 0.0, 0.3}, {3.0, 8.0, -4.0});
  RangeScan a, b;
  mesh_camera->scan(sensor, 0.0, {}, a);
  box_camera->scan(sensor, 0.0, {}, b);
  ASSERT_EQ(a.ranges_m.size(), b.ranges_m.size());
  int hits = 0, different = 0;
  for (std::size_t i = 0; i < a.ranges_m.size(); ++i) {
    if (a.hits[i] != b.hits[i]) {
      ++different;  // a pixel on the silhouette may go either way
      continue;
    }
    if (!a.hits[i]) continue;
    ++hits;
    EXPECT_NEAR(a.ranges_m[i], b.ranges_m[i], 3e-3) << "pixel " << i;
  }
  EXPECT_GT(hits, 500);
  EXPECT_LE(different, hits / 100);
}

}  // namespace
}  // namespace campo
