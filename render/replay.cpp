#include "render/replay.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <unordered_map>

#include "campo/json_reader.hpp"
#include "render/figure_style.hpp"
#include "campo/version.hpp"
#include "render/replay_assets.hpp"

namespace campo {

namespace {

using nlohmann::json;

// Millimetres and thousandths of a degree are plenty for a viewer, and keep the file short.
double rounded(double v, double unit = 1e-3) { return std::round(v / unit) * unit; }
json xyz(const Eigen::Vector3d& v) { return {rounded(v.x()), rounded(v.y()), rounded(v.z())}; }
json colour_json(const Color& c) { return {rounded(c.r), rounded(c.g), rounded(c.b)}; }

json rotation(const Eigen::Matrix3d& m) {
  json out = json::array();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out.push_back(rounded(m(r, c), 1e-6));
  }
  return out;
}

// Every `stride`-th index of n, the last always included.
std::vector<std::size_t> thinned(std::size_t n, std::size_t max) {
  std::vector<std::size_t> keep;
  if (n == 0) return keep;
  const std::size_t stride = max == 0 ? n : (n + max - 1) / max;
  for (std::size_t i = 0; i < n; i += std::max<std::size_t>(stride, 1)) keep.push_back(i);
  if (keep.back() != n - 1) keep.push_back(n - 1);
  return keep;
}

// A mesh's triangles after vertex clustering (Rossignac and Borrel): the
// vertices in each cell of a grid `cell_m` wide merge into their mean, and
// triangles that collapse (or repeat) drop out.
struct ClusteredMesh {
  std::vector<Eigen::Vector3d> vertices_m;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

ClusteredMesh clustered(const TriangleMesh& mesh, double cell_m) {
  ClusteredMesh out;
  std::unordered_map<std::uint64_t, std::uint32_t> cluster_of_cell;
  std::vector<std::uint32_t> cluster(mesh.vertices_m.size());
  std::vector<double> members;
  const Eigen::Vector3d origin = mesh.bounds_m.min();
  for (std::size_t i = 0; i < mesh.vertices_m.size(); ++i) {
    // 21 bits a coordinate: the caller keeps cell_m at least the mesh's extent / 2^20.
    const Eigen::Vector3d q = ((mesh.vertices_m[i] - origin) / cell_m).array().floor();
    const std::uint64_t key = (static_cast<std::uint64_t>(q.x()) << 42) | (static_cast<std::uint64_t>(q.y()) << 21) |
                              static_cast<std::uint64_t>(q.z());
    const auto [it, added] = cluster_of_cell.emplace(key, static_cast<std::uint32_t>(out.vertices_m.size()));
    if (added) {
      out.vertices_m.push_back(Eigen::Vector3d::Zero());
      members.push_back(0.0);
    }
    cluster[i] = it->second;
    out.vertices_m[it->second] += mesh.vertices_m[i];
    members[it->second] += 1.0;
  }
  for (std::size_t k = 0; k < out.vertices_m.size(); ++k) out.vertices_m[k] /= members[k];
  for (const auto& t : mesh.triangles) {
    const std::array<std::uint32_t, 3> c{cluster[t[0]], cluster[t[1]], cluster[t[2]]};
    if (c[0] != c[1] && c[1] != c[2] && c[2] != c[0]) out.triangles.push_back(c);
  }
  // The same three clusters in the same turn are one triangle.
  const auto canonical = [](std::array<std::uint32_t, 3> t) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    return t;
  };
  for (auto& t : out.triangles) t = canonical(t);
  std::sort(out.triangles.begin(), out.triangles.end());
  out.triangles.erase(std::unique(out.triangles.begin(), out.triangles.end()), out.triangles.end());
  return out;
}

// The meshes of the replay's shapes, each sent once however many shapes use
// it, vertices in the shape frame; over all of them at most
// max_mesh_triangles: a mesh holds its share of that by triangle count, and
// one with more is clustered on the finest grid that fits its share.
class ReplayMeshes {
 public:
  ReplayMeshes(const Scene& scene, std::size_t max_triangles) {
    std::unordered_map<const TriangleMesh*, bool> seen;
    double total = 0.0;
    const auto count = [&](const Shape& s) {
      if (s.type == ShapeType::mesh && seen.emplace(s.mesh.get(), true).second)
        total += static_cast<double>(s.mesh->triangles.size());
    };
    for (const Shape& s : scene.shapes) count(s);
    for (const Mover& m : scene.movers) count(m.shape);
    keep_ = total > static_cast<double>(max_triangles) ? static_cast<double>(max_triangles) / total : 1.0;
  }

  // Index of `mesh` in the "meshes" array, sending it the first time.
  std::size_t index(const TriangleMesh& mesh) {
    const auto [it, added] = index_.emplace(&mesh, meshes_.size());
    if (!added) return it->second;
    const std::size_t budget =
        std::max<std::size_t>(12, static_cast<std::size_t>(std::floor(keep_ * static_cast<double>(mesh.triangles.size()))));
    json vertices = json::array(), triangles = json::array();
    const auto write = [&](const std::vector<Eigen::Vector3d>& vs, const std::vector<std::array<std::uint32_t, 3>>& ts) {
      for (const Eigen::Vector3d& v : vs) {
        for (int k = 0; k < 3; ++k) vertices.push_back(rounded(v[k]));
      }
      for (const auto& t : ts) {
        for (int k = 0; k < 3; ++k) triangles.push_back(t[k]);
      }
    };
    bool decimated = false;
    if (mesh.triangles.size() <= budget) {
      write(mesh.vertices_m, mesh.triangles);
    } else {
      // Bisection on the cell size, geometric: fine enough to keep shape, coarse enough to fit.
      const double extent = std::max(mesh.bounds_m.sizes().maxCoeff(), 1e-6);
      double fine = extent / (1 << 20), coarse = 2.0 * extent;
      ClusteredMesh best = clustered(mesh, coarse);
      for (int i = 0; i < 12; ++i) {
        const double cell = std::sqrt(fine * coarse);
        ClusteredMesh c = clustered(mesh, cell);
        if (c.triangles.size() <= budget) {
          coarse = cell;
          best = std::move(c);
        } else {
          fine = cell;
        }
      }
      write(best.vertices_m, best.triangles);
      decimated = true;
    }
    meshes_.push_back({{"vertices_m", std::move(vertices)},
                       {"triangles", std::move(triangles)},
                       {"file_triangles", mesh.triangles.size()},
                       {"decimated", decimated}});
    return it->second;
  }

  json take() { return std::move(meshes_); }

 private:
  double keep_ = 1.0;  // fraction of its triangles a mesh may keep
  std::unordered_map<const TriangleMesh*, std::size_t> index_;
  json meshes_ = json::array();
};

// World-frame bounds of a mesh shape.
void extend_by_mesh(const Shape& s, Eigen::AlignedBox3d& bounds) {
  for (int corner = 0; corner < 8; ++corner) {
    bounds.extend(s.pose * s.mesh->bounds_m.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)));
  }
}

json solid_json(const Shape& s, int mover, ReplayMeshes& meshes) {
  json j{{"type", std::string(to_string(s.type))}, {"alias", s.alias}, {"position_m", xyz(s.pose.translation())},
         {"rotation", rotation(s.pose.linear())}, {"color", colour_json(s.color)}, {"mover", mover}};
  switch (s.type) {
    case ShapeType::cuboid:
      j["size_m"] = xyz(s.size_m);
      break;
    case ShapeType::cylinder:
    case ShapeType::cone:
      j["radius_m"] = rounded(s.radius_m);
      j["height_m"] = rounded(s.height_m);
      break;
    case ShapeType::sphere:
      j["radius_m"] = rounded(s.radius_m);
      break;
    case ShapeType::mesh:
      j["mesh"] = meshes.index(*s.mesh);
      break;
    case ShapeType::plane:
    case ShapeType::heightfield:
      throw std::logic_error("solid_json: not a solid");
  }
  return j;
}

// The heights of `g` on a grid of at most cols x rows vertices over the same extent, bilinear.
HeightGrid resampled(const HeightGrid& g, int cols, int rows) {
  if (cols >= g.cols && rows >= g.rows) return g;
  HeightGrid out;
  out.cols = std::max(2, std::min(cols, g.cols));
  out.rows = std::max(2, std::min(rows, g.rows));
  out.spacing_x_m = g.size_x_m() / (out.cols - 1);
  out.spacing_y_m = g.size_y_m() / (out.rows - 1);
  out.heights_m.resize(static_cast<std::size_t>(out.cols) * out.rows);
  for (int r = 0; r < out.rows; ++r) {
    const double y = static_cast<double>(r) * (g.rows - 1) / (out.rows - 1);
    const int r0 = std::min(static_cast<int>(y), g.rows - 2);
    const double fy = y - r0;
    for (int c = 0; c < out.cols; ++c) {
      const double x = static_cast<double>(c) * (g.cols - 1) / (out.cols - 1);
      const int c0 = std::min(static_cast<int>(x), g.cols - 2);
      const double fx = x - c0;
      const double low = g.at(c0, r0) + fx * (g.at(c0 + 1, r0) - g.at(c0, r0));
      const double high = g.at(c0, r0 + 1) + fx * (g.at(c0 + 1, r0 + 1) - g.at(c0, r0 + 1));
      out.heights_m[static_cast<std::size_t>(r) * out.cols + c] = low + fy * (high - low);
    }
  }
  return out;
}

json scene_json(const Scene& scene, double duration_s, const ReplayLimits& limits, Eigen::AlignedBox3d& bounds) {
  json shapes = json::array(), planes = json::array(), terrains = json::array(), movers = json::array();
  ReplayMeshes meshes(scene, limits.max_mesh_triangles);
  // Terrains share max_terrain_vertices: a finer set is resampled by one factor along both sides.
  double vertices = 0.0;
  for (const Shape& s : scene.shapes) {
    if (s.type == ShapeType::heightfield) vertices += static_cast<double>(s.terrain->cols) * s.terrain->rows;
  }
  const double shrink = vertices > static_cast<double>(limits.max_terrain_vertices)
                            ? std::sqrt(static_cast<double>(limits.max_terrain_vertices) / vertices)
                            : 1.0;
  for (const Shape& s : scene.shapes) {
    if (s.type == ShapeType::plane) {
      planes.push_back({{"position_m", xyz(s.pose.translation())}, {"normal", xyz(s.pose.linear().col(2))},
                        {"color", colour_json(s.color)}});
    } else if (s.type == ShapeType::heightfield) {
      const HeightGrid g = resampled(*s.terrain, static_cast<int>(std::floor((s.terrain->cols - 1) * shrink)) + 1,
                                     static_cast<int>(std::floor((s.terrain->rows - 1) * shrink)) + 1);
      json heights = json::array();
      for (double h : g.heights_m) heights.push_back(rounded(h));
      terrains.push_back({{"position_m", xyz(s.pose.translation())}, {"rotation", rotation(s.pose.linear())},
                          {"cols", g.cols}, {"rows", g.rows}, {"spacing_m", {g.spacing_x_m, g.spacing_y_m}},
                          {"heights_m", std::move(heights)}, {"color", colour_json(s.color)}});
      for (double x : {-0.5, 0.5}) {
        for (double y : {-0.5, 0.5}) {
          for (double z : {g.min_height_m(), g.max_height_m()}) {
            bounds.extend(s.pose * Eigen::Vector3d(x * g.size_x_m(), y * g.size_y_m(), z));
          }
        }
      }
    } else {
      shapes.push_back(solid_json(s, -1, meshes));
      if (s.type == ShapeType::mesh) {
        extend_by_mesh(s, bounds);
      } else {
        bounds.extend(s.pose.translation());
      }
    }
  }
  // Bounded whatever the recorded duration claims, and shared by the movers.
  const std::size_t mover_samples =
      std::max<std::size_t>(1, std::min(limits.max_mover_samples,
                                        limits.max_total_mover_samples / std::max<std::size_t>(scene.movers.size(), 1)));
  for (std::size_t i = 0; i < scene.movers.size(); ++i) {
    const Mover& m = scene.movers[i];
    json times = json::array(), positions = json::array();
    const double step_s = std::max(limits.mover_sample_s, duration_s / static_cast<double>(mover_samples));
    const auto samples = static_cast<std::size_t>(std::ceil(duration_s / step_s)) + 1;
    for (std::size_t k = 0; k < samples; ++k) {
      const double t = std::min(static_cast<double>(k) * step_s, duration_s);
      times.push_back(rounded(t));
      positions.push_back(xyz(m.position_at(t)));
    }
    movers.push_back({{"shape", shapes.size()}, {"times_s", std::move(times)}, {"positions_m", std::move(positions)}});
    shapes.push_back(solid_json(m.shape, static_cast<int>(i), meshes));
  }
  return {{"name", scene.name},         {"shapes", std::move(shapes)},     {"planes", std::move(planes)},
          {"terrains", std::move(terrains)}, {"movers", std::move(movers)}, {"meshes", meshes.take()}};
}

// What one of `runs` runs may put in the page: its share of the totals.
struct RunBudget {
  RunBudget(const ReplayLimits& limits, std::size_t runs)
      : track_samples(std::max<std::size_t>(2, std::min(limits.max_track_samples, limits.max_total_track_samples / runs))),
        scans(limits.max_scans),
        points_per_scan(limits.max_scan_points),
        scan_points(limits.max_total_scan_points / runs) {}
  std::size_t track_samples;
  std::size_t scans;
  std::size_t points_per_scan;
  std::size_t scan_points;  ///< over all of the run's scans
};

// trajectory.csv's poses, sample by sample.
struct RecordedPoses {
  explicit RecordedPoses(const TrajectoryTable& table)
      : time(table.column("time_s")),
        x(table.column("x_m")),
        y(table.column("y_m")),
        z(table.column("z_m")),
        roll(table.column("roll_deg")),
        pitch(table.column("pitch_deg")),
        yaw(table.column("yaw_deg")) {}
  Pose at(std::size_t i) const { return {{x[i], y[i], z[i]}, {roll[i], pitch[i], yaw[i]}}; }
  const std::vector<double>& time;  // s
  const std::vector<double>& x;     // m
  const std::vector<double>& y;
  const std::vector<double>& z;
  const std::vector<double>& roll;  // deg
  const std::vector<double>& pitch;
  const std::vector<double>& yaw;
};

// The returns of the first sensor of `vehicle` (null: the run's, recorded_vehicle) with recorded depth maps, in
// the world frame, from the vehicle's recorded pose at each scan.
json scans_json(const RecordedRun& run, const VehicleDef* def, const RecordedPoses& poses, const RunBudget& budget) {
  json scans = json::array();
  const std::vector<RecordedDepthMap> maps = recorded_depth_maps(run);
  if (maps.empty()) return scans;
  const VehicleDef& vehicle = def ? *def : recorded_vehicle(run);
  const SensorDef* sensor = nullptr;
  for (const SensorDef& s : vehicle.sensors) {
    if (std::any_of(maps.begin(), maps.end(), [&](const auto& m) { return m.sensor == s.alias; })) {
      sensor = &s;
      break;
    }
  }
  if (!sensor) return scans;
  std::vector<RecordedDepthMap> own;
  for (const auto& m : maps) {
    if (m.sensor == sensor->alias) own.push_back(m);
  }
  // The run's share of the scan points: fewer scans first (at least 100 points each), then fewer points.
  const std::size_t kept_scans = std::min(budget.scans, std::max<std::size_t>(1, budget.scan_points / 100));
  const std::size_t points_per_scan =
      std::min(budget.points_per_scan, std::max<std::size_t>(1, budget.scan_points / kept_scans));
  for (std::size_t k : thinned(own.size(), kept_scans)) {
    const RecordedDepthMap& m = own[k];
    // The recorded sample at the scan (samples are at least as frequent as scans).
    const auto it = std::upper_bound(poses.time.begin(), poses.time.end(), m.time_s + 1e-9);
    const std::size_t i = it == poses.time.begin() ? 0 : static_cast<std::size_t>(it - poses.time.begin() - 1);
    const std::vector<Eigen::Vector3d> points =
        depth_map_returns(read_depth_map(m.file), *sensor, to_isometry(poses.at(i)), m.file);
    json pts = json::array();
    for (std::size_t p : thinned(points.size(), points_per_scan)) pts.push_back(xyz(points[p]));
    scans.push_back({{"time_s", rounded(m.time_s)}, {"points_m", std::move(pts)}});
  }
  return scans;
}

// One vehicle of a run (RecordedRun::vehicles[`vehicle`]) as an entry of the page's runs, labelled `label` in `colour`.
json run_json(const RecordedRun& run, std::size_t vehicle, const std::string& label, const cv::Scalar& bgr,
              const RunBudget& budget, Eigen::AlignedBox3d& bounds) {
  const RecordedVehicle& recorded = run.vehicles.at(vehicle);
  const TrajectoryTable table = read_trajectory_table(run.dir / recorded.trajectory_file);
  const RecordedPoses poses(table);
  if (poses.time.empty()) throw InputError(table.file, "", "no samples; expected a track");
  json times = json::array(), positions = json::array(), attitudes = json::array();
  for (std::size_t i : thinned(poses.time.size(), budget.track_samples)) {
    const Pose pose = poses.at(i);
    times.push_back(rounded(poses.time[i], 1e-4));
    positions.push_back(xyz(pose.position_m));
    attitudes.push_back(xyz(pose.rpy_deg));
    bounds.extend(pose.position_m);
  }
  const std::string type = recorded.parameters.value("/vehicle/type"_json_pointer, std::string("quadrotor"));
  // The recorded depth maps are one vehicle's (campo run --vehicle), found in scene.json by its alias.
  json scans = json::array();
  if (!run.several()) {
    scans = scans_json(run, nullptr, poses, budget);
  } else if (recorded.alias == sensor_records_vehicle(run)) {
    if (const VehicleDef* def = run.scene.find_vehicle(recorded.alias)) scans = scans_json(run, def, poses, budget);
  }
  return {{"label", label},
          {"color", {rounded(bgr[2] / 255.0), rounded(bgr[1] / 255.0), rounded(bgr[0] / 255.0)}},
          {"vehicle", type},
          {"size_m", xyz(vehicle_size_m(recorded))},
          {"outcome", recorded.view.outcome},
          {"times_s", std::move(times)},
          {"positions_m", std::move(positions)},
          {"rpy_deg", std::move(attitudes)},
          {"scans", std::move(scans)}};
}

// The page: each line of the template that is one marker alone becomes that content; the
// inserted text is never searched for markers again.
std::string assemble(const ReplayAssets& assets, const std::string& data) {
  const std::pair<std::string_view, std::string_view> contents[] = {{"/*@CAMPO_THREE@*/", assets.three},
                                                                    {"/*@CAMPO_ORBIT@*/", assets.orbit},
                                                                    {"/*@CAMPO_REPLAY_JS@*/", assets.script},
                                                                    {"/*@CAMPO_DATA@*/", data}};
  std::string page;
  page.reserve(assets.page.size() + assets.three.size() + assets.orbit.size() + assets.script.size() + data.size());
  int found = 0;
  std::string_view rest = assets.page;
  while (!rest.empty()) {
    const std::size_t end = rest.find('\n');
    const std::string_view line = rest.substr(0, end == std::string_view::npos ? rest.size() : end + 1);
    rest.remove_prefix(line.size());
    std::string_view trimmed = line;
    while (!trimmed.empty() && std::isspace(static_cast<unsigned char>(trimmed.back()))) trimmed.remove_suffix(1);
    while (!trimmed.empty() && std::isspace(static_cast<unsigned char>(trimmed.front()))) trimmed.remove_prefix(1);
    const auto match = std::find_if(std::begin(contents), std::end(contents), [&](const auto& c) { return c.first == trimmed; });
    if (match == std::end(contents)) {
      page += line;
      continue;
    }
    page += match->second;
    page += '\n';
    ++found;
  }
  if (found != 4) throw std::logic_error("replay_html: the embedded template lacks a marker");
  return page;
}

}  // namespace

void check_replay_runs(std::size_t runs, const ReplayLimits& limits) {
  if (runs > limits.max_runs) {
    throw InputError("command line", "runs",
                     "at most " + std::to_string(limits.max_runs) + " run directories in one replay, got " +
                         std::to_string(runs) + " (a page of more would be too heavy to open; make several)");
  }
}

namespace {

void check_same_scene(const RecordedRun& run, const RecordedRun& first) {
  if (run.scene.name != first.scene.name) {
    throw InputError((run.dir / "scene.json").string(), "/name",
                     "expected the scene of the other runs (\"" + first.scene.name + "\"): one replay shows one scene, got \"" +
                         run.scene.name + "\"");
  }
}

// The page's data from the runs, `run(i)` giving the i-th of `count` (loaded or read then).
json replay_json(std::size_t count, const std::function<const RecordedRun&(std::size_t)>& run,
                 const ReplayLimits& limits) {
  if (count == 0) throw std::invalid_argument("replay_data: no runs");
  check_replay_runs(count, limits);
  const RunBudget budget(limits, count);
  Eigen::AlignedBox3d bounds;
  json run_list = json::array();
  double duration_s = 0.0;
  std::optional<RecordedRun> first;
  for (std::size_t i = 0; i < count; ++i) {
    const RecordedRun& r = run(i);
    if (i == 0) first = r;
    check_same_scene(r, *first);
    if (!r.several()) {
      run_list.push_back(run_json(r, 0, r.view.label, run_color(run_list.size()), budget, bounds));
      duration_s = std::max(duration_s, run_list.back()["times_s"].back().get<double>());
      continue;
    }
    // Every vehicle of a run of several, sharing the run's track samples; in the maps' colours when the replay
    // shows this run alone.
    RunBudget shared = budget;
    shared.track_samples = std::max<std::size_t>(2, budget.track_samples / r.vehicles.size());
    for (std::size_t v = 0; v < r.vehicles.size(); ++v) {
      const std::string label = count == 1 ? r.vehicles[v].alias : r.view.label + ": " + r.vehicles[v].alias;
      run_list.push_back(
          run_json(r, v, label, count == 1 ? vehicle_color(v) : run_color(run_list.size()), shared, bounds));
      duration_s = std::max(duration_s, run_list.back()["times_s"].back().get<double>());
    }
  }
  json scene = scene_json(first->scene, duration_s, limits, bounds);
  scene["bounds_m"] = {{"min", xyz(bounds.min())}, {"max", xyz(bounds.max())}};
  std::string title = first->scene.name;
  if (count == 1 && first->several()) {  // the fleet's outcome
    const std::string outcome = first->record.value("/metrics/outcome"_json_pointer, std::string());
    title += ": " + first->view.label + ", " + std::to_string(first->vehicles.size()) + " vehicles" +
             (outcome.empty() ? "" : " (" + outcome + ")");
  } else if (count == 1) {
    title += ": " + first->view.label + (first->view.outcome.empty() ? "" : " (" + first->view.outcome + ")");
  } else {
    title += ": " + std::to_string(count) + " runs";
  }
  return {{"campo_replay", 1},       {"title", title},
          {"generator", "campo " + std::string(library_version())},
          {"duration_s", duration_s}, {"scene", std::move(scene)},
          {"runs", std::move(run_list)}};
}

}  // namespace

nlohmann::json replay_data(const std::vector<RecordedRun>& runs, const ReplayLimits& limits) {
  return replay_json(runs.size(), [&](std::size_t i) -> const RecordedRun& { return runs[i]; }, limits);
}

nlohmann::json replay_data(const std::vector<std::filesystem::path>& dirs, const ReplayLimits& limits) {
  check_replay_runs(dirs.size(), limits);
  RecordedRun current;  // one run at a time
  return replay_json(dirs.size(), [&](std::size_t i) -> const RecordedRun& {
    current = load_run_dir(dirs[i]);
    return current;
  }, limits);
}

std::string replay_html(const nlohmann::json& data, const ReplayLimits& limits) {
  const std::optional<ReplayAssets> assets = replay_assets();
  if (!assets) {
    throw std::runtime_error(
        "this campo was built without the replay viewer: web/replay/node_modules was missing (tools/setup.sh installs "
        "it from the npm registry); rebuild after running it");
  }
  // Every "<" as \u003c: the same JSON, and nothing in it can end or confuse its <script> element.
  std::string text;
  for (char c : data.dump()) {
    if (c == '<') text += "\\u003c";
    else text += c;
  }
  if (text.size() > limits.max_page_bytes) {
    throw InputError("command line", "runs",
                     "a replay page of at most " + std::to_string(limits.max_page_bytes >> 20) + " MiB, got " +
                         std::to_string(text.size() >> 20) + " MiB of data; give fewer runs");
  }
  return assemble(*assets, text);
}

}  // namespace campo
