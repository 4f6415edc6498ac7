// Compiled with -mavx2 -mfma (CMakeLists.txt); see fan_kernels.hpp. Every
// helper has internal linkage and the maths are compiler builtins (which call
// the C library's functions when not expanded), not <cmath>'s inline
// overloads: an unoptimised build emits those as weak symbols, and the linker
// could hand an AVX2 copy of std::fmin to code that runs on any CPU.
#include "sensors/fan_kernels.hpp"

#include <cstddef>
#include <cstdint>

#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#define CAMPO_FAN_KERNELS 1
#endif

namespace campo::fan {

#if CAMPO_FAN_KERNELS

namespace {

constexpr float kInf = __builtin_inff();
constexpr float kHalfPi = 1.57079632679489662f;
// Margin on a surface's bin rectangle in face coordinates (which span [-1, 1]):
// covers the rounding of the vertices' projections and of the rays' own.
constexpr float kBinPad = 1e-5f;
// Slack on the rim tests of capped primitives, so a ray grazing a rim is not
// lost between the side test and the cap test through rounding: a few float
// roundings of the distances involved (the sensor's from the shape, the
// shape's size), per metre of them.
constexpr float kRimRounding = 1e-6f;

inline float min_f(float a, float b) { return a < b ? a : b; }
inline float max_f(float a, float b) { return a > b ? a : b; }

// Bins [i0, i1] x [j0, j1] of one face.
struct Rect {
  int face, i0, i1, j0, j1;
};

// Range of u = a / w covered by a ball (ca, cw, rho) seen from the origin in
// the (a, w) plane: the tangents from the origin bound it. False when the ball
// lies behind the face (w <= 0).
bool tangent_range(float ca, float cw, float rho, float& lo, float& hi) {
  const float l2 = ca * ca + cw * cw;
  if (l2 <= rho * rho) {
    lo = -kInf;
    hi = kInf;
    return true;
  }
  const float phi = __builtin_atan2f(ca, cw);
  const float delta = __builtin_asinf(min_f(1.0f, rho / __builtin_sqrtf(l2)));
  const float a0 = phi - delta, a1 = phi + delta;
  if (a0 >= kHalfPi || a1 <= -kHalfPi) return false;
  lo = a0 <= -kHalfPi ? -kInf : __builtin_tanf(a0);
  hi = a1 >= kHalfPi ? kInf : __builtin_tanf(a1);
  return true;
}

// The bins of face f whose rays may pass through the convex hull of points
// (px, py, pz)[0, n), which lies in the ball (c, rho). False when none.
bool face_rect(const Rays& rays, int f, const float* const p[3], int n, const float c[3], float rho,
               Rect& rect) {
  const int grid = rays.grid[f];
  if (grid == 0) return false;
  constexpr int kNext[3] = {1, 2, 0};
  const int m = f >> 1, a = kNext[m], b = kNext[a];
  const float s = (f & 1) ? -1.0f : 1.0f;
  float u0 = kInf, u1 = -kInf, v0 = kInf, v1 = -kInf;
  int front = 0;
  for (int k = 0; k < n; ++k) {
    const float w = s * p[m][k];
    if (!(w > 0.0f)) continue;
    ++front;
    const float inv = 1.0f / w;
    const float u = p[a][k] * inv, v = p[b][k] * inv;
    u0 = min_f(u0, u);
    u1 = max_f(u1, u);
    v0 = min_f(v0, v);
    v1 = max_f(v1, v);
  }
  // Every ray of the face has w > 0, so no point in front means no ray hits.
  if (front == 0) return false;
  if (front < n) {
    // The hull crosses the face's plane: its projection is unbounded; bound
    // it by the ball's tangents instead.
    const float r = rho * 1.0001f + 1e-6f;
    if (!tangent_range(c[a], s * c[m], r, u0, u1) || !tangent_range(c[b], s * c[m], r, v0, v1)) return false;
  }
  u0 -= kBinPad;
  u1 += kBinPad;
  v0 -= kBinPad;
  v1 += kBinPad;
  if (u0 > 1.0f || u1 < -1.0f || v0 > 1.0f || v1 < -1.0f) return false;
  rect = {f, bin_of(u0, grid), bin_of(u1, grid), bin_of(v0, grid), bin_of(v1, grid)};
  return true;
}

// The rectangles of every face for a hull; their count.
int hull_rects(const Rays& rays, const float* const p[3], int n, const float c[3], float rho,
               Rect (&rects)[kFaces]) {
  int count = 0;
  for (int f = 0; f < kFaces; ++f) count += face_rect(rays, f, p, n, c, rho, rects[count]);
  return count;
}

// Calls test(first, end) for each run of slots a rectangle covers: one run
// per row of bins, as a row's bins are contiguous.
template <class Test>
void for_each_run(const Rays& rays, const Rect& rect, Test&& test) {
  const int grid = rays.grid[rect.face];
  for (int j = rect.j0; j <= rect.j1; ++j) {
    const std::uint32_t row = rays.first_bin[rect.face] + static_cast<std::uint32_t>(j * grid);
    const std::uint32_t first = rays.bin_start[row + static_cast<std::uint32_t>(rect.i0)];
    const std::uint32_t end = rays.bin_start[row + static_cast<std::uint32_t>(rect.i1) + 1];
    if (first < end) test(first, end);
  }
}

// True when the ball (c, radius) lies wholly outside the fan's cone: the
// angle from the axis to its centre exceeds the cone's half-angle plus the
// ball's angular radius (by a margin of 1e-4 in their cosines).
bool outside_cone(const Rays& rays, const float c[3], float radius) {
  if (rays.cone_cos <= -1.0f) return false;
  const float l2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
  if (l2 <= radius * radius) return false;
  const float l = __builtin_sqrtf(l2);
  const float sin_b = radius / l, cos_b = __builtin_sqrtf(max_f(0.0f, 1.0f - sin_b * sin_b));
  // Past a half-turn (sine of the sum below 0) every direction is within.
  if (rays.cone_sin * cos_b + rays.cone_cos * sin_b < 0.0f) return false;
  const float cos_sum = rays.cone_cos * cos_b - rays.cone_sin * sin_b;
  const float along = rays.cone_axis[0] * c[0] + rays.cone_axis[1] * c[1] + rays.cone_axis[2] * c[2];
  return along < (cos_sum - 1e-4f) * l;
}

// --- eight lanes -----------------------------------------------------------

using V = __m256;

inline V set1(float x) { return _mm256_set1_ps(x); }
inline V add(V a, V b) { return _mm256_add_ps(a, b); }
inline V sub(V a, V b) { return _mm256_sub_ps(a, b); }
inline V mul(V a, V b) { return _mm256_mul_ps(a, b); }
inline V div(V a, V b) { return _mm256_div_ps(a, b); }
inline V fmadd(V a, V b, V c) { return _mm256_fmadd_ps(a, b, c); }
inline V vmin(V a, V b) { return _mm256_min_ps(a, b); }
inline V vmax(V a, V b) { return _mm256_max_ps(a, b); }
inline V vand(V a, V b) { return _mm256_and_ps(a, b); }
inline V ge(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_GE_OQ); }
inline V le(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_LE_OQ); }
inline V lt(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_LT_OQ); }
inline V select(V mask, V yes, V no) { return _mm256_blendv_ps(no, yes, mask); }
inline bool none(V mask) { return _mm256_movemask_ps(mask) == 0; }

// Lanes k + i < end.
inline V valid_lanes(std::uint32_t k, std::uint32_t end) {
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i left = _mm256_set1_epi32(static_cast<int>(end - k));
  return _mm256_castsi256_ps(_mm256_cmpgt_epi32(left, lane));
}

// Keeps `t` in `cand` where `ok`, t >= t0 and t is nearer.
inline void keep(V t, V ok, V t0, V& cand) {
  cand = select(vand(ok, vand(ge(t, t0), lt(t, cand))), t, cand);
}

// Writes the lanes of `cand` at least as near as the best so far (strictly
// nearer: kStrict) to it. A lane without a hit holds +inf; the best so far
// starts finite (see Best).
template <bool kStrict = false>
inline void commit(const Best& best, std::uint32_t k, V valid, V cand, std::int32_t shape) {
  const V old = _mm256_loadu_ps(best.t + k);
  const V take = vand(valid, kStrict ? lt(cand, old) : le(cand, old));
  if (none(take)) return;
  _mm256_storeu_ps(best.t + k, select(take, cand, old));
  const __m256i old_shape = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(best.shape + k));
  const __m256i new_shape = _mm256_blendv_epi8(old_shape, _mm256_set1_epi32(shape), _mm256_castps_si256(take));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(best.shape + k), new_shape);
}

// --- heightfield cells ------------------------------------------------------

// One cell's two triangles, (p00, p10, p01) and (p10, p11, p01), as seen from
// the origin. A ray d passes through a triangle when the edge functions
// d . (p x q) of its three edges have one sign. Each is computed with a
// rounding bound eps, and a triangle is accepted when its edge functions are
// all >= -eps or all <= eps: a superset of the rays that truly pass through
// it, edges and vertices included. Every ray that meets the surface is thus
// accepted by some triangle, whatever rounding did to the others: there is no
// crack to slip through, at a shared edge, a shared vertex or anywhere else.
// In double the margin is some 1e-15 rad wide.
using D = __m256d;

// Bound on the rounding of an edge function in double relative to the sum of
// the absolute products of p and q's components (5 roundings of 2^-53 each,
// doubled).
constexpr double kEdgeRounding = 1.2e-15;

struct Edge {
  double n[3];
  double eps;
};

Edge make_edge(const double p[3], const double q[3]) {
  Edge e;
  e.n[0] = p[1] * q[2] - p[2] * q[1];
  e.n[1] = p[2] * q[0] - p[0] * q[2];
  e.n[2] = p[0] * q[1] - p[1] * q[0];
  const double ax = __builtin_fabs(p[0]), ay = __builtin_fabs(p[1]), az = __builtin_fabs(p[2]);
  const double bx = __builtin_fabs(q[0]), by = __builtin_fabs(q[1]), bz = __builtin_fabs(q[2]);
  e.eps = kEdgeRounding * (ay * bz + az * by + az * bx + ax * bz + ax * by + ay * bx);
  return e;
}

struct Cell {
  Edge e0, diagonal, e2, e3, e4;  // p00p10, p10p01, p01p00 | p10p11, p11p01 (and p01p10 = -diagonal)
  double normal1[3], num1, normal2[3], num2;
  double near, far;  // distances from the origin bounding the cell
};

void triangle_plane(const double a[3], const double b[3], const double c[3], double n[3], double& num) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  n[0] = u[1] * v[2] - u[2] * v[1];
  n[1] = u[2] * v[0] - u[0] * v[2];
  n[2] = u[0] * v[1] - u[1] * v[0];
  num = n[0] * a[0] + n[1] * a[1] + n[2] * a[2];
}

inline D set1d(double x) { return _mm256_set1_pd(x); }
inline D dot3d(const double n[3], D x, D y, D z) {
  return _mm256_fmadd_pd(set1d(n[0]), x, _mm256_fmadd_pd(set1d(n[1]), y, _mm256_mul_pd(set1d(n[2]), z)));
}
inline D ged(D a, D b) { return _mm256_cmp_pd(a, b, _CMP_GE_OQ); }
inline D led(D a, D b) { return _mm256_cmp_pd(a, b, _CMP_LE_OQ); }
inline D andd(D a, D b) { return _mm256_and_pd(a, b); }
inline D ord(D a, D b) { return _mm256_or_pd(a, b); }

// All of a, b, c >= -eps (each its own), or all <= eps.
inline D one_sign(D a, D ea, D b, D eb, D c, D ec) {
  const D pos = andd(ged(a, -ea), andd(ged(b, -eb), ged(c, -ec)));
  const D neg = andd(led(a, ea), andd(led(b, eb), led(c, ec)));
  return ord(pos, neg);
}

// Nearest hit of four rays with a cell, +inf where none.
inline D hit_cell(const Cell& cell, D x, D y, D z, D t0) {
  const D a = dot3d(cell.e0.n, x, y, z), d = dot3d(cell.diagonal.n, x, y, z), c = dot3d(cell.e2.n, x, y, z);
  const D f = dot3d(cell.e3.n, x, y, z), g = dot3d(cell.e4.n, x, y, z);
  const D nd = _mm256_sub_pd(_mm256_setzero_pd(), d);  // the diagonal seen from the second triangle
  const D in1 = one_sign(a, set1d(cell.e0.eps), d, set1d(cell.diagonal.eps), c, set1d(cell.e2.eps));
  const D in2 = one_sign(f, set1d(cell.e3.eps), g, set1d(cell.e4.eps), nd, set1d(cell.diagonal.eps));
  const D inf = set1d(__builtin_inf());
  if (_mm256_movemask_pd(ord(in1, in2)) == 0) return inf;
  const D t1 = _mm256_div_pd(set1d(cell.num1), dot3d(cell.normal1, x, y, z));
  const D t2 = _mm256_div_pd(set1d(cell.num2), dot3d(cell.normal2, x, y, z));
  // A ray accepted at the margin meets the plane just outside the triangle;
  // one nearly in the plane could meet it anywhere, so hits are kept to the
  // cell's distances.
  const D lo = _mm256_max_pd(t0, set1d(cell.near)), hi = set1d(cell.far);
  const D ok1 = andd(in1, andd(ged(t1, lo), led(t1, hi)));
  const D ok2 = andd(in2, andd(ged(t2, lo), led(t2, hi)));
  const D cand = _mm256_blendv_pd(inf, t1, ok1);
  return _mm256_blendv_pd(cand, t2, andd(ok2, _mm256_cmp_pd(t2, cand, _CMP_LT_OQ)));
}

// The edge functions of a cell in float, eight rays at a time, as a cheap
// first look. What separates a float edge function from the double one
// hit_cell computes (the normal's rounding to float and the float dot
// product's, about 4 * 2^-24 of the sum of |n_i d_i|, taken as 3e-7 of |n|_1
// for unit d) plus hit_cell's own bound eps is the margin M: a float value of
// at least M means the double one is above +eps, at most -M below -eps. A ray
// whose edge functions settle both triangles this way gets hit_cell's answer
// with one plane (or none) instead of all five edges in double: the nearest
// hit is then that triangle's t = num / (n . d), computed as hit_cell computes
// it. Anything unsettled goes to hit_cell.
constexpr double kFloatEdgeSlack = 3e-7;

struct FloatEdge {
  V n[3];
  V margin;  // M
  V minus_margin;
};

FloatEdge float_edge(const Edge& e) {
  const double slack = kFloatEdgeSlack * (__builtin_fabs(e.n[0]) + __builtin_fabs(e.n[1]) + __builtin_fabs(e.n[2]));
  FloatEdge f;
  for (int i = 0; i < 3; ++i) f.n[i] = set1(static_cast<float>(e.n[i]));
  // Strictly above eps + slack once rounded to float.
  const auto margin = static_cast<float>((e.eps + slack) * (1.0 + 1e-5));
  f.margin = set1(margin);
  f.minus_margin = set1(-margin);
  return f;
}

struct FloatCell {
  FloatEdge e0, diagonal, e2, e3, e4;
};

inline V dot3(const V n[3], V x, V y, V z) { return fmadd(n[0], x, fmadd(n[1], y, mul(n[2], z))); }

// Per triangle, the rays surely through it (its edge functions all of one
// sign past the margin) and surely not (some past it on either side), as
// lane bits.
struct Settled {
  int in1, out1, in2, out2;
};

inline Settled settle(const FloatCell& f, V x, V y, V z) {
  const V a = dot3(f.e0.n, x, y, z), d = dot3(f.diagonal.n, x, y, z), c = dot3(f.e2.n, x, y, z);
  const V g = dot3(f.e3.n, x, y, z), h = dot3(f.e4.n, x, y, z);
  const V ap = ge(a, f.e0.margin), an = le(a, f.e0.minus_margin);
  const V dp = ge(d, f.diagonal.margin), dn = le(d, f.diagonal.minus_margin);
  const V cp = ge(c, f.e2.margin), cn = le(c, f.e2.minus_margin);
  const V gp = ge(g, f.e3.margin), gn = le(g, f.e3.minus_margin);
  const V hp = ge(h, f.e4.margin), hn = le(h, f.e4.minus_margin);
  const auto any = [](V p, V q, V r) { return _mm256_or_ps(p, _mm256_or_ps(q, r)); };
  const auto all = [](V p, V q, V r) { return vand(p, vand(q, r)); };
  // The second triangle sees the diagonal reversed: -d, whose signs swap.
  Settled s;
  s.in1 = _mm256_movemask_ps(_mm256_or_ps(all(ap, dp, cp), all(an, dn, cn)));
  s.out1 = _mm256_movemask_ps(vand(any(ap, dp, cp), any(an, dn, cn)));
  s.in2 = _mm256_movemask_ps(_mm256_or_ps(all(gp, hp, dn), all(gn, hn, dp)));
  s.out2 = _mm256_movemask_ps(vand(any(gp, hp, dn), any(gn, hn, dp)));
  return s;
}

// Four lanes' masks in double from their bits.
inline D lanes_of(int bits) {
  const __m256i bit = _mm256_setr_epi64x(1, 2, 4, 8);
  return _mm256_castsi256_pd(_mm256_cmpeq_epi64(_mm256_and_si256(_mm256_set1_epi64x(bits), bit), bit));
}

// hit_cell for four rays each settled through exactly one triangle (bits
// `in1` through the first) or neither.
inline D hit_settled(const Cell& cell, int in1, int in, D x, D y, D z, D t0) {
  const D first = lanes_of(in1);
  const D n0 = _mm256_blendv_pd(set1d(cell.normal2[0]), set1d(cell.normal1[0]), first);
  const D n1 = _mm256_blendv_pd(set1d(cell.normal2[1]), set1d(cell.normal1[1]), first);
  const D n2 = _mm256_blendv_pd(set1d(cell.normal2[2]), set1d(cell.normal1[2]), first);
  const D num = _mm256_blendv_pd(set1d(cell.num2), set1d(cell.num1), first);
  const D t = _mm256_div_pd(num, _mm256_fmadd_pd(n0, x, _mm256_fmadd_pd(n1, y, _mm256_mul_pd(n2, z))));
  const D lo = _mm256_max_pd(t0, set1d(cell.near)), hi = set1d(cell.far);
  const D ok = andd(lanes_of(in), andd(ged(t, lo), led(t, hi)));
  return _mm256_blendv_pd(set1d(__builtin_inf()), t, ok);
}

// The nearest hits of four rays (lanes `shift` to shift + 3 of the settled
// bits); `all_settled`: every one of the eight lanes is.
inline D hit_four(const Cell& cell, const Settled& s, bool all_settled, int shift, D x, D y, D z, D t0) {
  const int in1 = (s.in1 >> shift) & 15, in = ((s.in1 | s.in2) >> shift) & 15;
  if (all_settled) return in == 0 ? set1d(__builtin_inf()) : hit_settled(cell, in1, in, x, y, z, t0);
  if ((~(s.out1 & s.out2) >> shift & 15) == 0) return set1d(__builtin_inf());  // hit_cell's answer too
  const int in2 = (s.in2 >> shift) & 15;
  const bool settled = ((in1 | s.out1 >> shift) & (in2 | s.out2 >> shift) & 15) == 15 && (in1 & in2) == 0;
  if (settled) return hit_settled(cell, in1, in, x, y, z, t0);
  return hit_cell(cell, x, y, z, t0);
}

void cast_cell(const Rays& rays, const Cell& cell, const FloatCell& fcell, std::uint32_t first, std::uint32_t end,
               float t0, std::int32_t shape, const Best& best) {
  const D tmin = set1d(t0);
  for (std::uint32_t k = first; k < end; k += 8) {
    const V x = _mm256_loadu_ps(rays.x + k), y = _mm256_loadu_ps(rays.y + k), z = _mm256_loadu_ps(rays.z + k);
    const Settled s = settle(fcell, x, y, z);
    if ((s.out1 & s.out2) == 0xff) continue;  // no ray may cross: hit_cell gives +inf for all
    const bool all_settled = ((s.in1 | s.out1) & (s.in2 | s.out2)) == 0xff && (s.in1 & s.in2) == 0;
    const D lo = hit_four(cell, s, all_settled, 0, _mm256_cvtps_pd(_mm256_castps256_ps128(x)),
                          _mm256_cvtps_pd(_mm256_castps256_ps128(y)), _mm256_cvtps_pd(_mm256_castps256_ps128(z)), tmin);
    const D hi = hit_four(cell, s, all_settled, 4, _mm256_cvtps_pd(_mm256_extractf128_ps(x, 1)),
                          _mm256_cvtps_pd(_mm256_extractf128_ps(y, 1)), _mm256_cvtps_pd(_mm256_extractf128_ps(z, 1)),
                          tmin);
    const V cand = _mm256_set_m128(_mm256_cvtpd_ps(hi), _mm256_cvtpd_ps(lo));
    commit(best, k, valid_lanes(k, end), cand, shape);
  }
}

// --- analytic primitives -----------------------------------------------------

// A ray of the fan in a primitive's local frame, restarted at its closest
// approach to the centre so the solvers work with small numbers: local
// position o + s d at ray parameter t = shift + s.
struct LocalRays {
  V ox, oy, oz, dx, dy, dz, shift;
};

inline LocalRays to_local(const Primitive& p, V x, V y, V z) {
  const float* m = p.to_local;
  LocalRays r;
  r.dx = fmadd(set1(m[0]), x, fmadd(set1(m[1]), y, mul(set1(m[2]), z)));
  r.dy = fmadd(set1(m[3]), x, fmadd(set1(m[4]), y, mul(set1(m[5]), z)));
  r.dz = fmadd(set1(m[6]), x, fmadd(set1(m[7]), y, mul(set1(m[8]), z)));
  const V ox = set1(p.origin[0]), oy = set1(p.origin[1]), oz = set1(p.origin[2]);
  const V dd = fmadd(r.dx, r.dx, fmadd(r.dy, r.dy, mul(r.dz, r.dz)));
  r.shift = div(sub(_mm256_setzero_ps(), fmadd(ox, r.dx, fmadd(oy, r.dy, mul(oz, r.dz)))), dd);
  r.ox = fmadd(r.shift, r.dx, ox);
  r.oy = fmadd(r.shift, r.dy, oy);
  r.oz = fmadd(r.shift, r.dz, oz);
  return r;
}

inline V sqrt_clamped(V x) { return _mm256_sqrt_ps(vmax(x, _mm256_setzero_ps())); }

V hit_box(const Primitive& p, const LocalRays& r, V t0, float) {
  const V o[3] = {r.ox, r.oy, r.oz}, d[3] = {r.dx, r.dy, r.dz};
  const V zero = _mm256_setzero_ps(), inf = set1(kInf), minus_inf = set1(-kInf);
  V enter = minus_inf, exit = inf;
  for (int i = 0; i < 3; ++i) {
    const V h = set1(p.half[i]);
    const V inv = div(set1(1.0f), d[i]);
    const V a = mul(sub(sub(zero, h), o[i]), inv);
    const V b = mul(sub(h, o[i]), inv);
    V lo = vmin(a, b), hi = vmax(a, b);
    // A ray parallel to a slab is in it for every t, or never (on one of its
    // faces 0 * inf would give NaN). Rare: level rays and level boxes.
    const V parallel = _mm256_cmp_ps(d[i], zero, _CMP_EQ_OQ);
    if (!none(parallel)) {
      const V inside = le(_mm256_andnot_ps(set1(-0.0f), o[i]), h);
      lo = select(parallel, select(inside, minus_inf, inf), lo);
      hi = select(parallel, inf, hi);
    }
    enter = vmax(enter, lo);
    exit = vmin(exit, hi);
  }
  const V ok = le(enter, exit);
  V cand = set1(kInf);
  keep(add(enter, r.shift), ok, t0, cand);
  keep(add(exit, r.shift), ok, t0, cand);
  return cand;
}

V hit_sphere(const Primitive& p, const LocalRays& r, V t0, float) {
  const V rr = set1(p.half[0] * p.half[0]);
  const V disc = sub(rr, fmadd(r.ox, r.ox, fmadd(r.oy, r.oy, mul(r.oz, r.oz))));
  const V ok = ge(disc, _mm256_setzero_ps());
  const V s = sqrt_clamped(disc);
  V cand = set1(kInf);
  keep(sub(r.shift, s), ok, t0, cand);
  keep(add(r.shift, s), ok, t0, cand);
  return cand;
}

// Crossing with the disc of radius r in the plane z = zc.
inline void keep_cap(const LocalRays& r, float radius, float zc, float slack, V t0, V& cand) {
  const V s = div(sub(set1(zc), r.oz), r.dz);
  const V x = fmadd(s, r.dx, r.ox), y = fmadd(s, r.dy, r.oy);
  const float rim = radius + slack;
  keep(add(s, r.shift), le(fmadd(x, x, mul(y, y)), set1(rim * rim)), t0, cand);
}

V hit_cylinder(const Primitive& p, const LocalRays& r, V t0, float slack) {
  const float radius = p.half[0], hz = p.half[2];
  const V a = fmadd(r.dx, r.dx, mul(r.dy, r.dy));
  const V tc = div(sub(_mm256_setzero_ps(), fmadd(r.ox, r.dx, mul(r.oy, r.dy))), a);
  const V px = fmadd(tc, r.dx, r.ox), py = fmadd(tc, r.dy, r.oy);
  const V disc = sub(set1(radius * radius), fmadd(px, px, mul(py, py)));
  const V s = sqrt_clamped(div(disc, a));
  const V ok = ge(disc, _mm256_setzero_ps());
  const V rim = set1(hz + slack);
  V cand = set1(kInf);
  const V roots[2] = {sub(tc, s), add(tc, s)};
  for (const V t : roots) {
    const V z = fmadd(t, r.dz, r.oz);
    keep(add(t, r.shift), vand(ok, le(_mm256_andnot_ps(set1(-0.0f), z), rim)), t0, cand);
  }
  keep_cap(r, radius, -hz, slack, t0, cand);
  keep_cap(r, radius, hz, slack, t0, cand);
  return cand;
}

// Apex at z = +hz, base of radius r at z = -hz (as intersect_cone in
// sensors/raycaster.cpp).
V hit_cone(const Primitive& p, const LocalRays& r, V t0, float slack) {
  const float radius = p.half[0], hz = p.half[2];
  const float k = radius / (2.0f * hz);
  const V k2 = set1(k * k);
  const V w0 = sub(set1(hz), r.oz);
  const V a = sub(fmadd(r.dx, r.dx, mul(r.dy, r.dy)), mul(k2, mul(r.dz, r.dz)));
  const V b = fmadd(r.ox, r.dx, fmadd(r.oy, r.dy, mul(k2, mul(w0, r.dz))));
  const V c = sub(fmadd(r.ox, r.ox, mul(r.oy, r.oy)), mul(k2, mul(w0, w0)));
  const V disc = sub(mul(b, b), mul(a, c));
  const V ok = ge(disc, _mm256_setzero_ps());
  const V sign = _mm256_and_ps(b, set1(-0.0f));
  const V q = sub(_mm256_setzero_ps(), add(b, _mm256_or_ps(sqrt_clamped(disc), sign)));
  const V lo = set1(-hz - slack), hi = set1(hz + slack);
  V cand = set1(kInf);
  const V roots[2] = {div(q, a), div(c, q)};
  for (const V t : roots) {
    const V z = fmadd(t, r.dz, r.oz);
    keep(add(t, r.shift), vand(ok, vand(ge(z, lo), le(z, hi))), t0, cand);
  }
  keep_cap(r, radius, -hz, slack, t0, cand);
  return cand;
}

// Eight rays all stopped short of `near`, which no hit of the surface comes
// nearer than: none can take a hit from it.
inline bool stopped_short(const Best& best, std::uint32_t k, V near) {
  return none(ge(_mm256_loadu_ps(best.t + k), near));
}

template <V (*Hit)(const Primitive&, const LocalRays&, V, float)>
void cast_primitive_run(const Rays& rays, const Primitive& p, V near, std::uint32_t first, std::uint32_t end,
                        float t0, float rim_slack, const Best& best) {
  const V tmin = set1(t0);
  for (std::uint32_t k = first; k < end; k += 8) {
    if (stopped_short(best, k, near)) continue;
    const LocalRays r =
        to_local(p, _mm256_loadu_ps(rays.x + k), _mm256_loadu_ps(rays.y + k), _mm256_loadu_ps(rays.z + k));
    commit(best, k, valid_lanes(k, end), Hit(p, r, tmin, rim_slack), p.shape);
  }
}

}  // namespace

bool kernels_available() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
}

void reset(Best best, std::uint32_t count, float t, std::int32_t shape) {
  const V tv = set1(t);
  const __m256i sv = _mm256_set1_epi32(shape);
  for (std::uint32_t k = 0; k < count + 8; k += 8) {
    _mm256_storeu_ps(best.t + k, tv);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(best.shape + k), sv);
  }
}

void write_hits(const std::uint32_t* order, std::uint32_t count, Best best, std::int32_t no_shape, void* out) {
  auto* const bytes = static_cast<char*>(out);
  const __m256i none_v = _mm256_set1_epi32(no_shape);
  const V inf = set1(kInf);
  std::uint32_t k = 0;
  for (; k + 8 <= count; k += 8) {
    const __m256i shape = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(best.shape + k));
    const V t = select(_mm256_castsi256_ps(_mm256_cmpeq_epi32(shape, none_v)), inf, _mm256_loadu_ps(best.t + k));
    // (t, shape) pairs of rays 0 1 4 5 and 2 3 6 7, stored as 64-bit
    // integers (whose vector type may alias the RayHits).
    const __m256i lo = _mm256_castps_si256(_mm256_unpacklo_ps(t, _mm256_castsi256_ps(shape)));
    const __m256i hi = _mm256_castps_si256(_mm256_unpackhi_ps(t, _mm256_castsi256_ps(shape)));
    const __m128i pairs[4] = {_mm256_castsi256_si128(lo), _mm256_castsi256_si128(hi), _mm256_extracti128_si256(lo, 1),
                              _mm256_extracti128_si256(hi, 1)};
    const std::uint32_t* o = order + k;
    for (int i = 0; i < 4; ++i) {
      _mm_storel_epi64(reinterpret_cast<__m128i*>(bytes + 8 * std::size_t{o[2 * i]}), pairs[i]);
      _mm_storel_epi64(reinterpret_cast<__m128i*>(bytes + 8 * std::size_t{o[2 * i + 1]}),
                       _mm_unpackhi_epi64(pairs[i], pairs[i]));
    }
  }
  for (; k < count; ++k) {
    const float t = best.shape[k] == no_shape ? kInf : best.t[k];
    __builtin_memcpy(bytes + 8 * std::size_t{order[k]}, &t, 4);
    __builtin_memcpy(bytes + 8 * std::size_t{order[k]} + 4, best.shape + k, 4);
  }
}

void cast_planes(const Rays& rays, const Plane* planes, int count, float t0, Best best) {
  for (int i = 0; i < count; ++i) {
    const Plane& plane = planes[i];
    const D offset = set1d(plane.offset);
    // In double, like the cells: the ground is what a ray grazes most.
    const auto hit = [&](__m128 x, __m128 y, __m128 z) {
      return _mm256_cvtpd_ps(_mm256_div_pd(offset, dot3d(plane.normal, _mm256_cvtps_pd(x), _mm256_cvtps_pd(y),
                                                          _mm256_cvtps_pd(z))));
    };
    // A first look in float: a ray meets the plane short of its best hit so
    // far (t = offset / (n . d) <= best, rounded) only where s n . d, s the
    // sign of the offset, reaches |offset| / best. The float n . d is within
    // 1e-6 of the double one for unit vectors, and the products below are
    // rounded up by far more than their own rounding, so eight rays failing
    // it all would fail in double too.
    const bool screen = plane.offset != 0.0;
    const float sign = plane.offset > 0.0 ? 1.0f : -1.0f;
    const V n[3] = {set1(sign * static_cast<float>(plane.normal[0])), set1(sign * static_cast<float>(plane.normal[1])),
                    set1(sign * static_cast<float>(plane.normal[2]))};
    const V slack = set1(1e-6f), widen = set1(1.0f + 1e-5f);
    const V reach = set1(static_cast<float>(__builtin_fabs(plane.offset)) * (1.0f - 1e-6f));
    for (std::uint32_t k = 0; k < rays.size; k += 8) {
      const V x = _mm256_loadu_ps(rays.x + k), y = _mm256_loadu_ps(rays.y + k), z = _mm256_loadu_ps(rays.z + k);
      if (screen) {
        const V along = fmadd(n[0], x, fmadd(n[1], y, fmadd(n[2], z, slack)));
        if (none(ge(mul(mul(along, _mm256_loadu_ps(best.t + k)), widen), reach))) continue;
      }
      const V t = _mm256_set_m128(hit(_mm256_extractf128_ps(x, 1), _mm256_extractf128_ps(y, 1), _mm256_extractf128_ps(z, 1)),
                                  hit(_mm256_castps256_ps128(x), _mm256_castps256_ps128(y), _mm256_castps256_ps128(z)));
      V cand = set1(kInf);
      keep(t, _mm256_castsi256_ps(_mm256_set1_epi32(-1)), set1(t0), cand);
      commit<true>(best, k, valid_lanes(k, rays.size), cand, plane.shape);
    }
  }
}

namespace {

// The corners of one cell or triangle (float, sensor frame) and the ball
// about their mean that holds them.
struct Hull {
  float x[4], y[4], z[4];
  float centre[3];
  float rho;   // the ball's radius, padded for rounding
  float dist;  // of its centre from the origin
};

// Gathers vertices index[0, N) of (xf, yf, zf) into `hull`; false when its
// ball lies out of [t0, t1] or outside the fan's cone (no ray may meet it).
template <int N, class Index>
bool gather_hull(const Rays& rays, const float* xf, const float* yf, const float* zf, const Index* index, float t0,
                 float t1, Hull& hull) {
  static_assert(N >= 1 && N <= 4);
  for (int k = 0; k < N; ++k) {
    hull.x[k] = xf[index[k]];
    hull.y[k] = yf[index[k]];
    hull.z[k] = zf[index[k]];
  }
  constexpr float kInvN = 1.0f / N;
  float sum[3] = {hull.x[0], hull.y[0], hull.z[0]};
  for (int k = 1; k < N; ++k) {
    sum[0] += hull.x[k];
    sum[1] += hull.y[k];
    sum[2] += hull.z[k];
  }
  for (int a = 0; a < 3; ++a) hull.centre[a] = kInvN * sum[a];
  float rho2 = 0.0f;
  for (int k = 0; k < N; ++k) {
    const float ex = hull.x[k] - hull.centre[0], ey = hull.y[k] - hull.centre[1], ez = hull.z[k] - hull.centre[2];
    rho2 = max_f(rho2, ex * ex + ey * ey + ez * ez);
  }
  hull.rho = __builtin_sqrtf(rho2) * 1.00001f + 1e-6f;
  const float* c = hull.centre;
  hull.dist = __builtin_sqrtf(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  return !(hull.dist - hull.rho > t1 || hull.dist + hull.rho < t0 || outside_cone(rays, c, hull.rho));
}

// One heightfield cell (c, r) of the patch: culled, projected, and its rays tested.
void cast_terrain_cell(const Rays& rays, const TerrainPatch& patch, int c, int r, float t0, float t1,
                   const Best& best) {
  const double* const px = patch.x;
  const double* const py = patch.y;
  const double* const pz = patch.z;
  const int i00 = r * patch.cols + c, i10 = i00 + 1, i01 = i00 + patch.cols, i11 = i01 + 1;
  const int corners[4] = {i00, i10, i01, i11};
  Hull h;
  if (!gather_hull<4>(rays, patch.xf, patch.yf, patch.zf, corners, t0, t1, h)) return;
  const float* const hull[3] = {h.x, h.y, h.z};
  Rect rects[kFaces];
  const int n = hull_rects(rays, hull, 4, h.centre, h.rho, rects);
  if (n == 0) return;
  const double p00[3] = {px[i00], py[i00], pz[i00]}, p10[3] = {px[i10], py[i10], pz[i10]};
  const double p01[3] = {px[i01], py[i01], pz[i01]}, p11[3] = {px[i11], py[i11], pz[i11]};
  Cell cell;
  cell.e0 = make_edge(p00, p10);
  cell.diagonal = make_edge(p10, p01);
  cell.e2 = make_edge(p01, p00);
  cell.e3 = make_edge(p10, p11);
  cell.e4 = make_edge(p11, p01);
  triangle_plane(p00, p10, p01, cell.normal1, cell.num1);
  triangle_plane(p10, p11, p01, cell.normal2, cell.num2);
  cell.near = (h.dist - h.rho) * 0.9999 - 1e-5;
  cell.far = (h.dist + h.rho) * 1.0001 + 1e-5;
  const FloatCell fcell{float_edge(cell.e0), float_edge(cell.diagonal), float_edge(cell.e2),
                        float_edge(cell.e3), float_edge(cell.e4)};
  for (int i = 0; i < n; ++i) {
    for_each_run(rays, rects[i], [&](std::uint32_t first, std::uint32_t end) {
      cast_cell(rays, cell, fcell, first, end, t0, patch.shape, best);
    });
  }
}

}  // namespace

void cast_terrain(const Rays& rays, const TerrainPatch& patch, float t0, float t1, Best best) {
  // Blocks of cells are bounded first: most of the patch around the sensor
  // lies outside the fan's cone, and a block outside it (or out of range)
  // holds no cell a ray may meet.
  constexpr int kBlock = 4;
  for (int br = 0; br + 1 < patch.rows; br += kBlock) {
    for (int bc = 0; bc + 1 < patch.cols; bc += kBlock) {
      const int r_end = br + kBlock < patch.rows - 1 ? br + kBlock : patch.rows - 1;
      const int c_end = bc + kBlock < patch.cols - 1 ? bc + kBlock : patch.cols - 1;
      float lo[3] = {kInf, kInf, kInf}, hi[3] = {-kInf, -kInf, -kInf};
      for (int r = br; r <= r_end; ++r) {
        for (int c = bc; c <= c_end; ++c) {
          const int i = r * patch.cols + c;
          const float q[3] = {patch.xf[i], patch.yf[i], patch.zf[i]};
          for (int a = 0; a < 3; ++a) {
            lo[a] = min_f(lo[a], q[a]);
            hi[a] = max_f(hi[a], q[a]);
          }
        }
      }
      const float centre[3] = {0.5f * (lo[0] + hi[0]), 0.5f * (lo[1] + hi[1]), 0.5f * (lo[2] + hi[2])};
      const float half[3] = {0.5f * (hi[0] - lo[0]), 0.5f * (hi[1] - lo[1]), 0.5f * (hi[2] - lo[2])};
      const float radius = __builtin_sqrtf(half[0] * half[0] + half[1] * half[1] + half[2] * half[2]) * 1.0001f + 1e-5f;
      const float dist = __builtin_sqrtf(centre[0] * centre[0] + centre[1] * centre[1] + centre[2] * centre[2]);
      if (dist - radius > t1 || dist + radius < t0 || outside_cone(rays, centre, radius)) continue;
      for (int r = br; r < r_end; ++r) {
        for (int c = bc; c < c_end; ++c) cast_terrain_cell(rays, patch, c, r, t0, t1, best);
      }
    }
  }
}

namespace {

// --- mesh triangles ----------------------------------------------------------

// One triangle (a, b, c) as hit_cell sees each of a cell's two: its edge
// functions with their rounding bounds, in double and (as a first look) in
// float, its plane, and the distances bounding it.
struct Triangle {
  Edge ab, bc, ca;
  double normal[3], num;
  double near, far;
};

struct FloatTriangle {
  FloatEdge ab, bc, ca;
};

// hit_cell for one triangle: the nearest hit of four rays, +inf where none.
inline D hit_triangle(const Triangle& tri, D x, D y, D z, D t0) {
  const D a = dot3d(tri.ab.n, x, y, z), b = dot3d(tri.bc.n, x, y, z), c = dot3d(tri.ca.n, x, y, z);
  const D in = one_sign(a, set1d(tri.ab.eps), b, set1d(tri.bc.eps), c, set1d(tri.ca.eps));
  const D inf = set1d(__builtin_inf());
  if (_mm256_movemask_pd(in) == 0) return inf;
  const D t = _mm256_div_pd(set1d(tri.num), dot3d(tri.normal, x, y, z));
  const D ok = andd(in, andd(ged(t, _mm256_max_pd(t0, set1d(tri.near))), led(t, set1d(tri.far))));
  return _mm256_blendv_pd(inf, t, ok);
}

// hit_triangle for four rays whose float edge functions settled them: `in`
// the lane bits of those through the triangle (the others are not).
inline D hit_triangle_settled(const Triangle& tri, int in, D x, D y, D z, D t0) {
  const D inf = set1d(__builtin_inf());
  if (in == 0) return inf;
  const D t = _mm256_div_pd(set1d(tri.num), dot3d(tri.normal, x, y, z));
  const D ok = andd(lanes_of(in), andd(ged(t, _mm256_max_pd(t0, set1d(tri.near))), led(t, set1d(tri.far))));
  return _mm256_blendv_pd(inf, t, ok);
}

// The rays of slots [first, end) against one triangle: the float edge
// functions settle most rays past the margin (see FloatEdge), the rest get
// hit_triangle's double test, so every answer is hit_triangle's.
void cast_triangle_run(const Rays& rays, const Triangle& tri, const FloatTriangle& ftri, std::uint32_t first,
                       std::uint32_t end, float t0, std::int32_t shape, const Best& best) {
  const D tmin = set1d(t0);
  for (std::uint32_t k = first; k < end; k += 8) {
    const V x = _mm256_loadu_ps(rays.x + k), y = _mm256_loadu_ps(rays.y + k), z = _mm256_loadu_ps(rays.z + k);
    const V a = dot3(ftri.ab.n, x, y, z), b = dot3(ftri.bc.n, x, y, z), c = dot3(ftri.ca.n, x, y, z);
    const V ap = ge(a, ftri.ab.margin), an = le(a, ftri.ab.minus_margin);
    const V bp = ge(b, ftri.bc.margin), bn = le(b, ftri.bc.minus_margin);
    const V cp = ge(c, ftri.ca.margin), cn = le(c, ftri.ca.minus_margin);
    const int in = _mm256_movemask_ps(_mm256_or_ps(vand(ap, vand(bp, cp)), vand(an, vand(bn, cn))));
    const int out = _mm256_movemask_ps(
        vand(_mm256_or_ps(ap, _mm256_or_ps(bp, cp)), _mm256_or_ps(an, _mm256_or_ps(bn, cn))));
    if (out == 0xff) continue;
    const auto four = [&](int shift, D xd, D yd, D zd) {
      if (((in | out) >> shift & 15) == 15) return hit_triangle_settled(tri, in >> shift & 15, xd, yd, zd, tmin);
      return hit_triangle(tri, xd, yd, zd, tmin);
    };
    const D lo = four(0, _mm256_cvtps_pd(_mm256_castps256_ps128(x)), _mm256_cvtps_pd(_mm256_castps256_ps128(y)),
                      _mm256_cvtps_pd(_mm256_castps256_ps128(z)));
    const D hi = four(4, _mm256_cvtps_pd(_mm256_extractf128_ps(x, 1)), _mm256_cvtps_pd(_mm256_extractf128_ps(y, 1)),
                      _mm256_cvtps_pd(_mm256_extractf128_ps(z, 1)));
    commit(best, k, valid_lanes(k, end), _mm256_set_m128(_mm256_cvtpd_ps(hi), _mm256_cvtpd_ps(lo)), shape);
  }
}

}  // namespace

void cast_triangles(const Rays& rays, const TriangleSoup& soup, float t0, float t1, Best best) {
  for (std::uint32_t i = 0; i < soup.count; ++i) {
    const std::uint32_t* v = soup.triangles + 3 * static_cast<std::size_t>(i);
    Hull h;
    if (!gather_hull<3>(rays, soup.xf, soup.yf, soup.zf, v, t0, t1, h)) continue;
    const double a[3] = {soup.x[v[0]], soup.y[v[0]], soup.z[v[0]]};
    const double b[3] = {soup.x[v[1]], soup.y[v[1]], soup.z[v[1]]};
    const double c[3] = {soup.x[v[2]], soup.y[v[2]], soup.z[v[2]]};
    Triangle tri;
    triangle_plane(a, b, c, tri.normal, tri.num);
    if (soup.facing) {
      // Facing away: the origin on the inner side of its plane, num = n . a
      // of the sign of the facing, and not within 1e-9 rad of edge-on.
      const double* n = tri.normal;
      const double n2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2], a2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
      if (soup.facing[i] * tri.num > 0.0 && tri.num * tri.num > 1e-18 * n2 * a2) continue;
    }
    const float* const hull[3] = {h.x, h.y, h.z};
    Rect rects[kFaces];
    const int n = hull_rects(rays, hull, 3, h.centre, h.rho, rects);
    if (n == 0) continue;
    tri.ab = make_edge(a, b);
    tri.bc = make_edge(b, c);
    tri.ca = make_edge(c, a);
    tri.near = (h.dist - h.rho) * 0.9999 - 1e-5;
    tri.far = (h.dist + h.rho) * 1.0001 + 1e-5;
    const FloatTriangle ftri{float_edge(tri.ab), float_edge(tri.bc), float_edge(tri.ca)};
    for (int r = 0; r < n; ++r) {
      for_each_run(rays, rects[r], [&](std::uint32_t first, std::uint32_t end) {
        cast_triangle_run(rays, tri, ftri, first, end, t0, soup.shape, best);
      });
    }
  }
}

namespace {

// Calls test(first, end) for the runs of slots whose rays may meet the
// primitive. A long shape (a row's canopy, a fence) is projected in pieces
// along its longest axis, each about as long as the shape is wide, so its
// rectangles follow it across the view instead of one rectangle around all
// of it, and pieces out of range or out of the fan's cone are left out; a
// ray in the rectangles of two pieces is tested twice, to the same answer.
template <class Test>
void for_each_primitive_run(const Rays& rays, const Primitive& p, float t0, float t1, Test&& test) {
  int axis = 0;
  for (int i = 1; i < 3; ++i) axis = p.half[i] > p.half[axis] ? i : axis;
  const int b = (axis + 1) % 3, c = (axis + 2) % 3;
  const float width = max_f(max_f(p.half[b], p.half[c]), 0.5f);
  const float length = p.half[axis];
  const int pieces = p.kind == Kind::sphere || length < 2.0f ? 1 : static_cast<int>(__builtin_ceilf(length / width));
  const float piece = length / static_cast<float>(pieces);
  const float piece_radius =
      pieces == 1 ? p.radius
                  : __builtin_sqrtf(piece * piece + p.half[b] * p.half[b] + p.half[c] * p.half[c]) * 1.000001f + 1e-6f;
  const float* const u = p.to_local + 3 * axis;  // the long axis in the sensor frame
  for (int j = 0; j < pieces; ++j) {
    const float s = pieces == 1 ? 0.0f : -length + (2.0f * static_cast<float>(j) + 1.0f) * piece;
    const float centre[3] = {p.center[0] + s * u[0], p.center[1] + s * u[1], p.center[2] + s * u[2]};
    if (pieces > 1) {
      const float dist = __builtin_sqrtf(centre[0] * centre[0] + centre[1] * centre[1] + centre[2] * centre[2]);
      if (dist - piece_radius > t1 || dist + piece_radius < t0 || outside_cone(rays, centre, piece_radius)) continue;
    }
    // The piece's box corners: its centre plus or minus each half extent
    // along the local axes (rows of to_local, in the sensor frame).
    float corner_x[8], corner_y[8], corner_z[8];
    for (int k = 0; k < 8; ++k) {
      float q[3] = {centre[0], centre[1], centre[2]};
      for (int a = 0; a < 3; ++a) {
        const float extent = a == axis ? piece : p.half[a];
        const float h = (k >> a) & 1 ? extent : -extent;
        for (int i = 0; i < 3; ++i) q[i] += h * p.to_local[3 * a + i];
      }
      corner_x[k] = q[0];
      corner_y[k] = q[1];
      corner_z[k] = q[2];
    }
    const float* const hull[3] = {corner_x, corner_y, corner_z};
    Rect rects[kFaces];
    const int n = hull_rects(rays, hull, 8, centre, piece_radius, rects);
    for (int r = 0; r < n; ++r) for_each_run(rays, rects[r], test);
  }
}

}  // namespace

void cast_primitives(const Rays& rays, const Primitive* primitives, int count, float t0, float t1,
                     Best best) {
  for (int i = 0; i < count; ++i) {
    const Primitive& p = primitives[i];
    const float dist = __builtin_sqrtf(p.center[0] * p.center[0] + p.center[1] * p.center[1] + p.center[2] * p.center[2]);
    if (dist - p.radius > t1 || dist + p.radius < t0 || outside_cone(rays, p.center, p.radius)) continue;
    const float rim_slack = kRimRounding * (dist + p.radius);
    // Every hit lies in the bounding ball (the solvers' rounding, some 1e-6
    // of the distances, is far inside this margin), so rays already stopped
    // nearer are past testing. Not for a cone, whose quadratic may put a
    // nearly degenerate root anywhere along the ray.
    const V near = set1(p.kind == Kind::cone ? -kInf : (dist - p.radius) * 0.999f - 1e-3f);
    for_each_primitive_run(rays, p, t0, t1, [&](std::uint32_t first, std::uint32_t end) {
      switch (p.kind) {
        case Kind::cuboid:
          cast_primitive_run<&hit_box>(rays, p, near, first, end, t0, rim_slack, best);
          break;
        case Kind::cylinder:
          cast_primitive_run<&hit_cylinder>(rays, p, near, first, end, t0, rim_slack, best);
          break;
        case Kind::cone:
          cast_primitive_run<&hit_cone>(rays, p, near, first, end, t0, rim_slack, best);
          break;
        case Kind::sphere:
          cast_primitive_run<&hit_sphere>(rays, p, near, first, end, t0, rim_slack, best);
          break;
      }
    });
  }
}

#else  // no AVX2: the fan is never used (RayCaster casts every ray through Embree)

bool kernels_available() { return false; }
void reset(Best, std::uint32_t, float, std::int32_t) {}
void write_hits(const std::uint32_t*, std::uint32_t, Best, std::int32_t, void*) {}
void cast_planes(const Rays&, const Plane*, int, float, Best) {}
void cast_terrain(const Rays&, const TerrainPatch&, float, float, Best) {}
void cast_triangles(const Rays&, const TriangleSoup&, float, float, Best) {}
void cast_primitives(const Rays&, const Primitive*, int, float, float, Best) {}

#endif

}  // namespace campo::fan
