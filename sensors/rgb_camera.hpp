#pragma once
/// The OSMesa colour camera ("rgb_camera" sensor): the scene mesh rendered
/// off-screen through a pinhole, each shape in its colour.
///
/// Image: `cols` x `rows` pixels, row 0 at the top and column 0 at the left
/// as seen looking along the camera's x axis (so column 0 looks towards +y,
/// the camera's left). Square pixels: the horizontal field is fov_h_deg, the
/// vertical one 2 atan(tan(fov_h_deg / 2) rows / cols). Pixel (col, row)
/// shows what lies along the ray through its centre, in the camera frame
///   (1, -(2 (col + 0.5) / cols - 1) tan(fov_h / 2), (1 - 2 (row + 0.5) / rows) tan(fov_v / 2)).
///
/// Shading: Lambert under a sun fixed in the world (kSunDirection, from 60 deg
/// above the horizon, azimuth 30 deg from +x towards +y) plus ambient light
/// (kAmbient of full intensity): a surface of colour c facing the sun is c,
/// one turned away from it (or in the sun's plane) is kAmbient c. Surfaces are
/// two-sided (a face seen from behind is lit as if turned to the eye). There
/// are no shadows, textures or reflections; heightfields and planes take
/// their shape's colour and show their relief through the shading of their
/// vertex normals. Surfaces nearer than min_range_m or farther than
/// max_range_m along the pixel's ray are not drawn (as the depth camera skips
/// them); where nothing is drawn the pixel is the sky colour.
///
/// Noise (noise_stddev > 0): each channel of each pixel gets an independent
/// Gaussian draw of standard deviation noise_stddev * 255, rounded and
/// clamped to [0, 255], from a stream seeded by the world seed and the
/// camera's seed (Rng::derive_seed), continued image after image.
#include <cstdint>
#include <memory>

#include <Eigen/Core>

#include "campo/rgb_camera.hpp"
#include "scene/scene_mesh.hpp"

namespace campo {

/// Unit vector towards the sun, world frame (z up).
inline const Eigen::Vector3d kSunDirection(0.5 * 0.8660254037844386, 0.5 * 0.5, 0.8660254037844386);
/// Share of full light every surface gets, facing the sun or not.
inline constexpr double kAmbient = 0.35;

/// A colour camera for `def` rendering `mesh`, a scene's mesh (uploaded once;
/// not kept). Throws std::invalid_argument for a definition it cannot render
/// and std::runtime_error when no OSMesa context can be made.
std::unique_ptr<RgbCamera> make_rgb_camera(const SceneMesh& mesh, const RgbCameraDef& def, std::uint64_t world_seed);
/// The same, building the scene's mesh for this camera alone.
std::unique_ptr<RgbCamera> make_rgb_camera(const Scene& scene, const RgbCameraDef& def, std::uint64_t world_seed);

}  // namespace campo
