#include "sensors/raycaster.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <deque>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "scene/scene_mesh.hpp"
#include "sensors/fan_kernels.hpp"
#include "sensors/ray_fan.hpp"

namespace campo {

// fan::write_hits writes RayHits as (float, int32) pairs.
static_assert(std::is_standard_layout_v<RayHit> && sizeof(RayHit) == 8 && offsetof(RayHit, distance_m) == 0 &&
              offsetof(RayHit, shape) == 4);

namespace {

constexpr double kNoHit = std::numeric_limits<double>::infinity();
// Slack on the edge tests of capped primitives, so a ray grazing a rim is not
// lost between the side test and the cap test through rounding.
constexpr double kEdgeSlack_m = 1e-9;

struct MeshModel;

// An analytic shape (cuboid, cylinder, cone, sphere): centred on `center`,
// axis along the local z of `rotation`; or a triangle mesh whose local frame
// has its origin at `center` (its triangles in a MeshModel of their own).
struct Primitive {
  Eigen::Matrix3d rotation;      // local -> world
  Eigen::Vector3d center;        // world frame, metres
  Eigen::Vector3d half_extents;  // cuboid: size/2; cylinder, cone: (r, r, h/2); sphere: (r, r, r); mesh: unused
  ShapeType type;
  std::int32_t shape;  // RayHit::shape
  const MeshModel* mesh = nullptr;  // mesh only
};

// The triangles of one TriangleMesh (shared by every shape that uses it) in
// an Embree scene of their own, in the mesh's local frame: one user primitive
// per triangle, tested with the watertight double-precision test below. A
// mesh shape is one Primitive of the scene it sits in, whose intersect turns
// the ray into the local frame and traverses this scene (Embree's way of
// instancing user geometry), so static and moving meshes share one path.
struct MeshModel {
  RTCScene scene = nullptr;
  const TriangleMesh* mesh = nullptr;
  Eigen::Vector3d centre;  // of the local bounds
  Eigen::Vector3d half;    // half sizes of the local bounds
  double radius = 0.0;     // of a sphere about `centre` holding every vertex
  // Per triangle, +1 when counter-clockwise seen from outside, -1 when
  // clockwise (fan::TriangleSoup::facing); empty when two-sided.
  std::vector<std::int8_t> facing;
};

// An infinite plane, intersected outside Embree (it has no finite bounds).
struct Plane {
  Eigen::Vector3d point;
  Eigen::Vector3d normal;
  std::int32_t shape;
};

// What a user-geometry callback sees: Embree's context first, so the pointer
// Embree hands back can be cast to this, then the exact (double) ray origin
// shared by every ray of a cast() call; the float ray origin is only used to
// traverse the BVH.
struct CastContext {
  RTCIntersectContext base;
  Eigen::Vector3d origin;
};
static_assert(std::is_standard_layout_v<CastContext>);

Primitive make_primitive(const Shape& shape, std::int32_t id) {
  Primitive p;
  p.rotation = shape.pose.linear();
  p.center = shape.pose.translation();
  p.type = shape.type;
  p.shape = id;
  switch (shape.type) {
    case ShapeType::cuboid:
      p.half_extents = shape.size_m * 0.5;
      break;
    case ShapeType::cylinder:
    case ShapeType::cone:
      p.half_extents = Eigen::Vector3d(shape.radius_m, shape.radius_m, shape.height_m * 0.5);
      break;
    case ShapeType::sphere:
      p.half_extents = Eigen::Vector3d::Constant(shape.radius_m);
      break;
    case ShapeType::mesh:
      p.half_extents.setZero();  // unused: the bounds come from the mesh's model, which the caller sets
      break;
    case ShapeType::plane:
    case ShapeType::heightfield:
      throw std::logic_error("make_primitive: not an analytic primitive");
  }
  return p;
}

// Keeps t in `best` when it lies in [t0, t1] and is nearer (NaN never passes).
inline void consider(double t, double t0, double t1, double& best) {
  if (t >= t0 && t <= t1 && t < best) best = t;
}

// The functions below intersect a ray o + t d (local frame) with a surface and
// return the nearest crossing in [t0, t1], or kNoHit. Surfaces are two-sided,
// like the triangles of a heightfield: a ray that starts inside a solid (or
// skips its entry through min range) reports where it leaves.

double intersect_box(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& h,
                     double t0, double t1) {
  double enter = -kNoHit;
  double exit = kNoHit;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0) {
      if (std::abs(o[i]) > h[i]) return kNoHit;
      continue;
    }
    const double inv = 1.0 / d[i];
    double a = (-h[i] - o[i]) * inv;
    double b = (h[i] - o[i]) * inv;
    if (a > b) std::swap(a, b);
    enter = std::max(enter, a);
    exit = std::min(exit, b);
  }
  if (enter > exit) return kNoHit;
  double best = kNoHit;
  consider(enter, t0, t1, best);
  consider(exit, t0, t1, best);
  return best;
}

double intersect_sphere(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double r, double t0,
                        double t1) {
  // Solve around the point of closest approach: no cancellation for far rays.
  const double a = d.squaredNorm();
  const double tc = -o.dot(d) / a;
  const double disc = r * r - (o + tc * d).squaredNorm();
  if (disc < 0.0) return kNoHit;
  const double s = std::sqrt(disc / a);
  double best = kNoHit;
  consider(tc - s, t0, t1, best);
  consider(tc + s, t0, t1, best);
  return best;
}

// Crossing with the disc of radius r in the plane z = z_cap (a cap).
void consider_cap(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double r, double z_cap,
                  double t0, double t1, double& best) {
  if (d.z() == 0.0) return;
  const double t = (z_cap - o.z()) / d.z();
  const double x = o.x() + t * d.x();
  const double y = o.y() + t * d.y();
  if (x * x + y * y <= (r + kEdgeSlack_m) * (r + kEdgeSlack_m)) consider(t, t0, t1, best);
}

double intersect_cylinder(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double r, double hz,
                          double t0, double t1) {
  double best = kNoHit;
  const double a = d.x() * d.x() + d.y() * d.y();
  if (a > 0.0) {
    const double tc = -(o.x() * d.x() + o.y() * d.y()) / a;
    const double px = o.x() + tc * d.x();
    const double py = o.y() + tc * d.y();
    const double disc = r * r - (px * px + py * py);
    if (disc >= 0.0) {
      const double s = std::sqrt(disc / a);
      for (const double t : {tc - s, tc + s}) {
        if (std::abs(o.z() + t * d.z()) <= hz + kEdgeSlack_m) consider(t, t0, t1, best);
      }
    }
  }
  consider_cap(o, d, r, -hz, t0, t1, best);
  consider_cap(o, d, r, hz, t0, t1, best);
  return best;
}

// Cone with its apex at z = +hz and a base of radius r at z = -hz.
double intersect_cone(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double r, double hz,
                      double t0, double t1) {
  // x^2 + y^2 = k^2 (hz - z)^2 with k = r / (2 hz), as A t^2 + 2 B t + C = 0.
  const double k2 = (r / (2.0 * hz)) * (r / (2.0 * hz));
  const double w0 = hz - o.z();
  const double a = d.x() * d.x() + d.y() * d.y() - k2 * d.z() * d.z();
  const double b = o.x() * d.x() + o.y() * d.y() + k2 * w0 * d.z();
  const double c = o.x() * o.x() + o.y() * o.y() - k2 * w0 * w0;
  double best = kNoHit;
  const double disc = b * b - a * c;
  if (disc >= 0.0) {
    // Stable roots; with a == 0 (ray parallel to a generator) q / a is
    // infinite and c / q is the single root, so no special case is needed.
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    for (const double t : {q / a, c / q}) {
      const double z = o.z() + t * d.z();
      // The equation also holds on the mirrored cone above the apex.
      if (z >= -hz - kEdgeSlack_m && z <= hz + kEdgeSlack_m) consider(t, t0, t1, best);
    }
  }
  consider_cap(o, d, r, -hz, t0, t1, best);
  return best;
}

// Nearest crossing of the world ray origin + t dir with `p` in [t0, t1].
double intersect_mesh(const Primitive& p, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t0,
                      double t1);

double intersect_primitive(const Primitive& p, const Eigen::Vector3d& origin,
                           const Eigen::Vector3d& dir, double t0, double t1) {
  if (p.type == ShapeType::mesh) return intersect_mesh(p, origin, dir, t0, t1);
  Eigen::Vector3d o = p.rotation.transpose() * (origin - p.center);
  const Eigen::Vector3d d = p.rotation.transpose() * dir;
  // Restart the ray at its closest approach to the centre so the solvers work
  // with small numbers whatever the distance to the sensor.
  const double shift = -o.dot(d) / d.squaredNorm();
  o += shift * d;
  t0 -= shift;
  t1 -= shift;
  const Eigen::Vector3d& h = p.half_extents;
  double t = kNoHit;
  switch (p.type) {
    case ShapeType::cuboid:
      t = intersect_box(o, d, h, t0, t1);
      break;
    case ShapeType::cylinder:
      t = intersect_cylinder(o, d, h.x(), h.z(), t0, t1);
      break;
    case ShapeType::cone:
      t = intersect_cone(o, d, h.x(), h.z(), t0, t1);
      break;
    case ShapeType::sphere:
      t = intersect_sphere(o, d, h.x(), t0, t1);
      break;
    case ShapeType::plane:
    case ShapeType::heightfield:
    case ShapeType::mesh:  // above
      break;
  }
  return t + shift;
}

// Writes a world-frame box as Embree bounds, padded generously: the BVH is
// traversed in float, the intersectors work in double.
void write_bounds(const Eigen::AlignedBox3d& box, RTCBounds* out) {
  const double pad =
      1e-4 + 1e-6 * std::max(box.min().cwiseAbs().maxCoeff(), box.max().cwiseAbs().maxCoeff());
  const Eigen::Vector3f lo = (box.min().array() - pad).cast<float>();
  const Eigen::Vector3f hi = (box.max().array() + pad).cast<float>();
  *out = RTCBounds{lo.x(), lo.y(), lo.z(), 0.0f, hi.x(), hi.y(), hi.z(), 0.0f};
}

// Runs `intersect(origin, dir, tnear, tfar)` for every active ray of an
// Embree callback and records hits. The origin is the exact one of the cast()
// call, not Embree's float copy.
template <class Intersect>
void intersect_rays(const RTCIntersectFunctionNArguments* args, Intersect intersect) {
  const Eigen::Vector3d& origin = reinterpret_cast<const CastContext*>(args->context)->origin;
  const unsigned n = args->N;
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, n);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, n);
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    const Eigen::Vector3d dir(RTCRayN_dir_x(rays, n, i), RTCRayN_dir_y(rays, n, i),
                              RTCRayN_dir_z(rays, n, i));
    float& tfar = RTCRayN_tfar(rays, n, i);
    const double t = intersect(origin, dir, RTCRayN_tnear(rays, n, i), tfar);
    if (!(t < kNoHit && t <= tfar)) continue;  // kNoHit is no hit, even with an infinite tfar
    tfar = static_cast<float>(t);  // rounding is monotonic: stays within [tnear, tfar]
    RTCHitN_geomID(hits, n, i) = args->geomID;
    RTCHitN_primID(hits, n, i) = args->primID;
    RTCHitN_instID(hits, n, i, 0) = args->context->instID[0];
  }
}

void primitive_bounds(const RTCBoundsFunctionArguments* args) {
  const auto& p = static_cast<const Primitive*>(args->geometryUserPtr)[args->primID];
  const Eigen::Matrix3d& r = p.rotation;
  const Eigen::Vector3d& h = p.half_extents;
  Eigen::Vector3d extent;
  if (p.type == ShapeType::mesh) {
    // The local bounds turned into the world; their centre need not be the origin.
    const Eigen::Vector3d centre = p.center + r * p.mesh->centre;
    extent = r.cwiseAbs() * p.mesh->half;
    write_bounds(Eigen::AlignedBox3d(centre - extent, centre + extent), args->bounds_o);
    return;
  }
  if (p.type == ShapeType::cuboid) {
    extent = r.cwiseAbs() * h;
  } else if (p.type == ShapeType::sphere) {
    extent.setConstant(h.x());
  } else {
    // Cylinder (and the cone inside it): disc radius across the axis, half
    // height along it.
    const Eigen::Vector3d axis = r.col(2);
    for (int i = 0; i < 3; ++i) {
      extent[i] =
          h.x() * std::sqrt(std::max(0.0, 1.0 - axis[i] * axis[i])) + h.z() * std::abs(axis[i]);
    }
  }
  write_bounds(Eigen::AlignedBox3d(p.center - extent, p.center + extent), args->bounds_o);
}

void primitive_intersect(const RTCIntersectFunctionNArguments* args) {
  const auto& p = static_cast<const Primitive*>(args->geometryUserPtr)[args->primID];
  intersect_rays(args, [&p](const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t0,
                            double t1) { return intersect_primitive(p, origin, dir, t0, t1); });
}

// Heightfields are Embree user geometry too: one primitive per block of
// kBlockCells x kBlockCells cells, walked cell by cell along the ray (2D DDA)
// with a watertight triangle test in double precision. Embree's own float
// triangle test lets rays through shared edges now and then, even in robust
// mode; Bullet (and the ground under a robot) does not.
constexpr int kBlockCells = 4;

// A heightfield placed in the world; vertex (c, r) sits at local
// ((c - (cols-1)/2) dx, (r - (rows-1)/2) dy, height), as in Bullet.
struct Terrain {
  Eigen::Matrix3d rotation;     // local -> world
  Eigen::Vector3d translation;  // world frame, metres
  const HeightGrid* grid;
  int blocks_x;  // blocks along x; blocks are numbered row-major
  int blocks_y;
  std::int32_t shape;

  double vertex_x(int c) const { return (c - 0.5 * (grid->cols - 1)) * grid->spacing_x_m; }
  double vertex_y(int r) const { return (r - 0.5 * (grid->rows - 1)) * grid->spacing_y_m; }
  // Cells [c_lo, c_hi) x [r_lo, r_hi) of a block.
  void block_cells(unsigned block, int& c_lo, int& c_hi, int& r_lo, int& r_hi) const {
    c_lo = static_cast<int>(block % static_cast<unsigned>(blocks_x)) * kBlockCells;
    r_lo = static_cast<int>(block / static_cast<unsigned>(blocks_x)) * kBlockCells;
    c_hi = std::min(c_lo + kBlockCells, grid->cols - 1);
    r_hi = std::min(r_lo + kBlockCells, grid->rows - 1);
  }
};

Terrain make_terrain(const Shape& shape, std::int32_t id) {
  const HeightGrid& g = *shape.terrain;
  return {shape.pose.linear(),
          shape.pose.translation(),
          &g,
          (g.cols - 1 + kBlockCells - 1) / kBlockCells,
          (g.rows - 1 + kBlockCells - 1) / kBlockCells,
          id};
}

// The ray in the sheared frame of Woop, Benthin and Wald (JCGT 2013): the ray
// becomes the z axis, so triangle edges are tested in 2D. A vertex shared by
// several triangles is projected with the same arithmetic for each of them,
// so the edge functions of a shared edge are exact negatives of each other
// and a ray cannot pass between the two triangles.
struct ShearedRay {
  Eigen::Vector3d origin;
  int kx, ky, kz;
  double sx, sy, sz;
};

struct ShearedVertex {
  double x, y, z;
};

ShearedRay shear(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir) {
  ShearedRay r;
  r.origin = origin;
  dir.cwiseAbs().maxCoeff(&r.kz);
  r.kx = (r.kz + 1) % 3;
  r.ky = (r.kx + 1) % 3;
  r.sx = dir[r.kx] / dir[r.kz];
  r.sy = dir[r.ky] / dir[r.kz];
  r.sz = 1.0 / dir[r.kz];
  return r;
}

ShearedVertex project(const ShearedRay& r, double x, double y, double z) {
  const Eigen::Vector3d a = Eigen::Vector3d(x, y, z) - r.origin;
  return {a[r.kx] - r.sx * a[r.kz], a[r.ky] - r.sy * a[r.kz], r.sz * a[r.kz]};
}

// Ray parameter of the hit with triangle (a, b, c) in [t0, t1], or kNoHit.
// A ray exactly on an edge hits the triangles on both sides.
double intersect_triangle(const ShearedVertex& a, const ShearedVertex& b, const ShearedVertex& c,
                          double t0, double t1) {
  const double u = c.x * b.y - c.y * b.x;
  const double v = a.x * c.y - a.y * c.x;
  const double w = b.x * a.y - b.y * a.x;
  if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return kNoHit;
  const double det = u + v + w;
  if (det == 0.0) return kNoHit;
  const double t = (u * a.z + v * b.z + w * c.z) / det;
  return t >= t0 && t <= t1 ? t : kNoHit;
}

// Clips [enter, exit] to the ray parameters where o + t d lies in [lo, hi].
void clip_slab(double o, double d, double lo, double hi, double& enter, double& exit) {
  if (d == 0.0) {
    if (o < lo || o > hi) enter = kNoHit;
    return;
  }
  double a = (lo - o) / d;
  double b = (hi - o) / d;
  if (a > b) std::swap(a, b);
  enter = std::max(enter, a);
  exit = std::min(exit, b);
}

// Nearest hit in [t0, t1] of the world ray with one block of a heightfield.
double intersect_terrain_block(const Terrain& terrain, unsigned block,
                               const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t0,
                               double t1) {
  const HeightGrid& g = *terrain.grid;
  const Eigen::Vector3d o = terrain.rotation.transpose() * (origin - terrain.translation);
  const Eigen::Vector3d d = terrain.rotation.transpose() * dir;
  int c_lo, c_hi, r_lo, r_hi;
  terrain.block_cells(block, c_lo, c_hi, r_lo, r_hi);
  // Walk in grid units, where cell (c, r) spans [c, c+1] x [r, r+1].
  const double ou = o.x() / g.spacing_x_m + 0.5 * (g.cols - 1);
  const double ov = o.y() / g.spacing_y_m + 0.5 * (g.rows - 1);
  const double du = d.x() / g.spacing_x_m;
  const double dv = d.y() / g.spacing_y_m;
  double enter = t0;
  double exit = t1;
  clip_slab(ou, du, c_lo, c_hi, enter, exit);
  clip_slab(ov, dv, r_lo, r_hi, enter, exit);
  if (!(enter <= exit)) return kNoHit;

  int c = std::clamp(static_cast<int>(std::floor(ou + enter * du)), c_lo, c_hi - 1);
  int r = std::clamp(static_cast<int>(std::floor(ov + enter * dv)), r_lo, r_hi - 1);
  const int step_c = du > 0.0 ? 1 : -1;
  const int step_r = dv > 0.0 ? 1 : -1;
  const auto next_c = [&] { return du == 0.0 ? kNoHit : (c + (step_c > 0) - ou) / du; };
  const auto next_r = [&] { return dv == 0.0 ? kNoHit : (r + (step_r > 0) - ov) / dv; };
  double t_next_c = next_c();
  double t_next_r = next_r();
  const ShearedRay ray = shear(o, d);
  // Slack on the cell's height range test; the triangle test decides.
  constexpr double kSlack_m = 1e-6;
  for (double t_start = enter;;) {
    const double t_end = std::min({t_next_c, t_next_r, exit});
    const double z0 = o.z() + t_start * d.z();
    const double z1 = o.z() + t_end * d.z();
    const double h00 = g.at(c, r), h10 = g.at(c + 1, r), h01 = g.at(c, r + 1),
                 h11 = g.at(c + 1, r + 1);
    if (std::min(z0, z1) <= std::max({h00, h10, h01, h11}) + kSlack_m &&
        std::max(z0, z1) >= std::min({h00, h10, h01, h11}) - kSlack_m) {
      const double x0 = terrain.vertex_x(c), x1 = terrain.vertex_x(c + 1);
      const double y0 = terrain.vertex_y(r), y1 = terrain.vertex_y(r + 1);
      const ShearedVertex p00 = project(ray, x0, y0, h00), p10 = project(ray, x1, y0, h10);
      const ShearedVertex p01 = project(ray, x0, y1, h01), p11 = project(ray, x1, y1, h11);
      // The split along (c+1, r)-(c, r+1); cells come in ray order, so the
      // first cell with a hit holds the nearest one.
      const double t = std::min(intersect_triangle(p00, p10, p01, t0, t1),
                                intersect_triangle(p10, p11, p01, t0, t1));
      if (t < kNoHit) return t;
    }
    if (t_end >= exit) return kNoHit;
    const bool across_c = t_next_c <= t_next_r;
    const bool across_r = t_next_r <= t_next_c;
    if (across_c) {
      c += step_c;
      if (c < c_lo || c >= c_hi) return kNoHit;
      t_next_c = next_c();
    }
    if (across_r) {
      r += step_r;
      if (r < r_lo || r >= r_hi) return kNoHit;
      t_next_r = next_r();
    }
    t_start = t_end;
  }
}

void terrain_bounds(const RTCBoundsFunctionArguments* args) {
  const auto& terrain = *static_cast<const Terrain*>(args->geometryUserPtr);
  const HeightGrid& g = *terrain.grid;
  int c_lo, c_hi, r_lo, r_hi;
  terrain.block_cells(args->primID, c_lo, c_hi, r_lo, r_hi);
  double z_lo = kNoHit, z_hi = -kNoHit;
  for (int r = r_lo; r <= r_hi; ++r) {
    for (int c = c_lo; c <= c_hi; ++c) {
      z_lo = std::min(z_lo, g.at(c, r));
      z_hi = std::max(z_hi, g.at(c, r));
    }
  }
  Eigen::AlignedBox3d box;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d local(terrain.vertex_x(corner & 1 ? c_hi : c_lo),
                                terrain.vertex_y(corner & 2 ? r_hi : r_lo),
                                corner & 4 ? z_hi : z_lo);
    box.extend(terrain.rotation * local + terrain.translation);
  }
  write_bounds(box, args->bounds_o);
}

void terrain_intersect(const RTCIntersectFunctionNArguments* args) {
  const auto& terrain = *static_cast<const Terrain*>(args->geometryUserPtr);
  intersect_rays(
      args, [&](const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t0, double t1) {
        return intersect_terrain_block(terrain, args->primID, origin, dir, t0, t1);
      });
}

// What a mesh's triangle callback sees: one ray in the mesh's local frame,
// sheared once so that every triangle projects its shared vertices the same
// way (no ray slips through an edge), and the nearest exact hit so far.
struct MeshRayContext {
  RTCIntersectContext base;
  ShearedRay ray;
  double best;
};
static_assert(std::is_standard_layout_v<MeshRayContext>);

void mesh_triangle_bounds(const RTCBoundsFunctionArguments* args) {
  const TriangleMesh& mesh = *static_cast<const MeshModel*>(args->geometryUserPtr)->mesh;
  const std::array<std::uint32_t, 3>& tri = mesh.triangles[args->primID];
  Eigen::AlignedBox3d box(mesh.vertices_m[tri[0]]);
  box.extend(mesh.vertices_m[tri[1]]);
  box.extend(mesh.vertices_m[tri[2]]);
  write_bounds(box, args->bounds_o);
}

// Called by rtcIntersect1 in intersect_mesh: one ray (N = 1), the one in the context.
void mesh_triangle_intersect(const RTCIntersectFunctionNArguments* args) {
  auto& context = *reinterpret_cast<MeshRayContext*>(args->context);
  const TriangleMesh& mesh = *static_cast<const MeshModel*>(args->geometryUserPtr)->mesh;
  const std::array<std::uint32_t, 3>& tri = mesh.triangles[args->primID];
  assert(args->N == 1);
  if (args->valid[0] != -1) return;
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, 1);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, 1);
  const auto vertex = [&](std::uint32_t i) {
    const Eigen::Vector3d& v = mesh.vertices_m[i];
    return project(context.ray, v.x(), v.y(), v.z());
  };
  float& tfar = RTCRayN_tfar(rays, 1, 0);
  const double t = intersect_triangle(vertex(tri[0]), vertex(tri[1]), vertex(tri[2]), RTCRayN_tnear(rays, 1, 0), tfar);
  if (!(t < kNoHit)) return;
  tfar = static_cast<float>(t);  // shortens the traversal; the exact t is kept in the context
  context.best = std::min(context.best, t);
  RTCHitN_geomID(hits, 1, 0) = args->geomID;
  RTCHitN_primID(hits, 1, 0) = args->primID;
}

// Nearest hit in [t0, t1] of the world ray origin + t dir with mesh shape `p`.
// The ray keeps its parameter in the local frame (a rotation keeps lengths).
double intersect_mesh(const Primitive& p, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t0,
                      double t1) {
  const Eigen::Vector3d o = p.rotation.transpose() * (origin - p.center);
  const Eigen::Vector3d d = p.rotation.transpose() * dir;
  MeshRayContext context;
  rtcInitIntersectContext(&context.base);
  context.ray = shear(o, d);
  context.best = kNoHit;
  RTCRayHit query;
  const Eigen::Vector3f of = o.cast<float>(), df = d.cast<float>();
  query.ray.org_x = of.x();
  query.ray.org_y = of.y();
  query.ray.org_z = of.z();
  query.ray.dir_x = df.x();
  query.ray.dir_y = df.y();
  query.ray.dir_z = df.z();
  query.ray.tnear = static_cast<float>(t0);
  query.ray.tfar = static_cast<float>(t1);
  query.ray.time = 0.0f;
  query.ray.mask = ~0u;
  query.ray.id = 0;
  query.ray.flags = 0;
  query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(p.mesh->scene, &context.base, &query);
  return context.best >= t0 && context.best <= t1 ? context.best : kNoHit;
}

}  // namespace

// One Embree scene: a user geometry holding the analytic primitives, plus one
// user geometry per heightfield.
struct Layer {
  RTCScene scene = nullptr;
  std::vector<Primitive> primitives;  // element addresses are handed to Embree
  std::deque<Terrain> terrains;       // likewise (a deque never moves them)
  unsigned primitive_geometry = RTC_INVALID_GEOMETRY_ID;
  std::vector<std::int32_t> geometry_shape;  // geomID -> RayHit::shape, for terrains

  std::int32_t shape_of(unsigned geom_id, unsigned prim_id) const {
    return geom_id == primitive_geometry ? primitives[prim_id].shape : geometry_shape[geom_id];
  }
};

namespace {

// Buffers of a fan cast, kept per thread between casts: no allocation per scan
// once they have grown.
struct FanScratch {
  std::vector<float> best_t;
  std::vector<std::int32_t> best_shape;
  std::vector<double> x, y, z;  // a heightfield patch's or a mesh's vertices, in the sensor frame
  std::vector<float> xf, yf, zf;  // the same rounded to float, for culling and projecting

  // Room for `count` vertices, and vertex k set to p (and its float copy).
  void resize_vertices(std::size_t count) {
    for (std::vector<double>* v : {&x, &y, &z}) v->resize(count);
    for (std::vector<float>* v : {&xf, &yf, &zf}) v->resize(count);
  }
  void set_vertex(std::size_t k, const Eigen::Vector3d& p) {
    x[k] = p.x();
    y[k] = p.y();
    z[k] = p.z();
    xf[k] = static_cast<float>(p.x());
    yf[k] = static_cast<float>(p.y());
    zf[k] = static_cast<float>(p.z());
  }
  std::vector<fan::Plane> planes;
  std::vector<fan::Primitive> primitives;
  std::vector<Eigen::Vector3f> directions;  // world directions, for a fan cast through Embree
};

FanScratch& fan_scratch() {
  thread_local FanScratch scratch;
  return scratch;
}

// Cells [c0, c1] x [r0, r1] of a heightfield within `range` of `origin_local`
// horizontally; false when none.
bool cells_in_range(const Terrain& terrain, const Eigen::Vector3d& origin_local, double range, int& c0, int& c1,
                    int& r0, int& r1) {
  const HeightGrid& g = *terrain.grid;
  const double u = origin_local.x() / g.spacing_x_m + 0.5 * (g.cols - 1);
  const double v = origin_local.y() / g.spacing_y_m + 0.5 * (g.rows - 1);
  const double du = range / g.spacing_x_m, dv = range / g.spacing_y_m;
  const double lo_c = std::max(0.0, std::floor(u - du)), hi_c = std::min(g.cols - 2.0, std::floor(u + du));
  const double lo_r = std::max(0.0, std::floor(v - dv)), hi_r = std::min(g.rows - 2.0, std::floor(v + dv));
  if (!(lo_c <= hi_c && lo_r <= hi_r)) return false;
  c0 = static_cast<int>(lo_c);
  c1 = static_cast<int>(hi_c);
  r0 = static_cast<int>(lo_r);
  r1 = static_cast<int>(hi_r);
  return true;
}

// True when mesh shape `p`'s bounding sphere comes within `range` of `origin`.
bool mesh_in_range(const Primitive& p, const Eigen::Vector3d& origin, double range) {
  return (p.center + p.rotation * p.mesh->centre - origin).norm() - p.mesh->radius * (1.0 + 1e-9) - 1e-6 <= range;
}

// True when mesh shape `p` has an outside (MeshModel::facing) and `origin`
// lies outside its bounds by more than `min_range` (and a micrometre): every
// ray then meets a face turned towards the origin, at or past min_range,
// before any face turned away.
bool back_faces_hidden(const Primitive& p, const Eigen::Vector3d& origin, double min_range) {
  if (p.mesh->facing.empty()) return false;
  const Eigen::Vector3d local = p.rotation.transpose() * (origin - p.center);
  return p.mesh->mesh->bounds_m.exteriorDistance(local) > min_range + 1e-6;
}

fan::Primitive fan_primitive(const Primitive& p, const Eigen::Matrix3d& sensor_to_world,
                             const Eigen::Vector3d& origin) {
  fan::Primitive f;
  const Eigen::Vector3f o = (p.rotation.transpose() * (origin - p.center)).cast<float>();
  const Eigen::Matrix3f to_local = (p.rotation.transpose() * sensor_to_world).cast<float>();
  const Eigen::Vector3f center = (sensor_to_world.transpose() * (p.center - origin)).cast<float>();
  for (int i = 0; i < 3; ++i) {
    f.origin[i] = o[i];
    f.center[i] = center[i];
    f.half[i] = static_cast<float>(p.half_extents[i]);
    for (int j = 0; j < 3; ++j) f.to_local[3 * i + j] = to_local(i, j);
  }
  f.radius = static_cast<float>(p.half_extents.norm() * (1.0 + 1e-6) + 1e-6);
  switch (p.type) {
    case ShapeType::cuboid:
      f.kind = fan::Kind::cuboid;
      break;
    case ShapeType::cylinder:
      f.kind = fan::Kind::cylinder;
      break;
    case ShapeType::cone:
      f.kind = fan::Kind::cone;
      break;
    case ShapeType::sphere:
    case ShapeType::plane:  // never a Primitive (make_primitive)
    case ShapeType::heightfield:
    case ShapeType::mesh:   // never a fan::Primitive (cast_fan casts a mesh's triangles)
      f.kind = fan::Kind::sphere;
      break;
  }
  f.shape = p.shape;
  return f;
}

}  // namespace

// A fan is cast by projection from this many rays on, and when the surfaces
// in range (primitives and heightfield cells) number at most this many per
// ray.
constexpr std::size_t kMinFanRays = 256;
constexpr double kFanRaysPerSurface = 2.0;

struct RayCaster::Impl {
  RTCDevice device = nullptr;
  Layer fixed;   // static shapes, built once with high quality
  Layer moving;  // dynamic shapes and movers, moved by set_poses()
  std::vector<Plane> planes;
  // One model per distinct TriangleMesh (shapes may share one); the deque keeps addresses.
  std::deque<MeshModel> mesh_models;
  std::unordered_map<const TriangleMesh*, const MeshModel*> mesh_model_of;
  CastMethod method = CastMethod::automatic;
  bool fan_kernels = false;

  ~Impl() {
    if (fixed.scene) rtcReleaseScene(fixed.scene);
    if (moving.scene) rtcReleaseScene(moving.scene);
    for (const MeshModel& model : mesh_models) rtcReleaseScene(model.scene);
    if (device) rtcReleaseDevice(device);
  }

  // The model of `mesh`, built on first use: its triangles as user primitives
  // in a scene of their own, high-quality BVH.
  const MeshModel* mesh_model(const TriangleMesh& mesh) {
    if (const auto it = mesh_model_of.find(&mesh); it != mesh_model_of.end()) return it->second;
    MeshModel& model = mesh_models.emplace_back();
    model.mesh = &mesh;
    // An empty mesh (refused by the loader) would have infinite bounds: a point at the origin instead.
    model.centre.setZero();
    model.half.setZero();
    if (!mesh.bounds_m.isEmpty()) {
      model.centre = mesh.bounds_m.center();
      model.half = 0.5 * mesh.bounds_m.sizes();
    }
    for (const Eigen::Vector3d& v : mesh.vertices_m) model.radius = std::max(model.radius, (v - model.centre).norm());
    if (const MeshFacing facing = mesh_facing(mesh); !facing.two_sided) {
      for (const bool flip : facing.flip) model.facing.push_back(flip ? -1 : 1);
    }
    model.scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(model.scene, RTC_BUILD_QUALITY_HIGH);
    if (!mesh.triangles.empty()) {
      RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
      rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_HIGH);
      rtcSetGeometryUserPrimitiveCount(geom, static_cast<unsigned>(mesh.triangles.size()));
      rtcSetGeometryUserData(geom, &model);
      rtcSetGeometryBoundsFunction(geom, &mesh_triangle_bounds, nullptr);
      rtcSetGeometryIntersectFunction(geom, &mesh_triangle_intersect);
      rtcCommitGeometry(geom);
      rtcAttachGeometry(model.scene, geom);
      rtcReleaseGeometry(geom);
    }
    rtcCommitScene(model.scene);
    check("building a mesh's triangle scene");
    mesh_model_of.emplace(&mesh, &model);
    return &model;
  }

  Primitive primitive(const Shape& shape, std::int32_t id) {
    Primitive p = make_primitive(shape, id);
    if (shape.type == ShapeType::mesh) {
      p.mesh = mesh_model(*shape.mesh);
    }
    return p;
  }

  void check(const char* what) const {
    const RTCError error = rtcGetDeviceError(device);
    if (error != RTC_ERROR_NONE) {
      throw std::runtime_error(std::string("RayCaster: Embree error ") +
                               std::to_string(static_cast<int>(error)) + " while " + what);
    }
  }

  // A user geometry of `count` primitives described by `data`; its geomID.
  unsigned attach(Layer& layer, RTCBuildQuality quality, unsigned count, void* data,
                  RTCBoundsFunction bounds, RTCIntersectFunctionN intersect) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryBuildQuality(geom, quality);
    rtcSetGeometryUserPrimitiveCount(geom, count);
    rtcSetGeometryUserData(geom, data);
    rtcSetGeometryBoundsFunction(geom, bounds, nullptr);
    rtcSetGeometryIntersectFunction(geom, intersect);
    rtcCommitGeometry(geom);
    const unsigned id = rtcAttachGeometry(layer.scene, geom);
    rtcReleaseGeometry(geom);
    layer.geometry_shape.resize(std::max<std::size_t>(layer.geometry_shape.size(), id + 1),
                                RayHit::kNoShape);
    return id;
  }

  void attach_primitives(Layer& layer, RTCBuildQuality quality) {
    if (layer.primitives.empty()) return;
    layer.primitive_geometry =
        attach(layer, quality, static_cast<unsigned>(layer.primitives.size()),
               layer.primitives.data(), &primitive_bounds, &primitive_intersect);
  }

  void attach_terrain(Layer& layer, const Shape& shape, std::int32_t id) {
    Terrain& terrain = layer.terrains.emplace_back(make_terrain(shape, id));
    const auto blocks = static_cast<unsigned>(terrain.blocks_x * terrain.blocks_y);
    const unsigned geom_id = attach(layer, RTC_BUILD_QUALITY_HIGH, blocks, &terrain,
                                    &terrain_bounds, &terrain_intersect);
    layer.geometry_shape[geom_id] = id;
  }

  void cast_embree(const Eigen::Vector3d& origin, std::span<const Eigen::Vector3f> directions,
                   float min_range_m, float max_range_m, std::span<RayHit> hits) const {
    assert(directions.size() == hits.size());
    CastContext context;
    rtcInitIntersectContext(&context.base);
    context.base.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    context.origin = origin;
    const Eigen::Vector3f origin_f = origin.cast<float>();

    // Rays go to Embree in fixed-size batches on the stack: no allocation.
    constexpr std::size_t kBatch = 64;
    RTCRayHit batch[kBatch];
    std::int32_t shape[kBatch];
    for (std::size_t start = 0; start < directions.size(); start += kBatch) {
      const std::size_t count = std::min(kBatch, directions.size() - start);
      for (std::size_t i = 0; i < count; ++i) {
        const Eigen::Vector3f& d = directions[start + i];
        RTCRay& ray = batch[i].ray;
        ray.org_x = origin_f.x();
        ray.org_y = origin_f.y();
        ray.org_z = origin_f.z();
        ray.dir_x = d.x();
        ray.dir_y = d.y();
        ray.dir_z = d.z();
        ray.tnear = min_range_m;
        ray.tfar = max_range_m;
        ray.time = 0.0f;
        ray.mask = ~0u;
        ray.id = 0;
        ray.flags = 0;
        batch[i].hit.geomID = RTC_INVALID_GEOMETRY_ID;
        batch[i].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        shape[i] = RayHit::kNoShape;
        // Planes first: a plane hit only shortens the ray for Embree.
        const Eigen::Vector3d dir = d.cast<double>();
        for (const Plane& plane : planes) {
          const double t = plane.normal.dot(plane.point - origin) / plane.normal.dot(dir);
          if (t >= min_range_m && t <= ray.tfar) {
            ray.tfar = static_cast<float>(t);
            shape[i] = plane.shape;
          }
        }
      }
      rtcIntersect1M(fixed.scene, &context.base, batch, static_cast<unsigned>(count),
                     sizeof(RTCRayHit));
      for (std::size_t i = 0; i < count; ++i) {
        RTCHit& hit = batch[i].hit;
        if (hit.geomID != RTC_INVALID_GEOMETRY_ID) {
          shape[i] = fixed.shape_of(hit.geomID, hit.primID);
          hit.geomID = RTC_INVALID_GEOMETRY_ID;
        }
      }
      if (moving.scene) {
        rtcIntersect1M(moving.scene, &context.base, batch, static_cast<unsigned>(count),
                       sizeof(RTCRayHit));
        for (std::size_t i = 0; i < count; ++i) {
          const RTCHit& hit = batch[i].hit;
          if (hit.geomID != RTC_INVALID_GEOMETRY_ID)
            shape[i] = moving.shape_of(hit.geomID, hit.primID);
        }
      }
      for (std::size_t i = 0; i < count; ++i) {
        RayHit& out = hits[start + i];
        out.shape = shape[i];
        out.distance_m =
            shape[i] == RayHit::kNoShape ? std::numeric_limits<float>::infinity() : batch[i].ray.tfar;
      }
    }
  }

  // True when casting `fan` by projection does less work than ray by ray: a
  // scan of many rays over the geometry within range (a handful of beams
  // reaching far over a large heightfield is faster through the BVH).
  bool fan_pays(const RayFan& fan, const Eigen::Vector3d& origin, float max_range_m) const {
    if (method != CastMethod::automatic) return method == CastMethod::fan;
    if (!fan_kernels || fan.size() < kMinFanRays) return false;
    double surfaces = static_cast<double>(fixed.primitives.size() + moving.primitives.size());
    for (const Terrain& terrain : fixed.terrains) {
      int c0, c1, r0, r1;
      const Eigen::Vector3d local = terrain.rotation.transpose() * (origin - terrain.translation);
      if (cells_in_range(terrain, local, max_range_m, c0, c1, r0, r1)) {
        surfaces += (c1 - c0 + 1.0) * (r1 - r0 + 1.0);
      }
    }
    // A mesh in range is as many surfaces as it has triangles (one is counted above).
    for (const Layer* layer : {&fixed, &moving}) {
      for (const Primitive& p : layer->primitives) {
        if (p.type != ShapeType::mesh || !mesh_in_range(p, origin, max_range_m)) continue;
        surfaces += static_cast<double>(p.mesh->mesh->triangles.size()) - 1.0;
      }
    }
    return surfaces <= kFanRaysPerSurface * static_cast<double>(fan.size());
  }

  void cast_fan(const Eigen::Isometry3d& pose, const RayFan& fan, float min_range_m, float max_range_m,
                std::span<RayHit> hits) const {
    FanScratch& scratch = fan_scratch();
    const fan::Rays rays = fan.rays();
    // Rounded up to whole vectors of eight, and the eight readable past them.
    scratch.best_t.resize(rays.size + 16);
    scratch.best_shape.resize(rays.size + 16);
    const fan::Best best{scratch.best_t.data(), scratch.best_shape.data()};
    fan::reset(best, rays.size, std::min(max_range_m, std::numeric_limits<float>::max()), RayHit::kNoShape);
    const Eigen::Matrix3d& rotation = pose.linear();
    const Eigen::Vector3d& origin = pose.translation();

    for (const Terrain& terrain : fixed.terrains) {
      const Eigen::Vector3d local = terrain.rotation.transpose() * (origin - terrain.translation);
      int c0, c1, r0, r1;
      if (!cells_in_range(terrain, local, max_range_m, c0, c1, r0, r1)) continue;
      // Vertices in the sensor frame: turn v + shift for a local vertex v.
      const Eigen::Matrix3d turn = rotation.transpose() * terrain.rotation;
      const Eigen::Vector3d shift = rotation.transpose() * (terrain.translation - origin);
      const int cols = c1 - c0 + 2, rows = r1 - r0 + 2;
      const auto count = static_cast<std::size_t>(cols) * static_cast<std::size_t>(rows);
      scratch.resize_vertices(count);
      std::size_t k = 0;
      for (int r = r0; r <= r1 + 1; ++r) {
        const Eigen::Vector3d row = shift + turn.col(1) * terrain.vertex_y(r);
        for (int c = c0; c <= c1 + 1; ++c, ++k) {
          scratch.set_vertex(k, row + turn.col(0) * terrain.vertex_x(c) + turn.col(2) * terrain.grid->at(c, r));
        }
      }
      const fan::TerrainPatch patch{scratch.x.data(),  scratch.y.data(),  scratch.z.data(), scratch.xf.data(),
                                    scratch.yf.data(), scratch.zf.data(), cols,             rows,
                                    terrain.shape};
      fan::cast_terrain(rays, patch, min_range_m, max_range_m, best);
    }

    scratch.primitives.clear();
    for (const Layer* layer : {&fixed, &moving}) {
      for (const Primitive& p : layer->primitives) {
        if (p.type != ShapeType::mesh) scratch.primitives.push_back(fan_primitive(p, rotation, origin));
      }
    }
    fan::cast_primitives(rays, scratch.primitives.data(), static_cast<int>(scratch.primitives.size()), min_range_m,
                         max_range_m, best);

    // Meshes: their vertices turned into the sensor frame, each triangle
    // projected and tested like a heightfield cell's.
    for (const Layer* layer : {&fixed, &moving}) {
      for (const Primitive& p : layer->primitives) {
        if (p.type != ShapeType::mesh || !mesh_in_range(p, origin, max_range_m)) continue;
        const TriangleMesh& mesh = *p.mesh->mesh;
        const Eigen::Matrix3d turn = rotation.transpose() * p.rotation;
        const Eigen::Vector3d shift = rotation.transpose() * (p.center - origin);
        const std::size_t count = mesh.vertices_m.size();
        scratch.resize_vertices(count);
        for (std::size_t k = 0; k < count; ++k) scratch.set_vertex(k, turn * mesh.vertices_m[k] + shift);
        static_assert(sizeof(mesh.triangles[0]) == 3 * sizeof(std::uint32_t));
        const fan::TriangleSoup soup{scratch.x.data(),
                                     scratch.y.data(),
                                     scratch.z.data(),
                                     scratch.xf.data(),
                                     scratch.yf.data(),
                                     scratch.zf.data(),
                                     mesh.triangles.empty() ? nullptr : mesh.triangles.front().data(),
                                     back_faces_hidden(p, origin, min_range_m) ? p.mesh->facing.data() : nullptr,
                                     static_cast<std::uint32_t>(mesh.triangles.size()),
                                     p.shape};
        fan::cast_triangles(rays, soup, min_range_m, max_range_m, best);
      }
    }

    // Planes last, in reverse order, keeping strictly nearer hits only: the
    // answer of casting them first (fan::cast_planes), but rays stopped
    // short of the ground by then skip it.
    scratch.planes.clear();
    for (auto plane = planes.rbegin(); plane != planes.rend(); ++plane) {
      const Eigen::Vector3d n = rotation.transpose() * plane->normal;
      scratch.planes.push_back({{n.x(), n.y(), n.z()}, plane->normal.dot(plane->point - origin), plane->shape});
    }
    fan::cast_planes(rays, scratch.planes.data(), static_cast<int>(scratch.planes.size()), min_range_m, best);

    fan::write_hits(fan.order().data(), rays.size, best, RayHit::kNoShape, hits.data());
  }
};

RayCaster::RayCaster(const Scene& scene, CastMethod method) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.method = method;
  m.fan_kernels = fan::kernels_available();
  if (method == CastMethod::fan && !m.fan_kernels) {
    throw std::runtime_error("RayCaster: casting by fan needs a CPU with AVX2 and FMA");
  }
  m.device = rtcNewDevice(nullptr);
  if (!m.device) throw std::runtime_error("RayCaster: cannot create an Embree device");

  m.fixed.scene = rtcNewScene(m.device);
  rtcSetSceneBuildQuality(m.fixed.scene, RTC_BUILD_QUALITY_HIGH);
  for (std::size_t i = 0; i < scene.shapes.size(); ++i) {
    const Shape& shape = scene.shapes[i];
    const auto id = static_cast<std::int32_t>(i);
    if (!shape.is_static) continue;  // a moving body
    if (shape.type == ShapeType::plane) {
      m.planes.push_back({shape.pose.translation(), shape.pose.linear().col(2), id});
    } else if (shape.type == ShapeType::heightfield) {
      m.attach_terrain(m.fixed, shape, id);
    } else {
      m.fixed.primitives.push_back(m.primitive(shape, id));
    }
  }
  m.attach_primitives(m.fixed, RTC_BUILD_QUALITY_HIGH);
  rtcCommitScene(m.fixed.scene);
  m.check("building the static scene");

  const std::vector<MovingBody> bodies = moving_bodies(scene);
  if (!bodies.empty()) {
    m.moving.scene = rtcNewScene(m.device);
    rtcSetSceneFlags(m.moving.scene, RTC_SCENE_FLAG_DYNAMIC);
    rtcSetSceneBuildQuality(m.moving.scene, RTC_BUILD_QUALITY_LOW);
    for (const MovingBody& body : bodies) {
      const Shape& shape = *body.shape;
      if (shape.type == ShapeType::plane || shape.type == ShapeType::heightfield) {
        throw std::invalid_argument("RayCaster: moving body '" + shape.alias + "' is a " +
                                    std::string(to_string(shape.type)) +
                                    "; moving bodies must be cuboids, cylinders, cones, spheres or meshes");
      }
      m.moving.primitives.push_back(m.primitive(shape, body.id));
    }
    m.attach_primitives(m.moving, RTC_BUILD_QUALITY_LOW);
    rtcCommitScene(m.moving.scene);
    m.check("building the scene of moving bodies");
  }
}

RayCaster::~RayCaster() = default;

void RayCaster::set_poses(std::span<const Eigen::Isometry3d> poses) {
  Impl& m = *impl_;
  if (poses.size() != m.moving.primitives.size()) {
    throw std::invalid_argument("RayCaster::set_poses: " + std::to_string(poses.size()) + " poses for " +
                                std::to_string(m.moving.primitives.size()) + " moving bodies");
  }
  if (!m.moving.scene) return;
  bool moved = false;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    Primitive& p = m.moving.primitives[i];
    if (p.center == poses[i].translation() && p.rotation == poses[i].linear()) continue;
    p.center = poses[i].translation();
    p.rotation = poses[i].linear();
    moved = true;
  }
  // Bodies at rest (a box that has landed) cost no rebuild.
  if (!moved) return;
  rtcCommitGeometry(rtcGetGeometry(m.moving.scene, m.moving.primitive_geometry));
  rtcCommitScene(m.moving.scene);
}

void RayCaster::cast(const Eigen::Vector3d& origin, std::span<const Eigen::Vector3f> directions,
                     float min_range_m, float max_range_m, std::span<RayHit> hits) const {
  assert(directions.size() == hits.size());
  if (impl_->method == CastMethod::fan) {
    const RayFan fan(directions);
    cast(Eigen::Isometry3d(Eigen::Translation3d(origin)), fan, min_range_m, max_range_m, hits);
    return;
  }
  impl_->cast_embree(origin, directions, min_range_m, max_range_m, hits);
}

void RayCaster::cast(const Eigen::Isometry3d& sensor_pose, const RayFan& fan, float min_range_m,
                     float max_range_m, std::span<RayHit> hits) const {
  assert(fan.size() == hits.size());
  const Impl& m = *impl_;
  if (m.fan_pays(fan, sensor_pose.translation(), max_range_m)) {
    m.cast_fan(sensor_pose, fan, min_range_m, max_range_m, hits);
    return;
  }
  // Ray by ray: the fan's directions turned into the world, in beam order.
  std::vector<Eigen::Vector3f>& world = fan_scratch().directions;
  world.resize(fan.size());
  const fan::Rays rays = fan.rays();
  const Eigen::Matrix3f rotation = sensor_pose.linear().cast<float>();
  const std::span<const std::uint32_t> order = fan.order();
  for (std::size_t k = 0; k < order.size(); ++k) {
    world[order[k]] = rotation * Eigen::Vector3f(rays.x[k], rays.y[k], rays.z[k]);
  }
  m.cast_embree(sensor_pose.translation(), world, min_range_m, max_range_m, hits);
}

}  // namespace campo
