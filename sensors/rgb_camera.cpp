#include "sensors/rgb_camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "campo/random.hpp"
#include "core/angles.hpp"
#include "sensors/osmesa_gl.hpp"
#include "sensors/view_culling.hpp"

namespace campo {

namespace {

constexpr double kMaxFov_deg = 170.0;
constexpr int kMaxSide_px = 4096;

constexpr const char* kColourVertexShader = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 0) uniform mat4 model_view;  // eye from mesh; rigid
layout(location = 1) uniform mat4 projection;
out vec3 eye_position;
out vec3 eye_normal;
void main() {
  vec4 eye = model_view * vec4(position, 1.0);
  eye_position = eye.xyz;
  eye_normal = mat3(model_view) * normal;
  gl_Position = projection * eye;
}
)";

// Lambert plus ambient, in the eye frame. The projection flips y so that GL's
// first row read is the image's top row; that turns counter-clockwise faces
// (seen from outside) clockwise on screen, so GL calls the faces seen from
// outside back faces, and the normal turns towards the eye on front faces.
constexpr const char* kColourFragmentShader = R"(#version 450 core
in vec3 eye_position;
in vec3 eye_normal;
layout(location = 2) uniform vec3 colour;
layout(location = 3) uniform vec3 sun;       // unit, towards the sun, eye frame
layout(location = 4) uniform vec2 range_sq;  // (min, max) range along the ray, squared
layout(location = 5) uniform float ambient;
out vec4 frag;
void main() {
  float r2 = dot(eye_position, eye_position);
  if (r2 < range_sq.x || r2 > range_sq.y) discard;
  vec3 n = normalize(eye_normal);
  if (gl_FrontFacing) n = -n;
  frag = vec4(colour * (ambient + (1.0 - ambient) * max(dot(n, sun), 0.0)), 1.0);
}
)";

void validate_rgb_camera(const RgbCameraDef& def) {
  const RgbCameraConfig& c = def.camera;
  const std::string name = "colour camera '" + def.alias + "': ";
  if (c.cols < 1 || c.rows < 1 || c.cols > kMaxSide_px || c.rows > kMaxSide_px) {
    throw std::invalid_argument(name + "needs [1, " + std::to_string(kMaxSide_px) + "] columns and rows");
  }
  if (!(c.fov_h_deg > 0.0 && c.fov_h_deg <= kMaxFov_deg)) {
    throw std::invalid_argument(name + "needs a field of view in (0, " +
                                std::to_string(static_cast<int>(kMaxFov_deg)) + "] deg");
  }
  if (!(c.min_range_m >= 0.0 && c.min_range_m < c.max_range_m && std::isfinite(c.max_range_m))) {
    throw std::invalid_argument(name + "needs 0 <= min_range_m < max_range_m");
  }
  if (!(c.noise_stddev >= 0.0 && c.noise_stddev <= 1.0)) {
    throw std::invalid_argument(name + "needs noise_stddev in [0, 1]");
  }
}

// A colour in [0, 1] as GL writes it to 8 bits, and back as the exact float
// that writes it (so the sky colour reads back exactly).
std::uint8_t to_byte(double value) { return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0, 1.0) * 255.0)); }

class OsmesaRgbCamera final : public RgbCamera {
 public:
  OsmesaRgbCamera(const SceneMesh& mesh, const RgbCameraDef& def, std::uint64_t world_seed);
  ~OsmesaRgbCamera() override { context_.bind(); }
  OsmesaRgbCamera(const OsmesaRgbCamera&) = delete;
  OsmesaRgbCamera& operator=(const OsmesaRgbCamera&) = delete;

  const RgbCameraDef& def() const override { return def_; }
  void render(const Eigen::Isometry3d& camera_pose, double time_s, std::span<const Eigen::Isometry3d> body_poses,
              RgbImage& out) override;

 private:
  void flush(std::uint32_t part);
  void add_noise(std::vector<std::uint8_t>& rgb);

  RgbCameraDef def_;
  double half_width_ = 1.0;   // tan of the half-angle to the image's right edge
  double half_height_ = 1.0;  // ... and to its top edge
  ViewVolume view_volume_;
  std::vector<Chunk> chunks_;            // static geometry, index-buffer order, part = index into colours_
  std::vector<Chunk> mover_chunks_;      // one per moving body, shape frame
  std::vector<Eigen::Vector3f> colours_;        // static parts'
  std::vector<Eigen::Vector3f> mover_colours_;  // moving bodies'
  DrawRuns draw_runs_;                   // scratch for one multi-draw of one part
  Rng rng_;

  // GL objects last: they are released (context current) before the context.
  OsmesaContext context_;
  GlProgram program_;
  GpuMesh mesh_;
  Framebuffer target_;
};

OsmesaRgbCamera::OsmesaRgbCamera(const SceneMesh& mesh, const RgbCameraDef& def, std::uint64_t world_seed)
    : def_(def), rng_(Rng::derive_seed(world_seed, def.camera.seed)) {
  const RgbCameraConfig& c = def_.camera;
  half_width_ = std::tan(0.5 * c.fov_h_deg * kDegToRad);
  half_height_ = half_width_ * c.rows / c.cols;
  view_volume_ = ViewVolume(half_width_, half_height_, c.max_range_m);
  chunks_ = cut_into_chunks(mesh, mesh.parts, kCullChunkTriangles);
  for (const MeshPart& part : mesh.parts) {
    colours_.push_back(Eigen::Vector3d(part.color.r, part.color.g, part.color.b).cast<float>());
  }
  for (const MeshPart& part : mesh.moving_parts) {
    mover_chunks_.push_back(bound(mesh, part.first_index, part.index_count));
    mover_colours_.push_back(Eigen::Vector3d(part.color.r, part.color.g, part.color.b).cast<float>());
  }
  draw_runs_.reserve(chunks_.size());

  check_render_size(c.cols, c.rows, "colour camera '" + def_.alias + "'");
  // The context is this camera's alone, so its state is set once here.
  program_ = make_program(kColourVertexShader, kColourFragmentShader);
  mesh_ = upload_mesh(mesh, true);
  target_ = make_framebuffer(c.cols, c.rows, GL_RGBA8, GL_DEPTH_COMPONENT32F);
  use_reversed_depth(c.cols, c.rows);
  gl().Disable(GL_CULL_FACE);
  // The sky, as the exact float that GL writes as its 8-bit value.
  const auto sky = [](double v) { return static_cast<float>(to_byte(v)) / 255.0f; };
  gl().ClearColor(sky(c.sky.r), sky(c.sky.g), sky(c.sky.b), 1.0f);
  // The near plane cuts at the minimum range along the most oblique ray; the
  // fragment shader removes what lies nearer along its own ray. The far plane
  // at the maximum range cuts nothing within range along any ray.
  const double cos_corner = 1.0 / std::sqrt(1.0 + half_width_ * half_width_ + half_height_ * half_height_);
  const double near_m = std::max(c.min_range_m * cos_corner, kSmallestNear_m);
  Eigen::Matrix4f projection = reversed_depth_projection(half_width_, half_height_, near_m, c.max_range_m);
  projection.row(1) *= -1.0f;  // image rows top-down in GL's bottom-up framebuffer
  gl().UseProgram(program_.id());
  gl().UniformMatrix4fv(1, 1, GL_FALSE, projection.data());
  gl().Uniform2f(4, static_cast<float>(c.min_range_m * c.min_range_m),
                 static_cast<float>(c.max_range_m * c.max_range_m));
  gl().Uniform1f(5, static_cast<float>(kAmbient));
  check_gl("setting up the colour camera");
}

// Draws the runs gathered for static part `part`.
void OsmesaRgbCamera::flush(std::uint32_t part) {
  if (draw_runs_.empty()) return;
  const Eigen::Vector3f& colour = colours_[part];
  gl().Uniform3f(2, colour.x(), colour.y(), colour.z());
  draw_runs_.draw();
  draw_runs_.clear();
}

void OsmesaRgbCamera::render(const Eigen::Isometry3d& camera_pose, double time_s,
                             std::span<const Eigen::Isometry3d> body_poses, RgbImage& out) {
  if (body_poses.size() != mover_chunks_.size()) {
    throw std::invalid_argument("colour camera: " + std::to_string(body_poses.size()) + " poses for " +
                                std::to_string(mover_chunks_.size()) + " moving bodies");
  }
  const RgbCameraConfig& c = def_.camera;
  const Eigen::Isometry3d eye_from_world = eye_from_world_at(camera_pose);
  const Eigen::Matrix4f view = eye_from_world.matrix().cast<float>();
  const Eigen::Vector3f sun = (eye_from_world.linear() * kSunDirection).cast<float>();

  context_.make_current();
  gl().Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gl().Uniform3f(3, sun.x(), sun.y(), sun.z());
  gl().UniformMatrix4fv(0, 1, GL_FALSE, view.data());
  // Static geometry: the visible chunks, adjacent ones of a part merged into runs.
  const Eigen::Affine3f view_affine(view);
  std::uint32_t part = 0;
  for (const Chunk& chunk : chunks_) {
    if (!view_volume_.may_see(view_affine * chunk.centre, chunk.radius)) continue;
    if (chunk.part != part) flush(part);
    part = chunk.part;
    draw_runs_.add(chunk.first_index, chunk.index_count);
  }
  flush(part);
  // Moving bodies, each where the world has it now.
  for (std::size_t i = 0; i < mover_chunks_.size(); ++i) {
    const Chunk& chunk = mover_chunks_[i];
    const Eigen::Matrix4f model_view = (eye_from_world * body_poses[i]).matrix().cast<float>();
    if (!view_volume_.may_see(Eigen::Affine3f(model_view) * chunk.centre, chunk.radius)) continue;
    gl().UniformMatrix4fv(0, 1, GL_FALSE, model_view.data());
    gl().Uniform3f(2, mover_colours_[i].x(), mover_colours_[i].y(), mover_colours_[i].z());
    gl().DrawElements(GL_TRIANGLES, static_cast<GLsizei>(chunk.index_count), GL_UNSIGNED_INT,
                      reinterpret_cast<const void*>(std::size_t{chunk.first_index} * sizeof(std::uint32_t)));
  }

  out.rows = c.rows;
  out.cols = c.cols;
  out.time_s = time_s;
  out.sensor_pose = camera_pose;
  out.rgb.resize(static_cast<std::size_t>(c.rows) * c.cols * 3);  // no allocation once sized
  gl().ReadPixels(0, 0, c.cols, c.rows, GL_RGB, GL_UNSIGNED_BYTE, out.rgb.data());
  check_gl("rendering a colour image");
  if (c.noise_stddev > 0.0) add_noise(out.rgb);
}

void OsmesaRgbCamera::add_noise(std::vector<std::uint8_t>& rgb) {
  const double stddev = def_.camera.noise_stddev * 255.0;
  for (std::uint8_t& v : rgb) {
    v = static_cast<std::uint8_t>(std::clamp(std::round(v + rng_.normal(0.0, stddev)), 0.0, 255.0));
  }
}

}  // namespace

std::unique_ptr<RgbCamera> make_rgb_camera(const SceneMesh& mesh, const RgbCameraDef& def, std::uint64_t world_seed) {
  validate_rgb_camera(def);
  return std::make_unique<OsmesaRgbCamera>(mesh, def, world_seed);
}

std::unique_ptr<RgbCamera> make_rgb_camera(const Scene& scene, const RgbCameraDef& def, std::uint64_t world_seed) {
  return make_rgb_camera(build_scene_mesh(scene), def, world_seed);
}

}  // namespace campo
