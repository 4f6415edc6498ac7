#pragma once
/// The OSMesa depth camera (SPEC §6, §9): the sensor's angular grid rendered
/// off-screen from the scene mesh, producing the same range image and depth
/// map as the ray-cast LIDAR (ranges along each pixel's ray, equiangular in
/// azimuth and elevation), so planners take either source.
#include <memory>

#include "campo/range_sensor.hpp"
#include "scene/scene_mesh.hpp"

namespace campo {

/// A depth camera for `def` (type depth_camera, validated by the scene loader)
/// rendering `mesh`, the mesh of `scene` (uploaded once; not kept).
/// Throws std::invalid_argument for a definition it cannot render (explicit
/// beams, noise or dropout, too wide a field of view) and std::runtime_error
/// when no OSMesa context can be made.
std::unique_ptr<RangeSensor> make_depth_camera(const Scene& scene, const SceneMesh& mesh, const SensorDef& def);
/// The same, building the scene's mesh for this camera alone.
std::unique_ptr<RangeSensor> make_depth_camera(const Scene& scene, const SensorDef& def);

}  // namespace campo
