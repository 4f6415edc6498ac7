// campo's quadrotor against MuJoCo on the same scene (docs/PERFORMANCE.md, "Peers"):
// trees_rolling_terrain without sensors, the drone hovering at its start 1.5 m above
// the hills among the trees. campo steps its World with the quadrotor's own
// controllers (Quadrotor::pre_step: attitude and position loops, four rotor forces,
// motor lag, drag); MuJoCo steps a model built from the same Scene (the terrain as
// an hfield, every tree as a cylinder and a sphere, the drone a free box of the
// same mass, inertia and size) with a PD hover applying the equivalent force and
// torque. Both at the scene's physics step. Repetitions interleave, one process;
// the figure is physics steps per second, median of the repetitions.
//
//   build/campo_peer_quadrotor [--steps N] [--repetitions K]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>

#include "bench/peers/peer_record.hpp"
#include "campo/scene_loader.hpp"
#include "campo/world.hpp"
#include "campo/vehicle_factory.hpp"

namespace campo {
namespace {

using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Steps per second of campo's world with the hovering quadrotor.
double campo_rate(const Scene& scene, int steps) {
  World world(scene);
  const VehicleDef& def = scene.vehicles.front();
  const std::unique_ptr<Vehicle> drone = make_vehicle(world, def);
  drone->command(command::Hold{def.pose.translation(), std::nullopt});
  const double dt = scene.world.physics_step_s;
  const auto start = Clock::now();
  for (int i = 0; i < steps; ++i) {
    drone->pre_step(dt);
    world.step();
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (std::abs(drone->state().position_m.z() - def.pose.translation().z()) > 0.2) {
    throw std::runtime_error("campo's drone did not hover");
  }
  return steps / seconds;
}

// The drone's effective parameters (preset and the scene's overrides), as run.json records them.
nlohmann::json drone_parameters(const Scene& scene) {
  World world(scene);
  return make_vehicle(world, scene.vehicles.front())->parameters();
}

// The scene as MJCF: the terrain hfield (heights filled in after loading), the static shapes, the drone.
std::string mjcf(const Scene& scene, const HeightGrid*& terrain, Eigen::Vector3d& terrain_at) {
  std::ostringstream x;
  x << "<mujoco><option timestep=\"" << scene.world.physics_step_s << "\" gravity=\"0 0 "
    << scene.world.gravity_mps2.z() << "\"/><asset>";
  terrain = nullptr;
  for (const Shape& s : scene.shapes) {
    if (s.type != ShapeType::heightfield) continue;
    terrain = s.terrain.get();
    terrain_at = s.pose.translation();
    const double rx = 0.5 * (terrain->cols - 1) * terrain->spacing_x_m;
    const double ry = 0.5 * (terrain->rows - 1) * terrain->spacing_y_m;
    x << "<hfield name=\"terrain\" nrow=\"" << terrain->rows << "\" ncol=\"" << terrain->cols << "\" size=\"" << rx
      << " " << ry << " " << std::max(1e-6, terrain->max_height_m() - terrain->min_height_m()) << " 0.1\"/>";
  }
  x << "</asset><worldbody>";
  for (const Shape& s : scene.shapes) {
    const Eigen::Vector3d p = s.pose.translation();
    const Eigen::Quaterniond q(s.pose.linear());
    std::ostringstream pose;
    pose << " pos=\"" << p.x() << " " << p.y() << " " << p.z() << "\" quat=\"" << q.w() << " " << q.x() << " " << q.y()
         << " " << q.z() << "\"";
    switch (s.type) {
      case ShapeType::heightfield:
        x << "<geom type=\"hfield\" hfield=\"terrain\" pos=\"" << p.x() << " " << p.y() << " "
          << p.z() + terrain->min_height_m() << "\"/>";
        break;
      case ShapeType::plane:
        x << "<geom type=\"plane\" size=\"0 0 1\"" << pose.str() << "/>";
        break;
      case ShapeType::cuboid:
        x << "<geom type=\"box\" size=\"" << s.size_m.x() / 2 << " " << s.size_m.y() / 2 << " " << s.size_m.z() / 2
          << "\"" << pose.str() << "/>";
        break;
      case ShapeType::cylinder:
      case ShapeType::cone:  // MuJoCo has no cone: the cylinder around it
        x << "<geom type=\"cylinder\" size=\"" << s.radius_m << " " << s.height_m / 2 << "\"" << pose.str() << "/>";
        break;
      case ShapeType::sphere:
        x << "<geom type=\"sphere\" size=\"" << s.radius_m << "\"" << pose.str() << "/>";
        break;
      case ShapeType::mesh:
        // MuJoCo collides meshes as convex hulls; campo's static meshes are their triangles.
        throw std::runtime_error("the MuJoCo peer takes no mesh shapes ('" + s.alias + "'): MuJoCo would collide "
                                 "it as its convex hull, campo as its triangles");
    }
  }
  const nlohmann::json params = drone_parameters(scene);
  const auto vec = [&](const char* key) {
    const auto& v = params.at(key);
    return std::to_string(v[0].get<double>()) + " " + std::to_string(v[1].get<double>()) + " " +
           std::to_string(v[2].get<double>());
  };
  const Eigen::Vector3d start = scene.vehicles.front().pose.translation();
  x << "<body name=\"drone\" pos=\"" << start.x() << " " << start.y() << " " << start.z() << "\"><freejoint/>"
    << "<geom type=\"box\" size=\"" << vec("collision_half_extents_m") << "\"/>"
    << "<inertial pos=\"0 0 0\" mass=\"" << params.at("mass_kg").get<double>() << "\" diaginertia=\""
    << vec("inertia_kgm2") << "\"/></body></worldbody></mujoco>";
  return x.str();
}

// Steps per second of MuJoCo with a PD hover at the start.
double mujoco_rate(const Scene& scene, int steps) {
  const HeightGrid* terrain = nullptr;
  Eigen::Vector3d terrain_at = Eigen::Vector3d::Zero();
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "campo_peer_quadrotor.xml";
  std::ofstream(file) << mjcf(scene, terrain, terrain_at);
  char error[1000] = "";
  mjModel* m = mj_loadXML(file.c_str(), nullptr, error, sizeof error);
  std::filesystem::remove(file);
  if (!m) throw std::runtime_error(std::string("MuJoCo: ") + error);
  if (terrain) {
    // MuJoCo's rows run along +y from the bottom edge, as the grid's; heights normalised to [0, 1].
    const double low = terrain->min_height_m(), range = std::max(1e-6, terrain->max_height_m() - low);
    for (int r = 0; r < terrain->rows; ++r) {
      for (int c = 0; c < terrain->cols; ++c) {
        m->hfield_data[r * terrain->cols + c] = static_cast<float>((terrain->at(c, r) - low) / range);
      }
    }
  }
  mjData* d = mj_makeData(m);
  const int drone = mj_name2id(m, mjOBJ_BODY, "drone");
  const double mass = m->body_mass[drone], g = -m->opt.gravity[2];
  const Eigen::Vector3d target = scene.vehicles.front().pose.translation();
  const auto start = Clock::now();
  for (int i = 0; i < steps; ++i) {
    // qpos: x y z qw qx qy qz; qvel: v (world) w (body).
    double* f = d->xfrc_applied + 6 * drone;
    for (int k = 0; k < 3; ++k) f[k] = mass * (4.0 * (target[k] - d->qpos[k]) - 3.0 * d->qvel[k]);
    f[2] += mass * g;
    // Level the body: torque against the tilt (the quaternion's vector part) and the spin.
    for (int k = 0; k < 3; ++k) f[3 + k] = -0.5 * d->qpos[4 + k] - 0.05 * d->qvel[3 + k];
    mj_step(m, d);
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  const double drift = std::abs(d->qpos[2] - target.z());
  mj_deleteData(d);
  mj_deleteModel(m);
  if (drift > 0.2) throw std::runtime_error("MuJoCo's drone did not hover");
  return steps / seconds;
}

}  // namespace
}  // namespace campo

int main(int argc, char** argv) {
  int steps = 14400, repetitions = 7;  // a minute of flight at 240 Hz
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--steps") == 0) steps = std::stoi(argv[i + 1]);
    if (std::strcmp(argv[i], "--repetitions") == 0) repetitions = std::stoi(argv[i + 1]);
  }
  try {
    const campo::Scene scene = campo::load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/trees_rolling_terrain.json");
    std::vector<double> ours, theirs;
    for (int r = 0; r < repetitions; ++r) {
      ours.push_back(campo::campo_rate(scene, steps));
      theirs.push_back(campo::mujoco_rate(scene, steps));
    }
    const double a = campo::median(ours), b = campo::median(theirs);
    if (campo::peers::json_requested(argc, argv)) {
      campo::peers::print_json({"quadrotor/trees_rolling_terrain", "quadrotor hovering over trees_rolling_terrain", a, b,
                                "steps/s", std::string("MuJoCo ") + mj_versionString(), ""});
      return 0;
    }
    std::printf("| quadrotor hovering over trees_rolling_terrain | campo %.0f steps/s | MuJoCo %s %.0f steps/s | "
                "%.2fx | |\n",
                a, mj_versionString(), b, a / b);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "campo_peer_quadrotor: %s\n", e.what());
    return 1;
  }
  return 0;
}
