#include "render/snapshot.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>

#include "sensors/osmesa_gl.hpp"

namespace campo {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr int kSamples = 4;          // multisampling, for smooth edges
constexpr int kTubeSides = 10;       // around the trajectory tube
const Color kSky{0.63, 0.78, 0.94};
const Color kTrajectory{0.95, 0.12, 0.08};
const Color kQuadrotor{0.12, 0.30, 0.85};
const Color kRover{0.95, 0.72, 0.05};

constexpr const char* kVertexShader = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 0) uniform mat4 model;  // world from mesh; rigid
layout(location = 1) uniform mat4 view_projection;
out vec3 world_position;
out vec3 world_normal;
void main() {
  vec4 p = model * vec4(position, 1.0);
  world_position = p.xyz;
  world_normal = mat3(model) * normal;
  gl_Position = view_projection * p;
}
)";

// Lambert with ambient under a sun over the viewer's shoulder, an optional
// height tint (terrain), and fog towards the sky so that far ground meets
// the horizon softly.
constexpr const char* kFragmentShader = R"(#version 450 core
in vec3 world_position;
in vec3 world_normal;
layout(location = 2) uniform vec3 colour;
layout(location = 3) uniform float ambient;
layout(location = 4) uniform vec2 tint_heights;  // low, high; no tint unless high > low
layout(location = 5) uniform vec3 eye;
layout(location = 6) uniform vec3 sky;
layout(location = 7) uniform vec2 fog_m;         // fog starts, sky reached
layout(location = 8) uniform vec3 sun;           // unit, towards the sun
out vec4 frag;
void main() {
  vec3 n = normalize(world_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 base = colour;
  if (tint_heights.y > tint_heights.x) {
    float t = clamp((world_position.z - tint_heights.x) / (tint_heights.y - tint_heights.x), 0.0, 1.0);
    base *= mix(vec3(0.78, 0.88, 0.70), vec3(1.10, 1.04, 0.92), t);
  }
  vec3 lit = base * (ambient + (1.0 - ambient) * max(dot(n, sun), 0.0));
  float fog = clamp((distance(world_position, eye) - fog_m.x) / (fog_m.y - fog_m.x), 0.0, 1.0);
  frag = vec4(mix(lit, sky, fog), 1.0);
}
)";

Eigen::Matrix4f look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target, const Eigen::Vector3d& up) {
  const Eigen::Vector3d f = (target - eye).normalized();
  const Eigen::Vector3d s = f.cross(up).normalized();
  const Eigen::Vector3d u = s.cross(f);
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
  view.block<1, 3>(0, 0) = s.transpose();
  view.block<1, 3>(1, 0) = u.transpose();
  view.block<1, 3>(2, 0) = -f.transpose();
  view.block<3, 1>(0, 3) = -view.block<3, 3>(0, 0) * eye;
  return view.cast<float>();
}

Eigen::Matrix4f perspective(double fov_y_deg, double aspect, double near, double far) {
  const double t = 1.0 / std::tan(0.5 * fov_y_deg * kDegToRad);
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = t / aspect;
  p(1, 1) = t;
  p(2, 2) = -(far + near) / (far - near);
  p(2, 3) = -2.0 * far * near / (far - near);
  p(3, 2) = -1.0;
  return p.cast<float>();
}

// A closed-sided tube of `radius` along the polyline; rings are carried
// along by parallel transport so the tube does not twist.
SceneMesh trajectory_tube(const std::vector<Eigen::Vector3d>& points, double radius) {
  SceneMesh tube;
  std::vector<Eigen::Vector3d> path;
  for (const Eigen::Vector3d& p : points) {
    if (path.empty() || (p - path.back()).norm() > radius) path.push_back(p);
  }
  if (path.size() < 2) return tube;
  tube.positions.reserve(path.size() * kTubeSides);
  tube.normals.reserve(path.size() * kTubeSides);
  tube.indices.reserve((path.size() - 1) * kTubeSides * 6);
  Eigen::Vector3d side = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Eigen::Vector3d& prev = path[i > 0 ? i - 1 : i];
    const Eigen::Vector3d& next = path[i + 1 < path.size() ? i + 1 : i];
    const Eigen::Vector3d tangent = (next - prev).normalized();
    side -= side.dot(tangent) * tangent;
    if (side.norm() < 1e-6) side = tangent.unitOrthogonal();
    side.normalize();
    const Eigen::Vector3d other = tangent.cross(side);
    for (int k = 0; k < kTubeSides; ++k) {
      const double a = 2.0 * std::numbers::pi * k / kTubeSides;
      const Eigen::Vector3d n = std::cos(a) * side + std::sin(a) * other;
      tube.positions.push_back((path[i] + radius * n).cast<float>());
      tube.normals.push_back(n.cast<float>());
    }
  }
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const auto ring = static_cast<std::uint32_t>(i * kTubeSides);
    for (std::uint32_t k = 0; k < kTubeSides; ++k) {
      const std::uint32_t a = ring + k;
      const std::uint32_t b = ring + (k + 1) % kTubeSides;
      // (side, other, tangent) is right-handed, so this winding faces out.
      tube.indices.insert(tube.indices.end(), {a, b, b + kTubeSides, a, b + kTubeSides, a + kTubeSides});
    }
  }
  return tube;
}

void validate(const SnapshotCamera& c) {
  const Eigen::Vector3d view = c.target_m - c.eye_m;
  if (!(view.norm() > 0.0)) throw std::invalid_argument("snapshot camera: eye and target coincide");
  if (!(view.normalized().cross(c.up).norm() > 1e-9)) {
    throw std::invalid_argument("snapshot camera: 'up' is zero or along the line of sight");
  }
  if (!(c.fov_deg > 0.0 && c.fov_deg < 180.0)) {
    throw std::invalid_argument("snapshot camera: fov_deg must be in (0, 180)");
  }
  if (c.width_px < 1 || c.height_px < 1) {
    throw std::invalid_argument("snapshot camera: width_px and height_px must be >= 1");
  }
}

}  // namespace

cv::Mat render_snapshot(const Scene& scene, const SceneMesh& mesh, const SnapshotCamera& camera,
                        const std::vector<Eigen::Vector3d>& trajectory_m,
                        const std::optional<Eigen::Isometry3d>& vehicle_pose, VehicleType vehicle_type) {
  return render_snapshot(scene, mesh, camera, {SnapshotVehicle{trajectory_m, vehicle_pose, vehicle_type, std::nullopt}});
}

cv::Mat render_snapshot(const Scene& scene, const SceneMesh& mesh, const SnapshotCamera& camera,
                        const std::vector<SnapshotVehicle>& vehicles) {
  validate(camera);
  const double distance = (camera.target_m - camera.eye_m).norm();

  // Everything drawn besides the scene: the trajectory tubes and the vehicle boxes.
  std::vector<SceneMesh> tubes;
  Scene marker_scene;
  for (const SnapshotVehicle& vehicle : vehicles) {
    tubes.push_back(trajectory_tube(vehicle.trajectory_m, std::clamp(0.004 * distance, 0.03, 0.5)));
    if (!vehicle.pose) continue;
    Shape box;
    box.type = ShapeType::cuboid;
    box.pose = *vehicle.pose;
    const bool quadrotor = vehicle.type == VehicleType::quadrotor;
    box.size_m = quadrotor ? Eigen::Vector3d(0.6, 0.6, 0.12) : Eigen::Vector3d(1.5, 1.0, 0.35);
    box.color = vehicle.color.value_or(quadrotor ? kQuadrotor : kRover);
    marker_scene.shapes.push_back(box);
  }
  const SceneMesh marker = build_scene_mesh(marker_scene);

  // Declared first, destroyed last: the GL names below die in it.
  OsmesaContext context;
  GLint max_size = 0;
  gl().GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (camera.width_px > max_size || camera.height_px > max_size) {
    throw std::invalid_argument("snapshot camera: at most " + std::to_string(max_size) + " px a side");
  }
  const GlProgram program = make_program(kVertexShader, kFragmentShader);
  const GpuMesh scene_gpu = upload_mesh(mesh, true);
  std::vector<GpuMesh> tube_gpus;
  for (const SceneMesh& tube : tubes) tube_gpus.push_back(upload_mesh(tube, true));
  const GpuMesh marker_gpu = upload_mesh(marker, true);
  const Framebuffer multisampled =
      make_framebuffer(camera.width_px, camera.height_px, GL_RGBA8, GL_DEPTH_COMPONENT32F, kSamples);
  const Framebuffer resolved = make_framebuffer(camera.width_px, camera.height_px, GL_RGBA8, 0);

  gl().BindFramebuffer(GL_FRAMEBUFFER, multisampled.fbo.id());
  gl().Viewport(0, 0, camera.width_px, camera.height_px);
  gl().Enable(GL_DEPTH_TEST);
  gl().Enable(GL_MULTISAMPLE);
  gl().Disable(GL_CULL_FACE);
  gl().ClearColor(static_cast<float>(kSky.r), static_cast<float>(kSky.g), static_cast<float>(kSky.b), 1.0f);
  gl().Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

  // Fog from a few view distances out; nothing beyond it needs drawing.
  const double fog_start = 2.0 * distance;
  const double fog_end = 6.0 * distance;
  const Eigen::Matrix4f view_projection =
      perspective(camera.fov_deg, static_cast<double>(camera.width_px) / camera.height_px,
                  std::max(0.01, 0.002 * distance), fog_end) *
      look_at(camera.eye_m, camera.target_m, camera.up);
  gl().UseProgram(program.id());
  gl().UniformMatrix4fv(1, 1, GL_FALSE, view_projection.data());
  gl().Uniform3f(5, static_cast<float>(camera.eye_m.x()), static_cast<float>(camera.eye_m.y()),
              static_cast<float>(camera.eye_m.z()));
  gl().Uniform3f(6, static_cast<float>(kSky.r), static_cast<float>(kSky.g), static_cast<float>(kSky.b));
  gl().Uniform2f(7, static_cast<float>(fog_start), static_cast<float>(fog_end));
  // High, behind and a little to the right of the viewer, so that what faces
  // the camera is lit and the sides are shaded apart.
  Eigen::Vector3d back = camera.eye_m - camera.target_m;
  back.z() = 0.0;
  back = back.norm() > 1e-9 ? back.normalized() : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3f sun = (0.55 * back + 0.3 * up.cross(back) + 0.8 * up).normalized().cast<float>();
  gl().Uniform3f(8, sun.x(), sun.y(), sun.z());

  const auto draw = [](const MeshPart& part, const Eigen::Isometry3d& model, float ambient,
                       const Eigen::Vector2f& tint_heights) {
    const Eigen::Matrix4f m = model.matrix().cast<float>();
    gl().UniformMatrix4fv(0, 1, GL_FALSE, m.data());
    const Eigen::Vector3f colour = Eigen::Vector3d(part.color.r, part.color.g, part.color.b).cast<float>();
    gl().Uniform3f(2, colour.x(), colour.y(), colour.z());
    gl().Uniform1f(3, ambient);
    gl().Uniform2f(4, tint_heights.x(), tint_heights.y());
    gl().DrawElements(GL_TRIANGLES, static_cast<GLsizei>(part.index_count), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(std::size_t{part.first_index} * sizeof(std::uint32_t)));
  };
  const Eigen::Vector2f no_tint(1.0f, 0.0f);
  constexpr float kAmbient = 0.35f;

  gl().BindVertexArray(scene_gpu.vao.id());
  for (const MeshPart& part : mesh.parts) {
    Eigen::Vector2f tint = no_tint;
    const Shape& shape = scene.shapes[static_cast<std::size_t>(part.shape)];
    if (shape.type == ShapeType::heightfield) {
      const double z = shape.pose.translation().z();
      tint = Eigen::Vector2d(z + shape.terrain->min_height_m(), z + shape.terrain->max_height_m()).cast<float>();
    }
    draw(part, Eigen::Isometry3d::Identity(), kAmbient, tint);
  }
  const std::vector<Eigen::Isometry3d> body_poses = scripted_poses(scene, 0.0);
  for (std::size_t i = 0; i < mesh.moving_parts.size(); ++i) {
    draw(mesh.moving_parts[i], body_poses[i], kAmbient, no_tint);
  }
  for (std::size_t i = 0; i < tubes.size(); ++i) {
    if (tubes[i].indices.empty()) continue;
    gl().BindVertexArray(tube_gpus[i].vao.id());
    const MeshPart part{0, static_cast<std::uint32_t>(tubes[i].indices.size()), vehicles[i].color.value_or(kTrajectory), 0};
    draw(part, Eigen::Isometry3d::Identity(), 0.6f, no_tint);
  }
  gl().BindVertexArray(marker_gpu.vao.id());
  for (const MeshPart& part : marker.parts) draw(part, Eigen::Isometry3d::Identity(), kAmbient, no_tint);

  // Resolve the samples, then read BGR rows (bottom-up in GL) into OpenCV's order.
  gl().BindFramebuffer(GL_READ_FRAMEBUFFER, multisampled.fbo.id());
  gl().BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolved.fbo.id());
  gl().BlitFramebuffer(0, 0, camera.width_px, camera.height_px, 0, 0, camera.width_px, camera.height_px,
                    GL_COLOR_BUFFER_BIT, GL_NEAREST);
  gl().BindFramebuffer(GL_READ_FRAMEBUFFER, resolved.fbo.id());
  cv::Mat image(camera.height_px, camera.width_px, CV_8UC3);
  gl().PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl().ReadPixels(0, 0, camera.width_px, camera.height_px, GL_BGR, GL_UNSIGNED_BYTE, image.data);
  check_gl("rendering a snapshot");
  cv::flip(image, image, 0);
  return image;
}

SnapshotCamera default_snapshot_camera(const Scene& scene, const std::vector<Eigen::Vector3d>& trajectory_m) {
  // What to frame: the trajectory, else the objects and vehicles.
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : trajectory_m) box.extend(p);
  if (box.isEmpty()) {
    for (const Shape& shape : scene.shapes) {
      if (shape.type == ShapeType::mesh) {
        // Its vertices' bounds: a file's origin need not lie near its geometry.
        for (int corner = 0; corner < 8; ++corner) {
          box.extend(shape.pose * shape.mesh->bounds_m.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)));
        }
      } else if (shape.type != ShapeType::plane && shape.type != ShapeType::heightfield) {
        box.extend(shape.pose.translation());
      }
    }
    for (const VehicleDef& vehicle : scene.vehicles) box.extend(vehicle.pose.translation());
  }
  if (box.isEmpty()) box.extend(Eigen::Vector3d::Zero());

  // Behind: against the direction from the first to the last point (+x if none).
  Eigen::Vector3d heading = Eigen::Vector3d::UnitX();
  if (trajectory_m.size() >= 2) {
    Eigen::Vector3d travel = trajectory_m.back() - trajectory_m.front();
    travel.z() = 0.0;
    if (travel.norm() > 1e-6) heading = travel.normalized();
  }
  SnapshotCamera camera;
  constexpr double kElevation_deg = 35.0;
  constexpr double kMinRadius_m = 4.0;
  const double radius = std::max(0.5 * box.diagonal().norm(), kMinRadius_m);
  // Far enough that a sphere around the box fits the vertical field of view, with a margin.
  const double distance = 1.15 * radius / std::sin(0.5 * camera.fov_deg * kDegToRad);
  const double elevation = kElevation_deg * kDegToRad;
  camera.target_m = box.center();
  camera.eye_m = camera.target_m - distance * std::cos(elevation) * heading +
                 distance * std::sin(elevation) * Eigen::Vector3d::UnitZ();
  return camera;
}

}  // namespace campo
