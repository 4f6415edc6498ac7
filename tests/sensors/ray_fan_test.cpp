#include "sensors/ray_fan.hpp"

#include <embree3/rtcore.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <set>
#include <utility>
#include <vector>

#include "campo/random.hpp"
#include "campo/scene_loader.hpp"
#include "scene/scene_mesh.hpp"
#include "sensors/lidar.hpp"
#include "sensors/raycaster.hpp"
#include "tests/sensors/seam_points.hpp"

namespace campo {
namespace {

std::vector<Eigen::Vector3f> grid_beams(int cols, int rows, double fov_h_deg, double fov_v_deg) {
  RangeSensorConfig config;
  config.cols = cols;
  config.rows = rows;
  config.fov_h_deg = fov_h_deg;
  config.fov_v_deg = fov_v_deg;
  std::vector<Eigen::Vector3f> beams;
  for (const Beam& b : lidar_beams(config)) beams.push_back(beam_direction(b));
  return beams;
}

Eigen::Vector3f random_unit_float(Rng& rng) {
  const double z = rng.uniform(-1.0, 1.0);
  const double phi = rng.uniform(0.0, 2.0 * std::numbers::pi);
  const double s = std::sqrt(1.0 - z * z);
  return Eigen::Vector3d(s * std::cos(phi), s * std::sin(phi), z).cast<float>();
}

TEST(RayFan, SortsEveryDirectionIntoTheBinOfItsFace) {
  Rng rng(5);
  std::vector<Eigen::Vector3f> dirs = grid_beams(64, 48, 120.0, 90.0);
  for (int i = 0; i < 3000; ++i) dirs.push_back(random_unit_float(rng));
  dirs.push_back(Eigen::Vector3f::UnitX());  // exactly on a face centre, and one of each sign
  dirs.push_back(-Eigen::Vector3f::UnitZ());
  const RayFan fan(dirs);
  ASSERT_EQ(fan.size(), dirs.size());
  const fan::Rays rays = fan.rays();
  std::set<std::uint32_t> seen(fan.order().begin(), fan.order().end());
  EXPECT_EQ(seen.size(), dirs.size());  // a permutation
  std::vector<int> slot_bin(fan.size(), -1);
  for (int f = 0; f < fan::kFaces; ++f) {
    const int g = rays.grid[f];
    for (int b = 0; b < g * g; ++b) {
      for (std::uint32_t k = rays.bin_start[rays.first_bin[f] + b]; k < rays.bin_start[rays.first_bin[f] + b + 1]; ++k) {
        slot_bin[k] = static_cast<int>(rays.first_bin[f]) + b;
      }
    }
  }
  for (std::size_t k = 0; k < fan.size(); ++k) {
    const Eigen::Vector3f& d = dirs[fan.order()[k]];
    ASSERT_EQ(Eigen::Vector3f(rays.x[k], rays.y[k], rays.z[k]), d);
    const int f = RayFan::face_of(d);
    const Eigen::Vector2f uv = RayFan::face_coordinates(d, f);
    ASSERT_LE(uv.cwiseAbs().maxCoeff(), 1.0f);
    // The face's largest component is the direction's largest.
    EXPECT_EQ(std::abs(d[f / 2]), d.cwiseAbs().maxCoeff());
    const int g = rays.grid[f];
    ASSERT_GT(g, 0);
    const int i = std::min(g - 1, static_cast<int>((uv.x() + 1.0f) * 0.5f * g));
    const int j = std::min(g - 1, static_cast<int>((uv.y() + 1.0f) * 0.5f * g));
    EXPECT_EQ(slot_bin[k], static_cast<int>(rays.first_bin[f]) + j * g + i) << k;
  }
}

TEST(RayFan, FitsItsBinsToHowTheRaysSpread) {
  // A 256 x 256 scan fills its faces densely: the finest grid. A planar scan
  // of 181 beams is a line: coarse bins, still several rays each.
  const RayFan scan(grid_beams(256, 256, 90.0, 90.0));
  EXPECT_EQ(scan.grid(0), 64);
  std::vector<Eigen::Vector3f> line;
  for (const Beam& b : lidar_beams(*sensor_preset("planar180"))) line.push_back(beam_direction(b));
  const RayFan planar(line);
  for (int f = 0; f < fan::kFaces; ++f) EXPECT_LE(planar.grid(f), 16) << f;
  EXPECT_THROW(RayFan(std::vector<Eigen::Vector3f>{Eigen::Vector3f::Zero()}), std::invalid_argument);
  EXPECT_THROW(RayFan(std::vector<Eigen::Vector3f>{Eigen::Vector3f(2.0f, 0.0f, 0.0f)}), std::invalid_argument);
}

// Casts `beams` from `pose` with a caster of each method; returns how many
// rays disagree (hit or miss, shape, or distance by more than 1 mm) and
// counts the hits.
int disagreements(const RayCaster& embree, const RayCaster& fan_caster, const Eigen::Isometry3d& pose,
                  const RayFan& fan, float min_range, float max_range, int& hits) {
  std::vector<RayHit> a(fan.size()), b(fan.size());
  embree.cast(pose, fan, min_range, max_range, a);
  fan_caster.cast(pose, fan, min_range, max_range, b);
  int differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    hits += a[i].shape != RayHit::kNoShape;
    const bool same = a[i].shape == b[i].shape &&
                      (a[i].shape == RayHit::kNoShape || std::abs(a[i].distance_m - b[i].distance_m) <= 1e-3f);
    differ += !same;
  }
  return differ;
}

// The second method: on the scenes of the peer benchmark, a scanner's scans
// from many poses (turned, pitched, rolled, over the terrain and among the
// trees, rows and the walker) agree ray for ray with Embree's; every third
// scan covers the whole sphere, so every cube face is used and the cells
// under the sensor cross the faces' planes.
TEST(FanCast, AgreesWithEmbreeRayByRayOnTheBenchmarkScenes) {
  Rng rng(17);
  const RayFan scanner(grid_beams(160, 120, 100.0, 80.0));
  const RayFan sphere(grid_beams(160, 120, 360.0, 180.0));
  for (const char* name : {"scenes/trees_rolling_terrain.json", "scenes/vineyard.json"}) {
    const Scene scene = load_scene(name);
    RayCaster embree(scene, CastMethod::embree);
    RayCaster fan_caster(scene, CastMethod::fan);
    const auto bodies = scripted_poses(scene, 70.0);  // the vineyard's walker mid-row
    embree.set_poses(bodies);
    fan_caster.set_poses(bodies);
    int hits = 0, differ = 0;
    for (int i = 0; i < 24; ++i) {
      const Eigen::Vector3d start = scene.vehicles.front().pose.translation();
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.translation() = start + Eigen::Vector3d(rng.uniform(-6.0, 6.0), rng.uniform(-6.0, 6.0), rng.uniform(-0.2, 2.0));
      pose.linear() = (Eigen::AngleAxisd(rng.uniform(-3.2, 3.2), Eigen::Vector3d::UnitZ()) *
                       Eigen::AngleAxisd(rng.uniform(-0.8, 0.8), Eigen::Vector3d::UnitY()) *
                       Eigen::AngleAxisd(rng.uniform(-0.3, 0.3), Eigen::Vector3d::UnitX()))
                          .toRotationMatrix();
      differ += disagreements(embree, fan_caster, pose, i % 3 == 0 ? sphere : scanner, 0.05f, 15.0f, hits);
    }
    EXPECT_GT(hits, 24 * 160 * 120 / 4) << name;
    EXPECT_EQ(differ, 0) << name << ": " << differ << " of " << hits << " hits";
  }
}

// Centimetre-sized shapes of every kind, turned every way, close to the
// sensor, in front of a wall: the float solvers (with their rim slack) agree
// with the double ones ray for ray to 0.1 mm over 120,000 rays in all
// directions, rims and silhouettes included.
TEST(FanCast, AgreesWithEmbreeOnSmallShapesCloseToTheSensor) {
  Rng rng(29);
  Scene scene;
  const ShapeType kinds[] = {ShapeType::cuboid, ShapeType::cylinder, ShapeType::cone, ShapeType::sphere};
  for (int i = 0; i < 60; ++i) {
    Shape s;
    s.type = kinds[i % 4];
    const Eigen::Vector3d at = random_unit_float(rng).cast<double>() * rng.uniform(0.15, 1.2);
    s.pose = Eigen::Translation3d(at) * Eigen::AngleAxisd(rng.uniform(0.0, 3.0), random_unit_float(rng).cast<double>());
    s.size_m = Eigen::Vector3d(rng.uniform(0.01, 0.06), rng.uniform(0.01, 0.06), rng.uniform(0.01, 0.06));
    s.radius_m = rng.uniform(0.005, 0.03);
    s.height_m = rng.uniform(0.01, 0.06);
    scene.shapes.push_back(s);
  }
  Shape wall;
  wall.type = ShapeType::cuboid;
  wall.pose = Eigen::Isometry3d(Eigen::Translation3d(3.0, 0.0, 0.0));
  wall.size_m = Eigen::Vector3d(0.2, 8.0, 8.0);
  scene.shapes.push_back(wall);
  const RayCaster embree(scene, CastMethod::embree);
  const RayCaster fan_caster(scene, CastMethod::fan);
  std::vector<Eigen::Vector3f> dirs;
  for (int i = 0; i < 120000; ++i) dirs.push_back(random_unit_float(rng));
  const RayFan fan(dirs);
  std::vector<RayHit> a(fan.size()), b(fan.size());
  const Eigen::Isometry3d at_origin = Eigen::Isometry3d::Identity();
  embree.cast(at_origin, fan, 0.0f, 20.0f, a);
  fan_caster.cast(at_origin, fan, 0.0f, 20.0f, b);
  int small_hits = 0, differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    small_hits += a[i].shape >= 0 && a[i].shape < 60;
    differ += a[i].shape != b[i].shape ||
              (a[i].shape != RayHit::kNoShape && std::abs(a[i].distance_m - b[i].distance_m) > 1e-4f);
  }
  EXPECT_GT(small_hits, 1000);
  EXPECT_EQ(differ, 0);
}

// Long shapes (rows of canopy, fences, poles) are projected piece by piece
// along their length, and every surface outside the fan's cone is skipped:
// boxes, cylinders and cones up to 80 m long, turned every way, reaching in
// and out of range, over a ground plane the sensor sits 0.6 m above (whose
// rays are screened in float first), agree ray for ray with Embree's cast
// from many poses and fans (narrow, a scanner's, the whole sphere).
TEST(FanCast, AgreesWithEmbreeOnLongShapesAndTheGround) {
  Rng rng(41);
  Scene scene;
  Shape ground;
  ground.type = ShapeType::plane;
  scene.shapes.push_back(ground);
  const ShapeType kinds[] = {ShapeType::cuboid, ShapeType::cylinder, ShapeType::cone};
  for (int i = 0; i < 45; ++i) {
    Shape s;
    s.type = kinds[i % 3];
    const double length = rng.uniform(2.0, 80.0);
    const Eigen::Vector3d at(rng.uniform(-15.0, 15.0), rng.uniform(-15.0, 15.0), rng.uniform(0.0, 2.0));
    s.pose = Eigen::Translation3d(at) * Eigen::AngleAxisd(rng.uniform(0.0, 3.2), random_unit_float(rng).cast<double>());
    s.size_m = Eigen::Vector3d(rng.uniform(0.05, 1.0), rng.uniform(0.05, 1.5), length);
    s.radius_m = rng.uniform(0.03, 0.6);
    s.height_m = length;
    scene.shapes.push_back(s);
  }
  const RayCaster embree(scene, CastMethod::embree);
  const RayCaster fan_caster(scene, CastMethod::fan);
  const RayFan narrow(grid_beams(64, 48, 20.0, 15.0));
  const RayFan scanner(grid_beams(160, 120, 90.0, 90.0));
  const RayFan sphere(grid_beams(160, 90, 360.0, 179.0));
  int hits = 0, shape_hits = 0, differ = 0;
  for (int i = 0; i < 30; ++i) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(rng.uniform(-8.0, 8.0), rng.uniform(-8.0, 8.0), 0.6);
    pose.linear() = (Eigen::AngleAxisd(rng.uniform(-3.2, 3.2), Eigen::Vector3d::UnitZ()) *
                     Eigen::AngleAxisd(rng.uniform(-0.6, 0.6), Eigen::Vector3d::UnitY()))
                        .toRotationMatrix();
    const RayFan& fan = i % 3 == 0 ? narrow : i % 3 == 1 ? scanner : sphere;
    std::vector<RayHit> a(fan.size()), b(fan.size());
    embree.cast(pose, fan, 0.1f, 10.0f, a);
    fan_caster.cast(pose, fan, 0.1f, 10.0f, b);
    for (std::size_t k = 0; k < a.size(); ++k) {
      hits += a[k].shape != RayHit::kNoShape;
      shape_hits += a[k].shape > 0;
      differ += a[k].shape != b[k].shape ||
                (a[k].shape != RayHit::kNoShape && std::abs(a[k].distance_m - b[k].distance_m) > 1e-3f);
    }
  }
  EXPECT_GT(shape_hits, 20000);
  EXPECT_GT(hits, shape_hits + 20000);
  EXPECT_EQ(differ, 0) << differ << " of " << hits << " hits";
}

// The cone a fan keeps around its rays holds every one of them: a surface
// outside it is skipped unprojected.
TEST(RayFan, ItsConeHoldsEveryRay) {
  for (const auto& [fov_h, fov_v] : {std::pair{90.0, 90.0}, std::pair{20.0, 5.0}, std::pair{180.0, 0.0},
                                     std::pair{270.0, 60.0}, std::pair{360.0, 179.0}}) {
    const std::vector<Eigen::Vector3f> beams = grid_beams(97, fov_v > 0.0 ? 41 : 1, fov_h, fov_v);
    const RayFan fan(beams);
    const fan::Rays rays = fan.rays();
    const Eigen::Vector3f axis(rays.cone_axis[0], rays.cone_axis[1], rays.cone_axis[2]);
    EXPECT_NEAR(rays.cone_cos * rays.cone_cos + rays.cone_sin * rays.cone_sin, 1.0f, 1e-5f);
    for (const Eigen::Vector3f& d : beams) EXPECT_GE(axis.dot(d), rays.cone_cos) << fov_h << " x " << fov_v;
    if (fov_h < 180.0) {
      EXPECT_GT(rays.cone_cos, 0.0f) << fov_h << " x " << fov_v << ": a narrow fan culls";
    }
    if (fov_h == 360.0) {
      EXPECT_EQ(rays.cone_cos, -1.0f) << "the whole sphere culls nothing";
    }
  }
}

// Embree's own triangles of a scene, cast one ray at a time.
class EmbreeTriangles {
 public:
  EmbreeTriangles(const Scene& scene, bool robust) : device_(rtcNewDevice("threads=1")) {
    const SceneMesh mesh = build_scene_mesh(scene);
    scene_ = rtcNewScene(device_);
    if (robust) rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), mesh.positions.size()));
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) std::memcpy(vertices + 3 * i, mesh.positions[i].data(), 12);
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), mesh.indices.size() / 3));
    std::memcpy(indices, mesh.indices.data(), mesh.indices.size() * sizeof(unsigned));
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene_);
  }
  ~EmbreeTriangles() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  bool hits(const Eigen::Vector3d& origin, const Eigen::Vector3f& d, float max_range) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit r{};
    const Eigen::Vector3f o = origin.cast<float>();
    r.ray = {o.x(), o.y(), o.z(), 0.0f, d.x(), d.y(), d.z(), 0.0f, max_range, 0xffffffffu, 0, 0};
    r.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context, &r);
    return r.hit.geomID != RTC_INVALID_GEOMETRY_ID;
  }

 private:
  RTCDevice device_;
  RTCScene scene_ = nullptr;
};

// Watertightness: from each origin one fan of rays aimed exactly at every
// interior vertex, edge midpoint and cell centre of a bumpy heightfield (the
// points where triangles meet); none may slip through, and each hits where it
// was aimed. The same rays do slip between Embree's own triangles, so they
// do probe the cracks.
TEST(FanCast, HeightfieldLetsNoRayThroughItsSharedEdgesAndVertices) {
  Rng bumps(21);
  auto grid = std::make_shared<HeightGrid>();
  grid->cols = grid->rows = 49;
  grid->spacing_x_m = grid->spacing_y_m = 0.25;
  for (int i = 0; i < grid->cols * grid->rows; ++i) grid->heights_m.push_back(bumps.uniform(-0.1, 0.1));
  Scene scene;
  Shape hf;
  hf.type = ShapeType::heightfield;
  hf.terrain = grid;
  hf.pose = Eigen::Translation3d(0.3, -0.2, 0.0) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ());
  scene.shapes.push_back(hf);
  const RayCaster caster(scene, CastMethod::fan);
  const EmbreeTriangles triangles(scene, false);
  const HeightGrid& g = *grid;
  int rays = 0, embree_slips = 0;
  for (const Eigen::Vector3d origin : {Eigen::Vector3d(0.4, 0.1, 12.0), Eigen::Vector3d(1.3, -0.7, 30.0),
                                       Eigen::Vector3d(-2.1, 3.3, 25.0), Eigen::Vector3d(0.05, 0.05, 8.0)}) {
    std::vector<Eigen::Vector3f> dirs;
    std::vector<double> expected;
    for (const Eigen::Vector3d& seam : test_support::seam_points(g)) {
      const Eigen::Vector3d target = hf.pose * seam;
      dirs.push_back((target - origin).normalized().cast<float>());
      expected.push_back((target - origin).norm());
    }
    const RayFan fan(dirs);
    std::vector<RayHit> hits(fan.size());
    caster.cast(Eigen::Isometry3d(Eigen::Translation3d(origin)), fan, 0.0f, 60.0f, hits);
    for (std::size_t i = 0; i < hits.size(); ++i, ++rays) {
      ASSERT_EQ(hits[i].shape, 0) << "ray " << i << " from " << origin.transpose() << " slipped through";
      ASSERT_NEAR(hits[i].distance_m, expected[i], 1e-3) << "ray " << i;
      embree_slips += !triangles.hits(origin, dirs[i], 60.0f);
    }
  }
  EXPECT_EQ(rays, 4 * 47 * 47 * 4);
  EXPECT_GT(embree_slips, 0) << "the aimed rays never found a crack in Embree's triangles";
}

// Any ray, not only aimed ones: rays of dense fans from low over rolling
// terrain, grazing its ridges, never travel below the surface before their
// hit (checked on the ray every 2 cm against height_at), and where they hit
// they are on it.
TEST(FanCast, RaysOverRidgesNeverPassBelowTheSurface) {
  Scene scene = load_scene("scenes/trees_rolling_terrain.json");
  std::erase_if(scene.shapes, [](const Shape& s) { return s.type != ShapeType::heightfield; });
  const Shape& hf = scene.shapes.front();
  const RayCaster caster(scene, CastMethod::fan);
  const RayFan fan(grid_beams(96, 48, 360.0, 30.0));
  Rng rng(3);
  int checked = 0;
  for (int n = 0; n < 4; ++n) {
    const Eigen::Vector3d xy(rng.uniform(-20.0, 20.0), rng.uniform(-20.0, 20.0), 0.0);
    const Eigen::Vector3d local = hf.pose.inverse() * xy;
    const Eigen::Vector3d origin = xy + Eigen::Vector3d(0, 0, *hf.terrain->height_at(local.x(), local.y()) + 0.3);
    const Eigen::Isometry3d pose(Eigen::Translation3d(origin) * Eigen::AngleAxisd(rng.uniform(0.0, 6.0), Eigen::Vector3d::UnitZ()));
    std::vector<RayHit> hits(fan.size());
    caster.cast(pose, fan, 0.0f, 15.0f, hits);
    const fan::Rays rays = fan.rays();
    for (std::size_t k = 0; k < fan.size(); ++k) {
      const std::uint32_t i = fan.order()[k];
      const Eigen::Vector3d d = pose.linear() * Eigen::Vector3d(rays.x[k], rays.y[k], rays.z[k]);
      const double end = hits[i].shape == RayHit::kNoShape ? 15.0 : hits[i].distance_m;
      for (double t = 0.0; t < end - 1e-3; t += 0.02) {
        const Eigen::Vector3d p = hf.pose.inverse() * (origin + t * d);
        const auto h = hf.terrain->height_at(p.x(), p.y());
        ASSERT_TRUE(!h || p.z() >= *h - 1e-4) << "ray " << i << " below the surface at t = " << t << " of " << end;
      }
      if (hits[i].shape != RayHit::kNoShape) {
        const Eigen::Vector3d p = hf.pose.inverse() * (origin + end * d);
        ASSERT_NEAR(p.z(), *hf.terrain->height_at(p.x(), p.y()), 1e-3) << "ray " << i;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 4 * 96 * 48 / 3);
}

}  // namespace
}  // namespace campo
