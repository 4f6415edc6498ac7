#pragma once
/// The Bullet world built from a Scene. It owns every Bullet object (RAII);
/// nothing outside sim/ sees Bullet types. Reset = build a new World from the
/// same Scene, which gives bit-identical results (in-place reset would not).
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "sim/scene.hpp"

class btRigidBody;
class btDiscreteDynamicsWorld;

namespace campo {

/// Bullet user index of bodies that belong to vehicles (scene shapes carry
/// their index in Scene::shapes, movers -(1 + mover index)).
inline constexpr int kVehicleBodyTag = -2000000000;

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

  /// Terrain height at world (x, y); nullopt where there is no ground.
  std::optional<double> terrain_height(double x_m, double y_m) const;

  /// Closest hit along the segment from `from` to `to` (Bullet ray test).
  std::optional<WorldRayHit> ray_test(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;

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
