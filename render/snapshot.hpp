#pragma once
/// Colour snapshots (SPEC §9): a perspective view of a scene rendered
/// off-screen with OSMesa, with a run's trajectory and the vehicle drawn in.
#include <optional>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "campo/scene.hpp"
#include "scene/scene_mesh.hpp"

namespace campo {

/// Where the snapshot is taken from (world frame).
struct SnapshotCamera {
  Eigen::Vector3d eye_m = Eigen::Vector3d(-20.0, 0.0, 15.0);  ///< camera position, metres
  Eigen::Vector3d target_m = Eigen::Vector3d::Zero();         ///< point at the image centre, metres
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();              ///< world direction shown upward; not along the view
  double fov_deg = 60.0;   ///< vertical field of view, (0, 180)
  int width_px = 1280;     ///< >= 1
  int height_px = 720;     ///< >= 1
};

/// Renders `mesh` (built from `scene`) seen from `camera`: terrain shaded with
/// a height tint, objects in their scene colours, movers at their start
/// positions, the trajectory as a thick tube, and a box of the vehicle's
/// size at `vehicle_pose` if given, under a sky background. Returns an 8-bit
/// BGR image of width_px x height_px (top row first), the same bytes for the
/// same inputs. Throws std::invalid_argument for a bad camera and
/// std::runtime_error when no OSMesa context can be made.
cv::Mat render_snapshot(const Scene& scene, const SceneMesh& mesh, const SnapshotCamera& camera,
                        const std::vector<Eigen::Vector3d>& trajectory_m,
                        const std::optional<Eigen::Isometry3d>& vehicle_pose, VehicleType vehicle_type);

/// One vehicle of a snapshot of several: its trajectory, the box of its type's
/// preset size at `pose` if given, both in `color` when given (else the
/// trajectory red and the box blue for a quadrotor, amber for a rover).
struct SnapshotVehicle {
  std::vector<Eigen::Vector3d> trajectory_m;
  std::optional<Eigen::Isometry3d> pose;
  VehicleType type = VehicleType::quadrotor;
  std::optional<Color> color;
};
/// The snapshot of several vehicles, as render_snapshot above draws one: each
/// trajectory a tube and each vehicle a box, in its colour.
cv::Mat render_snapshot(const Scene& scene, const SceneMesh& mesh, const SnapshotCamera& camera,
                        const std::vector<SnapshotVehicle>& vehicles);

/// A camera that frames the trajectory (or, without one, the scene's objects
/// and vehicles) from above and behind its direction of travel, about 35 deg
/// above the horizontal.
SnapshotCamera default_snapshot_camera(const Scene& scene, const std::vector<Eigen::Vector3d>& trajectory_m);

}  // namespace campo
