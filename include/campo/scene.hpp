#pragma once
/// The validated, immutable description of a world: what a scene file says,
/// with generators expanded and every pose resolved to the world frame.
/// Plain data; no Bullet. Built by load_scene() (scene_loader.hpp).
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "campo/range_sensor_config.hpp"
#include "campo/params_block.hpp"
#include "campo/pose.hpp"
#include "campo/state_noise.hpp"

namespace campo {

/// RGB colour, components in [0, 1].
struct Color {
  double r = 0.6;
  double g = 0.6;
  double b = 0.6;
};

enum class ShapeType { cuboid, cylinder, sphere, cone, plane, heightfield, mesh };

/// One name table for both directions (parsing and printing).
std::string_view to_string(ShapeType type);
std::optional<ShapeType> shape_type_from_string(std::string_view name);

/// Heights on a regular vertex grid. Column index grows along local +x, row
/// index along local +y; the grid is centred on its local origin, so vertex
/// (c, r) sits at x = (c - (cols-1)/2) * spacing_x_m, y = (r - (rows-1)/2) * spacing_y_m.
/// Each cell is split into two triangles along the diagonal from (c+1, r) to
/// (c, r+1), which is how Bullet's btHeightfieldTerrainShape triangulates it.
struct HeightGrid {
  int cols = 0;                  ///< vertices along x (>= 2)
  int rows = 0;                  ///< vertices along y (>= 2)
  double spacing_x_m = 1.0;      ///< vertex spacing along x, metres
  double spacing_y_m = 1.0;      ///< vertex spacing along y, metres
  std::vector<double> heights_m; ///< rows*cols heights, row-major (index r*cols + c)

  double at(int col, int row) const { return heights_m[static_cast<std::size_t>(row) * cols + col]; }
  double size_x_m() const { return (cols - 1) * spacing_x_m; }
  double size_y_m() const { return (rows - 1) * spacing_y_m; }
  double min_height_m() const;
  double max_height_m() const;
  /// Height of the triangulated surface at local (x, y); nullopt outside the grid.
  std::optional<double> height_at(double x, double y) const;
};

/// A triangle mesh read from a file (scene/mesh_sources.hpp), in its shape's
/// local frame: the file's vertices times the object's scale, the file's
/// origin at the shape's pose. Triangles are counter-clockwise seen from
/// outside when the file says so; open or inconsistent meshes are kept (the
/// ray caster and the depth camera see both sides of every triangle).
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices_m;                ///< local frame, metres
  std::vector<std::array<std::uint32_t, 3>> triangles;    ///< indices into vertices_m
  Eigen::AlignedBox3d bounds_m;                           ///< of vertices_m
  /// Every edge is shared by exactly two triangles (a closed surface): only
  /// then has the mesh an inside (clearance may go negative, see docs).
  bool closed = false;
  std::string source_path;    ///< file it was read from
  std::string source_sha256;  ///< hash of the file bytes, for provenance
};

/// A rigid shape in the world frame. Shapes are centred on their pose:
/// cuboid (size_m = full extents), cylinder and cone (axis along local z,
/// radius_m, height_m; the cone's apex at +z), sphere (radius_m), plane
/// (local z = 0, normal +z, infinite), heightfield (terrain, see HeightGrid;
/// its pose has no roll or pitch), mesh (triangles of a file, see
/// TriangleMesh; a dynamic mesh collides as its convex hull).
struct Shape {
  std::string alias;
  ShapeType type = ShapeType::cuboid;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< world frame
  Eigen::Vector3d size_m = Eigen::Vector3d::Ones();         ///< cuboid extents, metres
  double radius_m = 0.5;                                    ///< cylinder, cone, sphere
  double height_m = 1.0;                                    ///< cylinder, cone
  std::shared_ptr<const HeightGrid> terrain;                ///< heightfield only
  std::shared_ptr<const TriangleMesh> mesh;                 ///< mesh only
  bool is_static = true;     ///< false: a dynamic body of mass_kg
  double mass_kg = 0.0;      ///< used when !is_static
  double friction = 0.8;     ///< Coulomb friction coefficient
  Color color;
  std::string source;        ///< JSON pointer of the object or generator it came from
};

/// A named frame (V-REP "dummy"): goals, waypoints, start poses.
struct Frame {
  std::string alias;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< world frame
};

/// A shape moved kinematically along a polyline at constant speed.
struct Mover {
  Shape shape;                          ///< pose = pose at t = 0 (first path point)
  std::vector<Eigen::Vector3d> path_m;  ///< world-frame points, >= 2
  double speed_mps = 1.0;               ///< along the path
  double start_time_s = 0.0;            ///< waits at the first point until then
  bool loop = false;                    ///< restart from the first point at the end
  /// Position of the shape's centre at simulation time t.
  Eigen::Vector3d position_at(double t_s) const;
};

enum class VehicleType { quadrotor, rover };
std::string_view to_string(VehicleType type);
std::optional<VehicleType> vehicle_type_from_string(std::string_view name);

/// A sensor mounted on a vehicle: its range-sensor configuration, whose kind
/// says whether it ray-casts beams or renders an image.
struct SensorDef {
  std::string alias;
  RangeSensorConfig range;  ///< kind, angular grid, ranges, mount, rate
};

/// An inertial measurement unit (a sensor block of "type": "imu"): specific
/// force and angular rate at its mount, in its frame, with the usual
/// datasheet imperfections per axis (sensors/imu.hpp has the error model).
struct ImuConfig {
  double rate_hz = 0.0;  ///< samples per second; 0 = the world's control rate; divides the physics rate
  Pose mount;            ///< relative to the carrier's body frame
  // Accelerometer.
  double accel_noise_density_mps2_per_sqrt_hz = 0.0;   ///< white noise (velocity random walk)
  double accel_bias_instability_mps2 = 0.0;            ///< flicker floor of the Allan deviation
  double accel_random_walk_mps3_per_sqrt_hz = 0.0;     ///< bias random walk
  // Gyroscope.
  double gyro_noise_density_radps_per_sqrt_hz = 0.0;   ///< white noise (angle random walk)
  double gyro_bias_instability_radps = 0.0;            ///< flicker floor of the Allan deviation
  double gyro_random_walk_radps2_per_sqrt_hz = 0.0;    ///< bias random walk
  double bias_correlation_time_s = 100.0;              ///< of the bias-instability process (Gauss-Markov)
  std::uint64_t seed = 0;  ///< noise stream, combined with the world seed
};
struct ImuDef {
  std::string alias;
  ImuConfig imu;
};

/// A colour camera (a sensor block of "type": "rgb_camera"), rendered
/// off-screen like the depth camera: pinhole, rows x cols pixels, 8-bit RGB.
struct RgbCameraConfig {
  double fov_h_deg = 90.0;     ///< horizontal field of view, (0, 170]
  int cols = 320;              ///< pixels across, [1, 4096]
  int rows = 240;              ///< pixels down, [1, 4096]; the vertical field follows from the aspect
  double min_range_m = 0.05;   ///< near clip plane
  double max_range_m = 200.0;  ///< far clip plane; beyond it the sky
  double rate_hz = 0.0;        ///< images per second; 0 = the world's sensor rate
  Pose mount;                  ///< relative to the carrier's body frame (x forward, y left, z up)
  Color sky{0.62, 0.75, 0.88}; ///< background colour
  std::uint64_t seed = 0;      ///< pixel noise stream, combined with the world seed
  double noise_stddev = 0.0;   ///< Gaussian pixel noise, in units of full scale [0, 1]
};
struct RgbCameraDef {
  std::string alias;
  RgbCameraConfig camera;
};

/// A mission waypoint, resolved to world coordinates at load time.
struct Waypoint {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  std::optional<double> heading_deg;  ///< required heading (Dubins routes), if any
};

struct PlannerSpec {
  std::string name;          ///< registry name; empty = the default planner
  std::string name_pointer;  ///< JSON pointer of "name" in params.file ("" when absent)
  ParamsBlock params;        ///< checked by the planner
};

/// An area of cells of the mission's grid (e.g. the slot between two
/// buildings) whose passage is a metric of the run.
struct MissionGate {
  std::string name;                ///< lower-case letters, digits, '_'; names the metrics
  Eigen::AlignedBox2d area_m;      ///< world x, y of the cells' outer edges
  std::optional<double> max_agl_m;  ///< counts only below this height above ground (e.g. under the roofs)
};

struct VehicleDef {
  std::string alias;
  VehicleType type = VehicleType::quadrotor;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< start pose, world frame
  std::vector<SensorDef> sensors;  ///< range sensors (LIDARs, depth cameras), in scene order
  std::vector<ImuDef> imus;        ///< "imu" sensor blocks, in scene order
  std::vector<RgbCameraDef> rgb_cameras;  ///< "rgb_camera" sensor blocks, in scene order
  ParamsBlock params;  ///< overrides of the vehicle preset, checked by vehicles/
  PlannerSpec planner;
  std::vector<Waypoint> mission;  ///< ordered; the last one is the goal
  /// The (x, y) extent of the grid the mission is given on, if any (maps show all of it).
  std::optional<Eigen::AlignedBox2d> mission_area_m;
  StateNoiseConfig state_noise;   ///< what the planner and controllers see of the state (none by default)
  /// Named areas of the mission's grid whose passage the run record reports (gate_<name>_* metrics).
  std::vector<MissionGate> gates;
};

/// How geodetic waypoints become local coordinates.
enum class GeoProjection : std::uint8_t {
  wgs84_enu,         ///< WGS84 geodetic -> ECEF -> ENU at the reference point (proper cos(latitude))
  sphere_no_coslat,  ///< seed 001's conversion (001 §4.2.3): sphere of 6371000 m, no cos(latitude)
};
std::string_view to_string(GeoProjection projection);

/// Geodetic reference point of the local frame (x east, y north, z up).
struct GeoReference {
  double latitude_deg = 0.0;   ///< [-90, 90]
  double longitude_deg = 0.0;  ///< [-180, 180]
  double altitude_m = 0.0;     ///< WGS84 ellipsoidal height
  GeoProjection projection = GeoProjection::wgs84_enu;
  /// Local x, y of the reference point (seed 001 refers its cells to a point
  /// off the grid's south-west corner), within [-1e6, 1e6].
  Eigen::Vector2d position_m{0.0, 0.0};
};

/// Local position of a geodetic point under a reference (projection, then the reference's position_m).
Eigen::Vector3d geodetic_to_local(const GeoReference& reference, double latitude_deg, double longitude_deg,
                                  double altitude_m);

/// Gust added to the steady wind (physics/wind.hpp computes the air's velocity).
enum class GustModel : std::uint8_t {
  none,
  one_minus_cos,  ///< a discrete gust: amplitude * (1 - cos(2 pi (t - start) / duration)) / 2 within the gust
  dryden,         ///< continuous turbulence: Dryden spectra (MIL-F-8785C), seeded
};
std::string_view to_string(GustModel model);

/// The world's "wind" block: the velocity of the air, world frame. Vehicles
/// feel it through their drag (docs/vehicles.md).
struct WindConfig {
  double speed_mps = 0.0;        ///< steady horizontal wind speed, [0, 100]
  double direction_deg = 0.0;    ///< where the steady wind blows toward, CCW from +x (east), degrees
  double vertical_mps = 0.0;     ///< steady vertical component (updraft > 0), [-20, 20]
  GustModel gust = GustModel::none;
  Eigen::Vector3d gust_amplitude_mps = Eigen::Vector3d::Zero();  ///< 1-cos: peak added velocity, world frame
  double gust_start_s = 0.0;     ///< 1-cos: when the gust begins
  double gust_duration_s = 2.0;  ///< 1-cos: how long it lasts, > 0
  double turbulence_intensity_mps = 0.0;  ///< Dryden: standard deviation of each component, [0, 20]
  double turbulence_length_m = 50.0;      ///< Dryden: length scale, > 0
  std::uint64_t seed = 0;        ///< turbulence stream, combined with the world seed
  /// The steady part as a vector, world frame.
  Eigen::Vector3d steady_velocity_mps() const;
};

struct WorldConfig {
  Eigen::Vector3d gravity_mps2{0.0, 0.0, -9.81};
  double physics_step_s = 1.0 / 240.0;  ///< fixed Bullet step
  double control_rate_hz = 60.0;        ///< controller and planner rate; divides 1/physics_step_s
  double sensor_rate_hz = 10.0;         ///< default rate of sensors that set none; divides 1/physics_step_s
  double time_limit_s = 600.0;          ///< an episode ends here with "timeout"
  GeoReference geo_reference;
  WindConfig wind;                      ///< none by default
  std::uint64_t seed = 0;               ///< master seed of everything random in a run, [0, 2^64-1]
};

/// Relative tolerance within which a rate's period counts as a whole number of physics steps.
inline constexpr double kRatePeriodTolerance = 1e-9;

/// Physics steps in one period of an event at `rate_hz` (control, a sensor)
/// with a fixed step of `physics_step_s`: 1 / (rate_hz * physics_step_s) when
/// that is a whole number >= 1 within kRatePeriodTolerance (relative), else 0
/// (the rate does not divide the physics rate, or is faster than it). Every
/// rate of a Scene from load_scene()/parse_scene() gives a value >= 1.
std::int64_t steps_per_period(double rate_hz, double physics_step_s);

/// Rates that divide the physics rate 1/physics_step_s, nearest `rate_hz`:
/// up to `each_side` at or above it and `each_side` below it, fastest first
/// (for 100 Hz at 1/240 s and 2 each side: 240, 120, 80, 60).
std::vector<double> dividing_rates_near(double rate_hz, double physics_step_s, int each_side = 2);

/// How a run of several vehicles ends (a scene's "end").
enum class EndRule {
  all,            ///< when every vehicle's mission has ended (default)
  first_failure,  ///< at the first vehicle's end other than reached; the others are stopped
};
std::string_view to_string(EndRule rule);

struct Scene {
  std::string name;            ///< file stem, or "name" from the file
  std::string source_path;     ///< file it was loaded from
  std::string source_sha256;   ///< hash of the file bytes, for provenance
  WorldConfig world;
  std::vector<Shape> shapes;
  std::vector<Frame> frames;
  std::vector<Mover> movers;
  std::vector<VehicleDef> vehicles;  ///< all simulated together, in this order
  EndRule end = EndRule::all;

  const Shape* find_shape(std::string_view alias) const;
  const Frame* find_frame(std::string_view alias) const;
  const VehicleDef* find_vehicle(std::string_view alias) const;
  /// Height of the highest heightfield or plane below (x, y) in the world
  /// frame; nullopt where there is no ground.
  std::optional<double> ground_height(double x, double y) const;
};

/// Height of one ground shape (heightfield or plane) below world (x, y);
/// nullopt for other shapes and where the shape has no ground there.
std::optional<double> ground_height_of(const Shape& shape, double x, double y);

/// A body that the physics moves during a run: a dynamic shape (Bullet
/// integrates it: it falls, is pushed, tips over) or a mover (kinematic, on
/// its path). Sensors and clearance see each where the world has it at that
/// instant, whatever its kind.
struct MovingBody {
  const Shape* shape = nullptr;  ///< geometry; shape->pose is its pose at t = 0
  std::int32_t id = 0;           ///< index into Scene::shapes, or -(1 + mover index)
};
/// The moving bodies of a scene: its dynamic shapes in scene order, then its
/// movers. World::moving_body_poses reports their poses in this order.
std::vector<MovingBody> moving_bodies(const Scene& scene);
/// Poses of moving_bodies() known without physics: movers where their path
/// has them at t_s, dynamic shapes where they start. For views of a scene
/// that have no world (`campo scan`, snapshots).
std::vector<Eigen::Isometry3d> scripted_poses(const Scene& scene, double t_s);

}  // namespace campo
