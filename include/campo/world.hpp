#pragma once
/// The Bullet world built from a Scene. It owns every Bullet object (RAII);
/// nothing outside physics/ and vehicles/ sees Bullet types. Reset = build a new World from the
/// same Scene, which gives bit-identical results (in-place reset would not).
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "campo/scene.hpp"

class btRigidBody;
class btDiscreteDynamicsWorld;

namespace campo {

/// Bullet user index of the bodies of the first vehicle (scene shapes carry
/// their index in Scene::shapes, movers -(1 + mover index)): a vehicle body
/// that must touch nothing, ground included (a quadrotor, a rover's chassis)...
inline constexpr int kVehicleBodyTag = -2000000000;
/// ... and one that may rest on the ground but touch nothing else (a wheel).
inline constexpr int kVehicleWheelTag = -2000000001;
/// Vehicles a world may hold: their tags stay within an int below every other tag.
inline constexpr std::size_t kMaxVehicles = 1000000;

/// The user index of a body of vehicle `vehicle` (the order it joined the
/// world, World::join_vehicle): kVehicleBodyTag and kVehicleWheelTag for the
/// first, two lower for each next. Also how a vehicle is named as an obstacle
/// (Clearance::obstacle, Touch::body) to the others: its body tag.
constexpr int vehicle_tag(std::size_t vehicle, bool wheel) {
  return kVehicleBodyTag - 2 * static_cast<int>(vehicle) - (wheel ? 1 : 0);
}
/// Whether a user index or obstacle id is a vehicle's (vehicle_tag).
constexpr bool is_vehicle_tag(int tag) { return tag <= kVehicleBodyTag; }
/// The vehicle a vehicle tag belongs to.
constexpr std::size_t vehicle_of_tag(int tag) { return static_cast<std::size_t>((kVehicleBodyTag - tag) / 2); }
/// Whether a vehicle tag is a wheel's (may rest on the ground).
constexpr bool is_wheel_tag(int tag) { return (kVehicleBodyTag - tag) % 2 == 1; }

/// What a vehicle's collision shapes touch, and where.
struct Touch {
  /// Index into Scene::shapes (a plane or heightfield when `ground`),
  /// -(1 + mover index), or another vehicle's vehicle_tag, as Clearance::obstacle.
  int body = 0;
  bool ground = false;  ///< a plane or heightfield
  /// The point of the touched body's surface nearest the vehicle (the
  /// deepest when they overlap), world frame, where the physics has them
  /// at the end of the step.
  Eigen::Vector3d point_m = Eigen::Vector3d::Zero();
};

/// Signed distances from a vehicle's collision shapes to the other collision
/// shapes of the world (Bullet GJK, EPA when penetrating): negative when
/// they overlap, 0 when they touch. Ground (planes, heightfields) is kept
/// apart from obstacles (every other shape: static, dynamic, movers, and the
/// other vehicles' bodies).
struct Clearance {
  double obstacle_m = std::numeric_limits<double>::infinity();  ///< to the nearest obstacle
  /// Which: index into Scene::shapes, -(1 + mover index) or another
  /// vehicle's vehicle_tag; valid when finite.
  int obstacle = -1;
  /// From the bodies that may not touch the ground (kVehicleBodyTag) to the ground.
  double ground_m = std::numeric_limits<double>::infinity();
  /// Bullet's narrow phase reported a contact point within kContact_m
  /// between a vehicle body and something it may not touch in this step.
  /// (A body pushed by a mover ends each step apart from it by the mover's
  /// travel in the step, yet they are in contact.)
  bool contact = false;
  static constexpr double kContact_m = 1e-3;
  /// When touching(): what (Bullet's contact when there is one, else the
  /// deeper overlap) and where; measured only then, so a step that touches
  /// nothing costs nothing more.
  std::optional<Touch> touch;
  /// The collision shapes touch: what the closed loop counts as a collision.
  /// Overlapping shapes (a clearance <= 0) always touch.
  bool touching() const { return contact || obstacle_m <= 0.0 || ground_m <= 0.0; }
};

/// State of one rigid body, world frame.
struct BodyState {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d linear_velocity_mps = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_radps = Eigen::Vector3d::Zero();
};

/// Closest hit of a Bullet ray test.
struct WorldRayHit {
  double distance_m = 0.0;
  Eigen::Vector3d point_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  int shape = -1;  ///< index into Scene::shapes, or -(1 + mover index)
};

class World {
 public:
  /// Builds the Bullet world. Keeps a reference to `scene`, which must outlive it.
  explicit World(const Scene& scene);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  const Scene& scene() const { return scene_; }
  /// Simulation time, seconds (steps * physics_step_s).
  double time_s() const;
  std::int64_t step_count() const;

  /// Advances by exactly one fixed physics step; movers follow their paths.
  void step();

  /// The velocity of the air at `position_m` now, world frame: the scene's
  /// steady wind plus its gusts (WorldConfig::wind, physics/wind.hpp).
  Eigen::Vector3d wind_mps(const Eigen::Vector3d& position_m) const;

  /// Terrain height at world (x, y); nullopt where there is no ground.
  std::optional<double> terrain_height(double x_m, double y_m) const;

  /// Closest hit along the segment from `from` to `to` (Bullet ray test).
  std::optional<WorldRayHit> ray_test(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;

  /// Poses of the scene's moving bodies (moving_bodies(scene): dynamic shapes,
  /// then movers) where the physics has them now, world frame; `out` reused.
  void moving_body_poses(std::vector<Eigen::Isometry3d>& out) const;

  /// The number of the next vehicle to join the world (0, 1, ...), which
  /// tags its bodies with vehicle_tag(number, ...). Called by each vehicle as
  /// it is built; the closed loop builds the scene's vehicles in scene
  /// order, so a vehicle's number is its index in Scene::vehicles.
  std::size_t join_vehicle();

  /// Clearance of vehicle `vehicle`'s bodies now; the other vehicles are
  /// moving obstacles to it. A distance at or beyond its cutoff is reported
  /// as +infinity (the nearest is at least that far); by default both are
  /// exact at any distance.
  /// Without `other_vehicles` the distances to the other vehicles are left
  /// out (the closed loop measures each pair once, vehicle_distance); a
  /// contact with one still makes it touching, naming it.
  Clearance vehicle_clearance(std::size_t vehicle,
                              double obstacle_cutoff_m = std::numeric_limits<double>::infinity(),
                              double ground_cutoff_m = std::numeric_limits<double>::infinity(),
                              bool other_vehicles = true) const;
  /// The same for the first vehicle (a world of one vehicle).
  Clearance vehicle_clearance(double obstacle_cutoff_m = std::numeric_limits<double>::infinity(),
                              double ground_cutoff_m = std::numeric_limits<double>::infinity()) const {
    return vehicle_clearance(0, obstacle_cutoff_m, ground_cutoff_m);
  }

  /// Signed distance between the collision shapes of vehicles `a` and `b`
  /// now (negative when they overlap); +infinity when it is at least
  /// `cutoff_m` (a bound from their bounding spheres skips the exact query).
  /// `point_on_b`, when given and the distance is below the cutoff, is set to
  /// the point of b's shapes nearest a's (the deepest when they overlap).
  double vehicle_distance(std::size_t a, std::size_t b, double cutoff_m = std::numeric_limits<double>::infinity(),
                          Eigen::Vector3d* point_on_b = nullptr) const;

  /// The collision shapes of vehicle `vehicle` as scene shapes (boxes as
  /// cuboids, spheres as spheres), posed where the physics has them now,
  /// named "<alias>/body" and "<alias>/wheel<i>": what the other vehicles'
  /// sensors see of it.
  std::vector<Shape> vehicle_shapes(std::size_t vehicle, const std::string& alias) const;
  /// Appends the poses of those shapes now, in the same order; `out` reused.
  void append_vehicle_poses(std::size_t vehicle, std::vector<Eigen::Isometry3d>& out) const;

  /// State of scene shape `shape_index` (static shapes: their scene pose, at rest).
  BodyState shape_state(int shape_index) const;

  /// Deterministic digest of the state of every body in the Bullet world,
  /// vehicles included (positions, orientations, velocities, bit patterns).
  std::uint64_t state_hash() const;

  /// For the vehicles module: the underlying Bullet world.
  btDiscreteDynamicsWorld& bullet();

 private:
  struct Impl;
  const Scene& scene_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace campo
