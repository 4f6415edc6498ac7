#include "sensors/depth_camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "campo/scene_loader.hpp"
#include "core/angles.hpp"
#include "scene/scene_mesh.hpp"
#include "sensors/lidar.hpp"
#include "sensors/osmesa_gl.hpp"
#include "sensors/view_culling.hpp"

namespace campo {

namespace {


// The perspective render is finer than the sensor grid by this factor at the
// image centre (and finer still towards the edges), so every grid ray falls
// between render pixels that see the same surface.
constexpr double kOversampling = 1.25;
// Between two render pixels, a change of inverse depth beyond the range of
// the changes beside it, widened by half their difference, by this fraction
// of the larger and by this fraction of the inverse depth, is a silhouette
// (see along_line) ...
constexpr float kStepSlack = 1.0f;
constexpr float kStepTolerance = 1e-3f;
// ... and so is one above this fraction beside empty space.
constexpr float kMaxLoneStep = 0.05f;
// Render pixels kept around the grid's rays on every side, for the 4 x 4 window.
constexpr int kMarginPx = 2;

// Range along the ray is z_eye * |(X, Y, 1)|; depth is kept as the reversed,
// zero-to-one window depth d = near (far - z) / ((far - near) z), which is
// affine in 1/z and so in screen position across any planar triangle.
constexpr const char* kVertexShader = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 0) uniform mat4 model_view;
layout(location = 1) uniform mat4 projection;
out vec3 eye_position;
void main() {
  vec4 eye = model_view * vec4(position, 1.0);
  eye_position = eye.xyz;
  gl_Position = projection * eye;
}
)";

// Depth only. With geometry near the eye, surfaces nearer than the minimum
// range are skipped as the LIDAR skips them: the pixel sees what lies behind.
constexpr const char* kFragmentShader = R"(#version 450 core
void main() {}
)";
constexpr const char* kNearFragmentShader = R"(#version 450 core
in vec3 eye_position;
layout(location = 2) uniform float min_range_sq;
void main() {
  if (dot(eye_position, eye_position) < min_range_sq) discard;
}
)";

// The perspective view covering every ray of the grid.
struct Frustum {
  double half_width = 1.0;   // tan of the half-angle to the image edge, right
  double half_height = 1.0;  // tan of the half-angle to the image edge, up
  int width_px = 2;
  int height_px = 2;
  double near_m = 0.0;
  double far_m = 0.0;
};

Frustum make_frustum(const RangeSensorConfig& c) {
  Frustum f;
  const double half_h = 0.5 * c.fov_h_deg * kDegToRad;
  const double half_v = 0.5 * c.fov_v_deg * kDegToRad;
  const double pitch_x = c.fov_h_deg * kDegToRad / c.cols / kOversampling;
  const double pitch_y = c.fov_v_deg > 0.0 ? c.fov_v_deg * kDegToRad / c.rows / kOversampling : pitch_x;
  // Ray (az, el) meets the image plane at X = -tan(az), Y = tan(el) / cos(az):
  // the grid's corners reach further up than its centre column.
  const double reach_x = std::tan(half_h);
  const double reach_y = std::tan(half_v) / std::cos(half_h);
  f.width_px = static_cast<int>(std::ceil(2.0 * reach_x / pitch_x)) + 2 * kMarginPx;
  f.height_px = static_cast<int>(std::ceil(2.0 * reach_y / pitch_y)) + 2 * kMarginPx;
  f.half_width = 0.5 * f.width_px * pitch_x;
  f.half_height = 0.5 * f.height_px * pitch_y;
  // The near plane cuts at the minimum range along the most oblique ray; when
  // a surface comes that close, the near-range fragment shader does the rest.
  const double cos_corner = 1.0 / std::sqrt(1.0 + f.half_width * f.half_width + f.half_height * f.half_height);
  f.near_m = std::max(c.min_range_m * cos_corner, kSmallestNear_m);
  f.far_m = c.max_range_m;
  return f;
}

// Where a grid ray samples the render (rows bottom-up, as GL reads them).
struct Tap {
  std::uint32_t corner;   // lower-left of the 2 x 2 render pixels around the ray
  float fx;               // position between the four, [0, 1] each way
  float fy;
  float ray_norm;         // |(X, Y, 1)|: range = z_eye * ray_norm
};

std::vector<Tap> make_taps(const RangeSensorConfig& c, const Frustum& f) {
  std::vector<Tap> taps;
  const std::vector<Beam> beams = lidar_beams(c);
  taps.reserve(beams.size());
  const auto place = [](double t, int size, std::uint32_t& low, float& frac) {
    // Continuous pixel coordinate with pixel centres on integers.
    const double p = std::clamp(t * size - 0.5, 1.0, size - 2.0);
    const int i = std::min(static_cast<int>(p), size - 3);
    low = static_cast<std::uint32_t>(i);
    frac = static_cast<float>(p - i);
  };
  for (const Beam& beam : beams) {
    const double az = beam.azimuth_deg * kDegToRad;
    const double el = beam.elevation_deg * kDegToRad;
    const double x = -std::tan(az);
    const double y = std::tan(el) / std::cos(az);
    std::uint32_t col = 0, row = 0;
    Tap tap{};
    place(0.5 * (x / f.half_width + 1.0), f.width_px, col, tap.fx);
    place(0.5 * (y / f.half_height + 1.0), f.height_px, row, tap.fy);
    const auto w = static_cast<std::uint32_t>(f.width_px);
    tap.corner = row * w + col;
    tap.ray_norm = static_cast<float>(std::sqrt(1.0 + x * x + y * y));
    taps.push_back(tap);
  }
  return taps;
}

// Inverse depth is piecewise linear along any image line across planar faces.
// along_line() takes four samples a, b, c, d at -1, 0, 1, 2 (0 = nothing
// drawn) and returns the value at t in [0, 1]:
// - a step from b to c unlike the steps beside it is a silhouette: the
//   nearer sample of the two, never a blend of two surfaces;
// - when the lines through (a, b) and (c, d) cross between b and c, a crease
//   lies there: the function follows the lower line where it bends down and
//   the upper where it bends up (exact across one crease);
// - otherwise linear between b and c.
inline float along_line(float a, float b, float c, float d, float t) {
  const float nearest = t < 0.5f ? b : c;
  if (!(b > 0.0f && c > 0.0f)) return nearest;
  const float step = c - b;
  const float linear = b + step * t;
  const float tolerance = kStepTolerance * std::min(b, c);
  if (!(a > 0.0f && d > 0.0f)) {
    // Beside empty space there are no neighbouring steps to compare with.
    return std::abs(step) <= kMaxLoneStep * std::min(b, c) ? linear : nearest;
  }
  const float left_slope = b - a;
  const float right_slope = d - c;
  // Most often all four lie on one face.
  if (std::abs(left_slope - step) <= tolerance && std::abs(right_slope - step) <= tolerance) return linear;
  const float slack = 0.5f * std::abs(left_slope - right_slope) +
                      kStepSlack * std::max(std::abs(left_slope), std::abs(right_slope)) + tolerance;
  if (step < std::min(left_slope, right_slope) - slack || step > std::max(left_slope, right_slope) + slack) {
    return nearest;
  }
  // The lines cross at t = crossing / bend.
  const float bend = left_slope - right_slope;
  const float crossing = step - right_slope;
  if (bend > 0.0f ? crossing >= 0.0f && crossing <= bend : crossing <= 0.0f && crossing >= bend) {
    const float left = b + left_slope * t;
    const float right = c + right_slope * (t - 1.0f);
    return bend > 0.0f ? std::min(left, right) : std::max(left, right);
  }
  return linear;
}

// Inverse depth along a grid ray from the 4 x 4 pixels around it of the
// inverse-depth image: along the four rows, then down the results.
float sample_inverse_depth(const float* image, std::size_t width, const Tap& tap) {
  const float* p = image + tap.corner - width - 1;
  float rows[4];
  for (float& row : rows) {
    row = along_line(p[0], p[1], p[2], p[3], tap.fx);
    p += width;
  }
  return along_line(rows[0], rows[1], rows[2], rows[3], tap.fy);
}

void validate_depth_camera(const SensorDef& def) {
  const RangeSensorConfig& c = def.range;
  const std::string name = "depth camera '" + def.alias + "': ";
  if (def.range.kind != RangeSensorKind::depth_camera) {
    throw std::invalid_argument(name + "a " + std::string(to_string(def.range.kind)) + " is built by make_lidar_sensor");
  }
  if (!c.beams.empty()) throw std::invalid_argument(name + "needs a beam grid, not explicit beams");
  if (c.cols < 1 || c.rows < 1) throw std::invalid_argument(name + "needs at least one column and row");
  if (!(c.fov_h_deg > 0.0 && c.fov_h_deg <= kMaxDepthCameraFov_deg && c.fov_v_deg >= 0.0 &&
        c.fov_v_deg <= kMaxDepthCameraFov_deg)) {
    throw std::invalid_argument(name + "needs fields of view in (0, " +
                                std::to_string(static_cast<int>(kMaxDepthCameraFov_deg)) + "] deg");
  }
  if (!(c.min_range_m >= 0.0 && c.min_range_m < c.max_range_m)) {
    throw std::invalid_argument(name + "needs 0 <= min_range_m < max_range_m");
  }
  // Noise and dropout draw from the world's seeded stream, which this
  // factory is not given; a silent noise-free camera would misreport a run.
  if (c.noise_stddev_m != 0.0 || c.dropout_probability != 0.0) {
    throw std::invalid_argument(name + "range noise and dropout are supported by the ray-cast LIDAR only");
  }
  if (!(c.quantization_m >= 0.0)) throw std::invalid_argument(name + "quantization_m must be >= 0");
}

class DepthCamera final : public RangeSensor {
 public:
  DepthCamera(const Scene& scene, const SceneMesh& mesh, const SensorDef& def);
  ~DepthCamera() override { context_.bind(); }
  DepthCamera(const DepthCamera&) = delete;
  DepthCamera& operator=(const DepthCamera&) = delete;

  const SensorDef& def() const override { return def_; }
  void scan(const Eigen::Isometry3d& sensor_pose, double time_s, std::span<const Eigen::Isometry3d> body_poses,
            RangeScan& out) override;

 private:
  bool visible(const Eigen::Affine3f& eye_from_mesh, const Eigen::Vector3f& eye_in_mesh, const Chunk& chunk,
               bool& close_by) const;
  bool back_faces_hidden(const Eigen::Vector3d& eye) const;
  void render(const Eigen::Isometry3d& sensor_pose, std::span<const Eigen::Isometry3d> body_poses);
  void fill(const Eigen::Isometry3d& sensor_pose, double time_s, RangeScan& out) const;

  SensorDef def_;
  Frustum frustum_;
  std::vector<Tap> taps_;
  std::vector<Eigen::Vector3f> directions_;  // unit rays in the sensor frame, beam order
  std::vector<Chunk> chunks_;                // static geometry, index-buffer order
  std::vector<Chunk> mover_chunks_;          // one per moving body, shape frame
  std::vector<Chunk> solids_;                // closed static shapes, one per shape
  std::vector<OpenSurface> open_surfaces_;   // heightfields and planes
  std::vector<Eigen::Isometry3d> mover_poses_;     // world from shape at the scan time
  std::vector<Eigen::Matrix4f> mover_model_views_; // eye from shape at the scan time
  std::vector<std::size_t> visible_movers_;
  ViewVolume view_volume_;
  DrawRuns draw_runs_;                       // scratch for one multi-draw
  std::vector<float> inverse_depth_;         // near * far / z per render pixel (0: none), rows bottom-up

  // GL objects last: they are released (context current) before the context.
  OsmesaContext context_;
  GlProgram program_;       // far from everything: depth only
  GlProgram near_program_;  // some surface may be within the minimum range
  GpuMesh mesh_;
  Framebuffer target_;
};

DepthCamera::DepthCamera(const Scene& scene, const SceneMesh& mesh, const SensorDef& def)
    : def_(def), frustum_(make_frustum(def.range)) {
  const RangeSensorConfig& c = def_.range;
  taps_ = make_taps(c, frustum_);
  for (const Beam& beam : lidar_beams(c)) directions_.push_back(beam_direction(beam));
  inverse_depth_.resize(static_cast<std::size_t>(frustum_.width_px) * frustum_.height_px);

  chunks_ = cut_into_chunks(mesh, mesh.parts, kCullChunkTriangles);
  for (const MeshPart& part : mesh.moving_parts) {
    mover_chunks_.push_back(bound(mesh, part.first_index, part.index_count));
  }
  mover_poses_.resize(mover_chunks_.size(), Eigen::Isometry3d::Identity());
  mover_model_views_.resize(mover_chunks_.size());
  visible_movers_.reserve(mover_chunks_.size());
  for (const MeshPart& part : mesh.parts) {
    const Shape& shape = scene.shapes[static_cast<std::size_t>(part.shape)];
    // Mesh shapes are solids here: one that is open or wound either way is in the scene mesh from both sides.
    if (shape.type == ShapeType::plane || shape.type == ShapeType::heightfield) {
      open_surfaces_.push_back({&shape, shape.terrain ? shape.terrain->max_height_m() : 0.0});
    } else {
      solids_.push_back(bound(mesh, part.first_index, part.index_count));
    }
  }
  draw_runs_.reserve(chunks_.size());
  view_volume_ = ViewVolume(frustum_.half_width, frustum_.half_height, frustum_.far_m);
  check_render_size(frustum_.width_px, frustum_.height_px, "depth camera '" + def_.alias + "': its grid");

  // The context is this camera's alone, so its state is set once here.
  program_ = make_program(kVertexShader, kFragmentShader);
  mesh_ = upload_mesh(mesh, false);
  target_ = make_framebuffer(frustum_.width_px, frustum_.height_px, 0, GL_DEPTH_COMPONENT32F);
  use_reversed_depth(frustum_.width_px, frustum_.height_px);
  const Eigen::Matrix4f projection =
      reversed_depth_projection(frustum_.half_width, frustum_.half_height, frustum_.near_m, frustum_.far_m);
  near_program_ = make_program(kVertexShader, kNearFragmentShader);
  gl().UseProgram(near_program_.id());
  gl().UniformMatrix4fv(1, 1, GL_FALSE, projection.data());
  gl().Uniform1f(2, static_cast<float>(c.min_range_m * c.min_range_m));
  gl().UseProgram(program_.id());
  gl().UniformMatrix4fv(1, 1, GL_FALSE, projection.data());
  check_gl("setting up the depth camera");
}

// In view and within range; `close_by` is set when it may come within the
// minimum range of the eye (`eye_in_mesh`: the eye in the mesh frame).
bool DepthCamera::visible(const Eigen::Affine3f& eye_from_mesh, const Eigen::Vector3f& eye_in_mesh,
                          const Chunk& chunk, bool& close_by) const {
  if (!view_volume_.may_see(eye_from_mesh * chunk.centre, chunk.radius)) return false;
  close_by = close_by || chunk.box.exteriorDistance(eye_in_mesh) < static_cast<float>(def_.range.min_range_m);
  return true;
}

bool DepthCamera::back_faces_hidden(const Eigen::Vector3d& eye) const {
  return campo::back_faces_hidden(eye, solids_, mover_chunks_, mover_poses_, open_surfaces_);
}

void DepthCamera::render(const Eigen::Isometry3d& sensor_pose, std::span<const Eigen::Isometry3d> body_poses) {
  const Eigen::Isometry3d eye_from_world = eye_from_world_at(sensor_pose);

  // Static geometry: the visible chunks, adjacent ones merged into runs.
  bool close_by = false;  // some visible surface may lie within the minimum range
  const Eigen::Affine3f view(eye_from_world.matrix().cast<float>());
  const Eigen::Vector3f eye = sensor_pose.translation().cast<float>();
  draw_runs_.clear();
  for (const Chunk& chunk : chunks_) {
    if (!visible(view, eye, chunk, close_by)) continue;
    draw_runs_.add(chunk.first_index, chunk.index_count);
  }
  // Moving bodies, each where the world has it now.
  if (body_poses.size() != mover_chunks_.size()) {
    throw std::invalid_argument("depth camera: " + std::to_string(body_poses.size()) + " poses for " +
                                std::to_string(mover_chunks_.size()) + " moving bodies");
  }
  visible_movers_.clear();
  for (std::size_t i = 0; i < mover_chunks_.size(); ++i) {
    mover_poses_[i] = body_poses[i];
    mover_model_views_[i] = (eye_from_world * mover_poses_[i]).matrix().cast<float>();
    const Eigen::Vector3f eye_in_shape = (mover_poses_[i].inverse() * sensor_pose.translation()).cast<float>();
    if (visible(Eigen::Affine3f(mover_model_views_[i]), eye_in_shape, mover_chunks_[i], close_by)) {
      visible_movers_.push_back(i);
    }
  }

  context_.make_current();
  gl().UseProgram(close_by ? near_program_.id() : program_.id());
  if (!close_by && back_faces_hidden(sensor_pose.translation())) {
    gl().Enable(GL_CULL_FACE);
  } else {
    gl().Disable(GL_CULL_FACE);
  }
  gl().Clear(GL_DEPTH_BUFFER_BIT);
  if (!draw_runs_.empty()) {
    gl().UniformMatrix4fv(0, 1, GL_FALSE, view.matrix().data());
    draw_runs_.draw();
  }
  for (const std::size_t i : visible_movers_) {
    const Chunk& chunk = mover_chunks_[i];
    gl().UniformMatrix4fv(0, 1, GL_FALSE, mover_model_views_[i].data());
    gl().DrawElements(GL_TRIANGLES, static_cast<GLsizei>(chunk.index_count), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(std::size_t{chunk.first_index} * sizeof(std::uint32_t)));
  }
  gl().ReadPixels(0, 0, frustum_.width_px, frustum_.height_px, GL_DEPTH_COMPONENT, GL_FLOAT, inverse_depth_.data());
  check_gl("rendering a depth image");
  // Window depth d = near (far - z) / ((far - near) z) becomes w = d (far -
  // near) + near = near * far / z, or 0 where nothing was drawn (d = 0).
  const auto near = static_cast<float>(frustum_.near_m);
  const auto scale = static_cast<float>(frustum_.far_m - frustum_.near_m);
  for (float& value : inverse_depth_) value = value > 0.0f ? value * scale + near : 0.0f;
}

void DepthCamera::fill(const Eigen::Isometry3d& sensor_pose, double time_s, RangeScan& out) const {
  const RangeSensorConfig& c = def_.range;
  const std::size_t n = taps_.size();
  begin_scan(out, c, time_s, sensor_pose);
  const auto near_far = static_cast<float>(frustum_.near_m * frustum_.far_m);
  const auto max_range = static_cast<float>(c.max_range_m);
  const auto width = static_cast<std::size_t>(frustum_.width_px);
  const Eigen::Matrix3f rotation = sensor_pose.linear().cast<float>();
  const Eigen::Vector3d origin = sensor_pose.translation();
  for (std::size_t i = 0; i < n; ++i) {
    const Tap& tap = taps_[i];
    const float w = sample_inverse_depth(inverse_depth_.data(), width, tap);
    const float range = w > 0.0f ? near_far / w * tap.ray_norm : max_range + 1.0f;
    if (!(range <= max_range)) {
      out.ranges_m[i] = max_range;
      out.hits[i] = 0;
      continue;
    }
    const float r = reported_range(range, c);
    out.ranges_m[i] = r;
    out.hits[i] = 1;
    out.points.push_back((origin + r * (rotation * directions_[i]).cast<double>()).cast<float>());
  }
}

void DepthCamera::scan(const Eigen::Isometry3d& sensor_pose, double time_s,
                       std::span<const Eigen::Isometry3d> body_poses, RangeScan& out) {
  render(sensor_pose, body_poses);
  fill(sensor_pose, time_s, out);
}

}  // namespace

std::unique_ptr<RangeSensor> make_depth_camera(const Scene& scene, const SceneMesh& mesh, const SensorDef& def) {
  validate_depth_camera(def);
  return std::make_unique<DepthCamera>(scene, mesh, def);
}

std::unique_ptr<RangeSensor> make_depth_camera(const Scene& scene, const SensorDef& def) {
  return make_depth_camera(scene, build_scene_mesh(scene), def);
}

}  // namespace campo
