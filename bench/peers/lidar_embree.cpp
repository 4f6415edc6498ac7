// campo's LIDAR against Embree's own triangles cast as a stream, and against a software
// rasteriser (docs/PERFORMANCE.md, "Peers" and "LIDAR against a rasteriser"): scanner3d
// scans (256 x 256 beams, 90 x 90 deg, 10 m) from each scene's vehicle, turned 0.05 rad per
// scan, one thread. campo casts them as a Lidar does: the beams' RayFan cast from each
// scan's pose (analytic primitives, the heightfield's triangles with watertight edge
// tests). Embree casts the same rays with rtcIntersect1M (coherent) against the same scene
// as Embree triangles (build_scene_mesh: the heightfield exactly as Bullet triangulates it,
// round shapes tessellated with 64 segments, meshes as their triangles), high-quality BVH,
// once with RTC_SCENE_FLAG_ROBUST and once without. The rasteriser (lidar_raster.hpp) draws
// the same triangles with OSMesa on one thread into a depth buffer of the scan's resolution
// and field of view, one pixel per ray, and reads the ranges back; its agreement with campo
// is checked ray for ray by casting the pixels' own rays with campo (untimed). Repetitions
// interleave in one process; the figure is rays per second, median of the repetitions.
// Scenes: trees_rolling_terrain, vineyard, trees_rolling_terrain's terrain alone, then every
// other bundled scene (scenes/*.json, by name), each from its first vehicle's start.
//
//   build/campo_peer_lidar [--scans N] [--repetitions K] [--json]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <embree3/rtcore.h>

#include "bench/peers/lidar_raster.hpp"
#include "bench/peers/peer_record.hpp"
#include "campo/scene_loader.hpp"
#include "scene/scene_mesh.hpp"
#include "sensors/lidar.hpp"
#include "sensors/ray_fan.hpp"
#include "sensors/raycaster.hpp"

namespace campo {
namespace {

using Clock = std::chrono::steady_clock;
constexpr float kMinRange_m = 0.1f, kMaxRange_m = 10.0f;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// The scans' rays: the beams in the sensor frame, and each scan's pose with
// its origin and world directions.
struct Scans {
  std::vector<Eigen::Vector3f> beams;
  std::vector<Eigen::Isometry3d> poses;
  std::vector<Eigen::Vector3d> origins;
  std::vector<std::vector<Eigen::Vector3f>> directions;
};

Scans scanner3d_scans(const Scene& scene, int count) {
  RangeSensorConfig config = *sensor_preset("scanner3d");
  config.cols = config.rows = 256;
  const std::vector<Beam> beams = lidar_beams(config);
  const Eigen::Isometry3d mount = scene.vehicles.front().pose * to_isometry(config.mount);
  Scans scans;
  for (const Beam& b : beams) scans.beams.push_back(beam_direction(b));
  for (int i = 0; i < count; ++i) {
    Eigen::Isometry3d pose = mount;
    pose.linear() = Eigen::AngleAxisd(0.05 * i, Eigen::Vector3d::UnitZ()) * mount.linear();
    scans.poses.push_back(pose);
    scans.origins.push_back(pose.translation());
    std::vector<Eigen::Vector3f> world;
    const Eigen::Matrix3f rotation = pose.linear().cast<float>();
    for (const Beam& b : beams) world.push_back(rotation * beam_direction(b));
    scans.directions.push_back(std::move(world));
  }
  return scans;
}

// campo's LIDAR path: the beams binned once (Lidar keeps a RayFan), each scan
// cast from its pose.
double campo_rate(const Scene& scene, const Scans& scans, std::size_t& hits) {
  const RayCaster caster(scene);
  const RayFan fan(scans.beams);
  std::vector<RayHit> out(scans.beams.size());
  hits = 0;
  const auto start = Clock::now();
  for (std::size_t s = 0; s < scans.poses.size(); ++s) {
    caster.cast(scans.poses[s], fan, kMinRange_m, kMaxRange_m, out);
    for (const RayHit& h : out) hits += h.shape != RayHit::kNoShape;
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return static_cast<double>(scans.origins.size() * out.size()) / seconds;
}

// Embree's triangles of `scene`, cast as a coherent stream.
class EmbreeTriangles {
 public:
  // `robust`: RTC_SCENE_FLAG_ROBUST (Embree's traversal and triangle test
  // avoid some optimisations so fewer rays slip through shared edges).
  EmbreeTriangles(const Scene& scene, bool robust) : device_(rtcNewDevice("threads=1")) {
    const SceneMesh mesh = build_scene_mesh(scene);
    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                 RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                                 mesh.positions.size()));
    // The static shapes in the world frame, mesh shapes as their own triangles (build_scene_mesh), and the moving
    // bodies (a vineyard's walker) where they are at t = 0, as campo's RayCaster places them when it is built.
    const std::vector<Eigen::Isometry3d> poses = scripted_poses(scene, 0.0);
    std::vector<int> body_of(mesh.positions.size(), -1);
    for (std::size_t b = 0; b < mesh.moving_parts.size(); ++b) {
      const MeshPart& part = mesh.moving_parts[b];
      for (std::uint32_t i = 0; i < part.index_count; ++i) body_of[mesh.indices[part.first_index + i]] = static_cast<int>(b);
    }
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      const Eigen::Vector3f p = body_of[i] < 0 ? mesh.positions[i]
                                               : (poses[static_cast<std::size_t>(body_of[i])].cast<float>() * mesh.positions[i]);
      std::memcpy(vertices + 3 * i, p.data(), 12);
    }
    std::size_t triangles = 0;
    for (const auto* parts : {&mesh.parts, &mesh.moving_parts}) {
      for (const MeshPart& part : *parts) triangles += part.index_count / 3;
    }
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                                   RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangles));
    std::size_t k = 0;
    for (const auto* parts : {&mesh.parts, &mesh.moving_parts}) {
      for (const MeshPart& part : *parts) {
        for (std::uint32_t i = 0; i < part.index_count; ++i) indices[k++] = mesh.indices[part.first_index + i];
      }
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene_);
    triangles_ = triangles;
  }
  ~EmbreeTriangles() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  std::size_t triangles() const { return triangles_; }

  double rate(const Scans& scans, std::size_t& hits) const {
    std::vector<RTCRayHit> rays(scans.directions.front().size());
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    hits = 0;
    const auto start = Clock::now();
    for (std::size_t s = 0; s < scans.origins.size(); ++s) {
      const Eigen::Vector3f o = scans.origins[s].cast<float>();
      for (std::size_t i = 0; i < rays.size(); ++i) {
        RTCRayHit& r = rays[i];
        const Eigen::Vector3f& d = scans.directions[s][i];
        r.ray = {o.x(), o.y(), o.z(), kMinRange_m, d.x(), d.y(), d.z(), 0.0f, kMaxRange_m, 0xffffffffu, 0, 0};
        r.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect1M(scene_, &context, rays.data(), static_cast<unsigned>(rays.size()), sizeof(RTCRayHit));
      for (const RTCRayHit& r : rays) hits += r.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return static_cast<double>(scans.origins.size() * rays.size()) / seconds;
  }

 private:
  RTCDevice device_;
  RTCScene scene_ = nullptr;
  std::size_t triangles_ = 0;
};

std::string embree_name(std::size_t triangles, bool robust) {
  return "Embree " + std::to_string(RTC_VERSION_MAJOR) + "." + std::to_string(RTC_VERSION_MINOR) + "." +
         std::to_string(RTC_VERSION_PATCH) + " triangles (" + std::to_string(triangles) +
         "), rtcIntersect1M coherent, " + (robust ? "robust" : "not robust");
}

// The rasteriser's view of a scan: its resolution and field of view, the
// scan's range (docs/PERFORMANCE.md, "LIDAR against a rasteriser").
peers::RasterView raster_view() {
  const RangeSensorConfig config = *sensor_preset("scanner3d");
  constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
  peers::RasterView view;
  view.width_px = view.height_px = 256;
  view.half_width = std::tan(0.5 * config.fov_h_deg * kDegToRad);
  view.half_height = std::tan(0.5 * config.fov_v_deg * kDegToRad);
  // The near plane cuts at the minimum range along the most oblique ray.
  view.near_m = kMinRange_m / std::sqrt(1.0 + view.half_width * view.half_width + view.half_height * view.half_height);
  view.far_m = kMaxRange_m;
  return view;
}

// The rasteriser's scans, rays per second (a pixel is a ray).
double raster_rate(peers::RasterScanner& raster, const Scans& scans, std::vector<float>& ranges, std::size_t& hits) {
  hits = 0;
  const auto start = Clock::now();
  for (const Eigen::Isometry3d& pose : scans.poses) {
    raster.scan(pose, ranges);
    for (const float r : ranges) hits += r < kMaxRange_m + 1.0f;
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return static_cast<double>(scans.poses.size() * ranges.size()) / seconds;
}

// How the depth buffer agrees with campo: campo casts the pixels' own rays
// (through their centres) from every pose of the scans, untimed, and each
// pixel's range is compared with campo's along the same ray.
struct Agreement {
  std::size_t rays = 0, both_miss = 0, both_hit = 0, within_1cm = 0, campo_only = 0, raster_only = 0;
  std::string text() const {
    char buffer[256];
    std::snprintf(buffer, sizeof buffer,
                  "pixel rays cast by campo: %.2f %% agree (%zu hits within 1 cm of %zu both hit, %zu both miss; "
                  "hit by one only: campo %zu, raster %zu)",
                  100.0 * static_cast<double>(within_1cm + both_miss) / static_cast<double>(rays), within_1cm,
                  both_hit, both_miss, campo_only, raster_only);
    return buffer;
  }
};

Agreement raster_agreement(const Scene& scene, peers::RasterScanner& raster, const Scans& scans) {
  const RayCaster caster(scene);
  const std::vector<Eigen::Vector3f> pixels = raster.pixel_directions();
  const RayFan fan(pixels);
  std::vector<RayHit> ours(pixels.size());
  std::vector<float> theirs(pixels.size());
  Agreement a;
  for (const Eigen::Isometry3d& pose : scans.poses) {
    caster.cast(pose, fan, kMinRange_m, kMaxRange_m, ours);
    raster.scan(pose, theirs);
    for (std::size_t i = 0; i < pixels.size(); ++i) {
      const bool hit = ours[i].shape != RayHit::kNoShape, their_hit = std::isfinite(theirs[i]);
      ++a.rays;
      if (hit && their_hit) {
        ++a.both_hit;
        a.within_1cm += std::abs(ours[i].distance_m - theirs[i]) <= 0.01f;
      } else if (hit) {
        ++a.campo_only;
      } else if (their_hit) {
        ++a.raster_only;
      } else {
        ++a.both_miss;
      }
    }
  }
  return a;
}

void print(const peers::Comparison& c, bool json) {
  if (json) {
    peers::print_json(c);
    return;
  }
  std::printf("| %s | campo %.2f M rays/s | %s: %.2f M rays/s | %.2fx | %s |\n", c.comparison.c_str(), c.campo / 1e6,
              c.peer_name.c_str(), c.peer / 1e6, c.campo / c.peer, c.note.c_str());
}

// One scene against its peers: Embree robust and not, and the rasteriser,
// culling each object as a whole or in runs of 256 triangles (the faster of
// the two is reported); repetitions interleave campo and each peer.
void compare(const std::string& id, const std::string& label, const Scene& scene, int scans_per_repetition,
             int repetitions, bool json) {
  const Scans scans = scanner3d_scans(scene, scans_per_repetition);
  const EmbreeTriangles robust(scene, true), fast(scene, false);
  std::vector<peers::RasterView> views(2, raster_view());
  views[0].cull_run_triangles = 0;
  views[1].cull_run_triangles = 256;
  std::vector<std::unique_ptr<peers::RasterScanner>> rasters;
  for (const peers::RasterView& view : views) rasters.push_back(std::make_unique<peers::RasterScanner>(scene, view));
  std::vector<float> ranges(rasters.front()->pixel_directions().size());
  std::vector<double> ours, robust_rates, fast_rates;
  std::vector<std::vector<double>> raster_rates(rasters.size());
  std::size_t our_hits = 0, robust_hits = 0, fast_hits = 0, raster_hits = 0;
  for (int r = 0; r < repetitions; ++r) {
    ours.push_back(campo_rate(scene, scans, our_hits));
    robust_rates.push_back(robust.rate(scans, robust_hits));
    fast_rates.push_back(fast.rate(scans, fast_hits));
    for (std::size_t i = 0; i < rasters.size(); ++i) {
      raster_rates[i].push_back(raster_rate(*rasters[i], scans, ranges, raster_hits));
    }
  }
  const double a = median(ours);
  const auto hits = [&](std::size_t theirs) {
    return "hits " + std::to_string(our_hits) + " vs " + std::to_string(theirs);
  };
  print({"lidar/" + id, label, a, median(robust_rates), "rays/s", embree_name(robust.triangles(), true),
         hits(robust_hits)},
        json);
  print({"lidar/" + id + "/embree_not_robust", label, a, median(fast_rates), "rays/s",
         embree_name(fast.triangles(), false), hits(fast_hits)},
        json);
  const std::size_t best = median(raster_rates[0]) >= median(raster_rates[1]) ? 0 : 1;
  const peers::RasterView& view = views[best];
  char other[96];
  std::snprintf(other, sizeof other, "; culled %s: %.2f M rays/s",
                best == 0 ? "in runs of 256 triangles" : "object by object", median(raster_rates[1 - best]) / 1e6);
  print({"lidar/" + id + "/raster", label, a, median(raster_rates[best]), "rays/s",
         "OSMesa llvmpipe, 1 thread, " + std::to_string(view.width_px) + " x " + std::to_string(view.height_px) +
             " px depth buffer read back (" + std::to_string(rasters[best]->triangles()) + " triangles, culled " +
             (best == 0 ? std::string("object by object") : "in runs of 256 triangles") + ")",
         raster_agreement(scene, *rasters[best], scans).text() + other},
        json);
}

}  // namespace
}  // namespace campo

int main(int argc, char** argv) {
  // llvmpipe renders on the calling thread alone (read when its first context is made).
  setenv("LP_NUM_THREADS", "0", 1);
  int scans = 20, repetitions = 5;
  std::string only;  // --scene NAME: that comparison alone
  const bool json = campo::peers::json_requested(argc, argv);
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--scans") == 0) scans = std::stoi(argv[i + 1]);
    if (std::strcmp(argv[i], "--repetitions") == 0) repetitions = std::stoi(argv[i + 1]);
    if (std::strcmp(argv[i], "--scene") == 0) only = argv[i + 1];
  }
  const auto wanted = [&](const std::string& id) { return only.empty() || only == id; };
  try {
    const std::string scenes = std::string(CAMPO_SOURCE_DIR) + "/scenes/";
    const campo::Scene trees = campo::load_scene(scenes + "trees_rolling_terrain.json");
    if (wanted("trees_rolling_terrain")) {
      campo::compare("trees_rolling_terrain", "trees_rolling_terrain", trees, scans, repetitions, json);
    }
    if (wanted("vineyard")) {
      campo::compare("vineyard", "vineyard", campo::load_scene(scenes + "vineyard.json"), scans, repetitions, json);
    }
    campo::Scene terrain = trees;
    std::erase_if(terrain.shapes, [](const campo::Shape& s) { return s.type != campo::ShapeType::heightfield; });
    if (wanted("terrain")) {
      campo::compare("terrain", "terrain alone (trees_rolling_terrain's)", terrain, scans, repetitions, json);
    }
    std::vector<std::filesystem::path> others;
    for (const auto& entry : std::filesystem::directory_iterator(scenes)) {
      const std::string name = entry.path().stem().string();
      if (entry.path().extension() == ".json" && name != "trees_rolling_terrain" && name != "vineyard" &&
          wanted(name)) {
        others.push_back(entry.path());
      }
    }
    std::sort(others.begin(), others.end());
    for (const std::filesystem::path& path : others) {
      const std::string name = path.stem().string();
      campo::compare(name, name, campo::load_scene(path), scans, repetitions, json);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "campo_peer_lidar: %s\n", e.what());
    return 1;
  }
  return 0;
}
