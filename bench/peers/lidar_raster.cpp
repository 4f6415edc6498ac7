#include "bench/peers/lidar_raster.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "scene/scene_mesh.hpp"
#include "sensors/osmesa_gl.hpp"
#include "sensors/view_culling.hpp"

namespace campo::peers {

namespace {

constexpr const char* kVertexShader = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 0) uniform mat4 model_view;
layout(location = 1) uniform mat4 projection;
void main() { gl_Position = projection * (model_view * vec4(position, 1.0)); }
)";
constexpr const char* kFragmentShader = R"(#version 450 core
void main() {}
)";

}  // namespace

struct RasterScanner::Impl {
  RasterView view;
  std::size_t triangles = 0;
  std::vector<Chunk> chunks;        // static geometry, index-buffer order
  std::vector<Chunk> solids;        // one per closed static shape
  std::vector<OpenSurface> open_surfaces;
  std::vector<Chunk> movers;        // one per moving body, shape frame
  std::vector<Eigen::Isometry3d> mover_poses;
  std::vector<float> ray_norm;      // |(X, Y, 1)| per pixel, GL's row order (bottom up)
  std::vector<float> depth;         // read back, GL's row order
  ViewVolume volume;
  DrawRuns runs;

  // GL objects last: released (context current) before the context.
  OsmesaContext context;
  GlProgram program;
  GpuMesh mesh;
  Framebuffer target;

  ~Impl() { context.bind(); }

  // As the depth camera decides it (sensors/view_culling).
  bool back_faces_hidden(const Eigen::Vector3d& eye) const {
    return campo::back_faces_hidden(eye, solids, movers, mover_poses, open_surfaces);
  }

};

RasterScanner::RasterScanner(const Scene& scene, const RasterView& view) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.view = view;
  const SceneMesh mesh = build_scene_mesh(scene);
  m.triangles = mesh.triangle_count();
  if (view.cull_run_triangles > 0) {
    m.chunks = cut_into_chunks(mesh, mesh.parts, view.cull_run_triangles);
  } else {
    for (const MeshPart& part : mesh.parts) m.chunks.push_back(bound(mesh, part.first_index, part.index_count));
  }
  for (const MeshPart& part : mesh.parts) {
    const Shape& shape = scene.shapes[static_cast<std::size_t>(part.shape)];
    if (shape.type == ShapeType::plane || shape.type == ShapeType::heightfield) {
      m.open_surfaces.push_back({&shape, shape.terrain ? shape.terrain->max_height_m() : 0.0});
    } else {
      m.solids.push_back(bound(mesh, part.first_index, part.index_count));
    }
  }
  for (const MeshPart& part : mesh.moving_parts) m.movers.push_back(bound(mesh, part.first_index, part.index_count));
  m.mover_poses = scripted_poses(scene, 0.0);
  if (m.mover_poses.size() != m.movers.size()) throw std::runtime_error("RasterScanner: moving bodies do not match");
  m.volume = ViewVolume(view.half_width, view.half_height, view.far_m);
  m.runs.reserve(m.chunks.size());

  const auto w = static_cast<std::size_t>(view.width_px), h = static_cast<std::size_t>(view.height_px);
  m.depth.resize(w * h);
  m.ray_norm.resize(w * h);
  for (std::size_t row = 0; row < h; ++row) {
    for (std::size_t col = 0; col < w; ++col) {
      const double x = (2.0 * (static_cast<double>(col) + 0.5) / static_cast<double>(w) - 1.0) * view.half_width;
      const double y = (2.0 * (static_cast<double>(row) + 0.5) / static_cast<double>(h) - 1.0) * view.half_height;
      m.ray_norm[row * w + col] = static_cast<float>(std::sqrt(1.0 + x * x + y * y));
    }
  }

  m.program = make_program(kVertexShader, kFragmentShader);
  m.mesh = upload_mesh(mesh, false);
  m.target = make_framebuffer(view.width_px, view.height_px, 0, GL_DEPTH_COMPONENT32F);
  use_reversed_depth(view.width_px, view.height_px);
  gl().UseProgram(m.program.id());
  const Eigen::Matrix4f projection =
      reversed_depth_projection(view.half_width, view.half_height, view.near_m, view.far_m);
  gl().UniformMatrix4fv(1, 1, GL_FALSE, projection.data());
  check_gl("setting up the rasteriser");
}

RasterScanner::~RasterScanner() = default;

std::size_t RasterScanner::triangles() const { return impl_->triangles; }

std::vector<Eigen::Vector3f> RasterScanner::pixel_directions() const {
  const RasterView& v = impl_->view;
  std::vector<Eigen::Vector3f> out;
  for (int row = 0; row < v.height_px; ++row) {
    for (int col = 0; col < v.width_px; ++col) {
      // Eye frame: x right, y up, looking along -z; sensor frame: x forward, y left, z up.
      const double x = (2.0 * (col + 0.5) / v.width_px - 1.0) * v.half_width;
      const double y = (1.0 - 2.0 * (row + 0.5) / v.height_px) * v.half_height;
      out.push_back(Eigen::Vector3d(1.0, -x, y).normalized().cast<float>());
    }
  }
  return out;
}

void RasterScanner::scan(const Eigen::Isometry3d& sensor_pose, std::span<float> ranges_m) {
  Impl& m = *impl_;
  const Eigen::Isometry3d eye_from_world = eye_from_world_at(sensor_pose);
  const Eigen::Affine3f view(eye_from_world.matrix().cast<float>());
  m.runs.clear();
  for (const Chunk& chunk : m.chunks) {
    if (m.volume.may_see(view * chunk.centre, chunk.radius)) m.runs.add(chunk.first_index, chunk.index_count);
  }
  m.context.make_current();
  if (m.back_faces_hidden(sensor_pose.translation())) {
    gl().Enable(GL_CULL_FACE);
  } else {
    gl().Disable(GL_CULL_FACE);
  }
  gl().Clear(GL_DEPTH_BUFFER_BIT);
  if (!m.runs.empty()) {
    gl().UniformMatrix4fv(0, 1, GL_FALSE, view.matrix().data());
    m.runs.draw();
  }
  for (std::size_t i = 0; i < m.movers.size(); ++i) {
    const Chunk& mover = m.movers[i];
    const Eigen::Matrix4f model_view = (eye_from_world * m.mover_poses[i]).matrix().cast<float>();
    if (!m.volume.may_see((Eigen::Affine3f(model_view) * mover.centre), mover.radius)) continue;
    gl().UniformMatrix4fv(0, 1, GL_FALSE, model_view.data());
    gl().DrawElements(GL_TRIANGLES, static_cast<GLsizei>(mover.index_count), GL_UNSIGNED_INT,
                      reinterpret_cast<const void*>(std::size_t{mover.first_index} * sizeof(std::uint32_t)));
  }
  gl().ReadPixels(0, 0, m.view.width_px, m.view.height_px, GL_DEPTH_COMPONENT, GL_FLOAT, m.depth.data());
  // Window depth d = near (far - z) / ((far - near) z): z = near far / (d (far - near) + near),
  // and the range along the pixel's ray z |(X, Y, 1)|; d = 0 where nothing was drawn.
  const auto near = static_cast<float>(m.view.near_m), far = static_cast<float>(m.view.far_m);
  const float scale = far - near, near_far = near * far;
  const auto w = static_cast<std::size_t>(m.view.width_px), h = static_cast<std::size_t>(m.view.height_px);
  constexpr float kInf = std::numeric_limits<float>::infinity();
  for (std::size_t row = 0; row < h; ++row) {
    const float* depth = m.depth.data() + (h - 1 - row) * w;
    const float* norm = m.ray_norm.data() + (h - 1 - row) * w;
    float* out = ranges_m.data() + row * w;
    for (std::size_t col = 0; col < w; ++col) {
      const float range = near_far / (depth[col] * scale + near) * norm[col];
      out[col] = depth[col] > 0.0f && range <= far ? range : kInf;
    }
  }
}

}  // namespace campo::peers
