#pragma once
/// The inner loops of casting a RayFan (sensors/ray_fan.hpp): each surface is
/// projected onto the bins of the fan it may cover and tested against their
/// rays, eight at a time in float (primitives) or four in double (heightfield
/// cells, planes). Everything here is in the sensor frame, relative to the
/// fan's origin. The kernels are compiled for AVX2 + FMA and only called where
/// the CPU has them (kernels_available()); the inputs are plain structs so
/// that no inline function of another header is compiled for an instruction
/// set the rest of campo does not assume.
#include <cstdint>

namespace campo::fan {

/// Cube-map faces: face f looks along axis f / 2, positive when f is even.
/// A direction belongs to the face of its largest component; on face f its
/// coordinates are u = p[(f/2 + 1) % 3] / w, v = p[(f/2 + 2) % 3] / w with
/// w = ±p[f/2], both in [-1, 1].
constexpr int kFaces = 6;

/// Bin of face coordinate u on a face of `grid` bins a side. RayFan bins rays
/// with it and the kernels bin surfaces (padded, so a ray on a boundary is
/// found from either side). `static`: each file gets its own copy, compiled
/// for its own instruction set.
static inline int bin_of(float u, int grid) {
  u = __builtin_fminf(__builtin_fmaxf(u, -1.0f), 1.0f);  // also turns NaN into -1
  const int i = static_cast<int>((u + 1.0f) * 0.5f * static_cast<float>(grid));
  return i < grid ? i : grid - 1;
}

/// Rays sorted by bin, structure of arrays; readable 8 floats past `size`.
struct Rays {
  const float* x = nullptr;
  const float* y = nullptr;
  const float* z = nullptr;
  std::uint32_t size = 0;
  int grid[kFaces] = {};                // bins per side of each face; 0 when it holds no ray
  std::uint32_t first_bin[kFaces] = {};  // index of a face's bin (0, 0) in bin_start
  const std::uint32_t* bin_start = nullptr;  // first slot of bin b; bin_start[b + 1] ends it
  // A cone around every ray (unit axis, cosine and sine of its half-angle,
  // padded): a surface outside it is skipped unprojected. A fan over more
  // than a hemisphere has cone_cos = -1: nothing is outside.
  float cone_axis[3] = {1.0f, 0.0f, 0.0f};
  float cone_cos = -1.0f;
  float cone_sin = 0.0f;
};

/// Nearest hit so far per sorted slot: distance (starts at the max range, and
/// at most the largest float: a lane without a hit carries +inf, which must
/// never count as one) and shape (RayHit::shape).
struct Best {
  float* t = nullptr;
  std::int32_t* shape = nullptr;
};

/// An infinite plane: n . (t d) = offset, the origin at 0.
struct Plane {
  double normal[3];
  double offset;  ///< n . (point on the plane - origin)
  std::int32_t shape;
};

/// A grid of heightfield vertices in the sensor frame, row-major; cell (c, r)
/// is split along (c + 1, r)-(c, r + 1) like the heightfield. In double: a
/// ray grazing the ground meets it at a distance that moves by the vertices'
/// rounding divided by the grazing angle, and float vertices ten metres away
/// put such hits millimetres off.
struct TerrainPatch {
  const double* x = nullptr;
  const double* y = nullptr;
  const double* z = nullptr;
  const float* xf = nullptr;  ///< the same vertices rounded to float (culling, projection)
  const float* yf = nullptr;
  const float* zf = nullptr;
  int cols = 0;  ///< vertices per row
  int rows = 0;
  std::int32_t shape = 0;
};

/// A triangle mesh's vertices in the sensor frame (in double, as a
/// heightfield's, and rounded to float for culling and projection) and its
/// triangles as three vertex indices each. Open or closed, either winding: a
/// triangle is met from both sides.
struct TriangleSoup {
  const double* x = nullptr;
  const double* y = nullptr;
  const double* z = nullptr;
  const float* xf = nullptr;
  const float* yf = nullptr;
  const float* zf = nullptr;
  const std::uint32_t* triangles = nullptr;  ///< 3 * count vertex indices
  /// Per triangle, +1 when it runs counter-clockwise seen from outside the
  /// mesh, -1 when clockwise; null when back faces must be tested too (an
  /// open mesh, or an origin inside the mesh's bounds or within t0 of them).
  /// Given, a triangle facing away from the origin (by more than 1e-9 rad) is
  /// skipped: a ray reaches a back face only through a front face nearer.
  const std::int8_t* facing = nullptr;
  std::uint32_t count = 0;
  std::int32_t shape = 0;
};

/// The analytic shapes of Primitive (sensors/raycaster.cpp), local axis z.
enum class Kind : std::uint8_t { cuboid, cylinder, cone, sphere };

struct Primitive {
  float origin[3];     ///< the fan's origin in the shape's local frame
  float to_local[9];   ///< row-major: sensor-frame direction -> local direction
  float half[3];       ///< cuboid: size/2; cylinder, cone: (r, r, h/2); sphere: (r, r, r)
  float center[3];     ///< the shape's centre in the sensor frame
  float radius;        ///< of a sphere around the shape
  Kind kind;
  std::int32_t shape;
};

/// True when the CPU runs the kernels (AVX2 and FMA).
bool kernels_available();

/// Sets slots [0, count) of `best`, and those past them up to the next
/// multiple of 8 plus 8 more (best holds count + 16), to (t, shape).
void reset(Best best, std::uint32_t count, float t, std::int32_t shape);
/// Writes each sorted slot's result to its beam: out[order[k]] = (t, shape)
/// as pairs of a float and an int32 (RayHit's layout), t = +inf where the
/// shape is `no_shape`.
void write_hits(const std::uint32_t* order, std::uint32_t count, Best best, std::int32_t no_shape, void* out);

/// Each cast keeps, per ray, the nearest hit with t in [t0, best.t]: on a tie
/// the surface cast later wins.
void cast_terrain(const Rays& rays, const TerrainPatch& patch, float t0, float t1, Best best);
/// Each triangle as a heightfield cell's triangle is tested: every ray through
/// it, edges and vertices included, is found, so a closed mesh lets no ray out.
void cast_triangles(const Rays& rays, const TriangleSoup& soup, float t0, float t1, Best best);
void cast_primitives(const Rays& rays, const Primitive* primitives, int count, float t0, float t1,
                     Best best);
/// Planes keep a hit only when strictly nearer than the best so far: cast
/// last (when most rays have stopped short of the ground) and in reverse
/// order, they give what casting them first and in order would, where on a
/// tie the other surfaces win, then the later plane.
void cast_planes(const Rays& rays, const Plane* planes, int count, float t0, Best best);

}  // namespace campo::fan
