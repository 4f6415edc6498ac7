#include "physics/clearance.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include <btBulletCollisionCommon.h>
#include <BulletCollision/CollisionShapes/btTriangleCallback.h>
#include <BulletCollision/CollisionShapes/btTriangleShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>

namespace campo {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// The search radius starts here at the first query, and never below it.
constexpr double kMinSearch_m = 0.25;

// Euclidean distance between two axis-aligned boxes (0 when they overlap): a
// lower bound of the distance between anything inside them.
double box_distance(const btVector3& a_min, const btVector3& a_max, const btVector3& b_min, const btVector3& b_max) {
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double gap = std::max({0.0, static_cast<double>(a_min[i] - b_max[i]), static_cast<double>(b_min[i] - a_max[i])});
    sum += gap * gap;
  }
  return std::sqrt(sum);
}

// True when the box [lo, hi] contains [inner_lo, inner_hi] along the axes `axes`.
bool covers(const btVector3& lo, const btVector3& hi, const btVector3& inner_lo, const btVector3& inner_hi, int axes) {
  for (int i = 0; i < axes; ++i) {
    if (lo[i] > inner_lo[i] || hi[i] < inner_hi[i]) return false;
  }
  return true;
}

// Heightfield triangles near a vehicle body: gathered with the distance of
// their box from the body's box, then measured nearest box first, so that
// the first few exact distances prune the rest.
struct TriangleDistances final : btTriangleCallback {
  using Candidate = TriangleCandidate;
  const btConvexShape* body = nullptr;
  btTransform body_pose;        // in the heightfield's frame
  btVector3 body_min, body_max; // the body's box, heightfield frame
  double best = kInfinity;
  btVector3 best_point{0, 0, 0};  // of the nearest triangle, heightfield frame
  double cutoff = kInfinity;
  // Terrain is seen from above only; a mesh's triangles from either side.
  bool two_sided = false;
  std::vector<Candidate>* candidates = nullptr;  // scratch, reused
  void processTriangle(btVector3* v, int, int) override {
    btVector3 lo = v[0], hi = v[0];
    lo.setMin(v[1]);
    lo.setMin(v[2]);
    hi.setMax(v[1]);
    hi.setMax(v[2]);
    double bound = box_distance(lo, hi, body_min, body_max);
    if (bound >= std::min(best, cutoff)) return;
    // The body lies above the triangle's plane at least as far as its
    // lowest point: a bound that is tight for terrain under the body.
    btVector3 normal = (v[1] - v[0]).cross(v[2] - v[0]);
    if (normal.z() < 0) normal = -normal;
    if (normal.length2() > 0) {
      normal.normalize();
      const btVector3 lowest = body_pose * body->localGetSupportingVertex(body_pose.getBasis().transpose() * -normal);
      bound = std::max(bound, static_cast<double>(normal.dot(lowest - v[0])));
      if (two_sided) {  // a body wholly below the plane is at least as far as its highest point
        const btVector3 highest = body_pose * body->localGetSupportingVertex(body_pose.getBasis().transpose() * normal);
        bound = std::max(bound, static_cast<double>(normal.dot(v[0] - highest)));
      }
    }
    if (bound < std::min(best, cutoff)) candidates->push_back({bound, {v[0], v[1], v[2]}});
  }
  void measure() {
    if (two_sided) return measure_nearest_first();
    std::sort(candidates->begin(), candidates->end(),
              [](const Candidate& a, const Candidate& b) { return a.bound_m < b.bound_m; });
    for (const Candidate& c : *candidates) {
      if (c.bound_m >= std::min(best, cutoff)) break;
      measure(c);
    }
    candidates->clear();
  }
  void measure(const Candidate& c) {
    btTriangleShape triangle(c.v[0], c.v[1], c.v[2]);
    triangle.setMargin(0.0);
    btVector3 point;
    const double d = signed_distance(*body, body_pose, triangle, btTransform::getIdentity(), &point);
    if (d < best) {
      best = d;
      best_point = point;
    }
  }
  // A finely tessellated mesh puts thousands of slivers near a body, of which
  // a few are measured: a heap yields them nearest bound first without
  // sorting them all.
  void measure_nearest_first() {
    const auto farther = [](const Candidate& a, const Candidate& b) { return a.bound_m > b.bound_m; };
    std::make_heap(candidates->begin(), candidates->end(), farther);
    for (auto end = candidates->end(); end != candidates->begin(); --end) {
      if (candidates->front().bound_m >= std::min(best, cutoff)) break;
      std::pop_heap(candidates->begin(), end, farther);
      measure(*(end - 1));
    }
    candidates->clear();
  }
};

// Counts the triangles a ray crosses (Moller-Trumbore), for the parity test
// of a point inside a closed mesh.
struct RayCrossings final : btTriangleCallback {
  btVector3 origin, direction;
  double length = 0.0;
  int crossings = 0;
  void processTriangle(btVector3* v, int, int) override {
    const btVector3 e1 = v[1] - v[0], e2 = v[2] - v[0];
    const btVector3 p = direction.cross(e2);
    const double det = e1.dot(p);
    if (det == 0.0) return;  // parallel to the triangle
    const btVector3 s = origin - v[0];
    const double u = s.dot(p) / det;
    if (u < 0.0 || u > 1.0) return;
    const btVector3 q = s.cross(e1);
    const double w = direction.dot(q) / det;
    if (w < 0.0 || u + w > 1.0) return;
    const double t = e2.dot(q) / det;
    if (t > 0.0 && t <= length) ++crossings;
  }
};

}  // namespace

double signed_distance(const btConvexShape& a, const btTransform& pose_a, const btConvexShape& b,
                       const btTransform& pose_b, btVector3* point_on_b) {
  btVoronoiSimplexSolver simplex;
  btGjkEpaPenetrationDepthSolver epa;
  btGjkPairDetector gjk(&a, &b, &simplex, &epa);
  btGjkPairDetector::ClosestPointInput input;
  input.m_transformA = pose_a;
  input.m_transformB = pose_b;
  btPointCollector result;
  gjk.getClosestPoints(input, result, nullptr);
  // No result only when EPA cannot resolve a degenerate overlap: touching,
  // somewhere about b's support point toward a.
  if (point_on_b) {
    *point_on_b = result.m_hasResult
                      ? result.m_pointInWorld
                      : pose_b * b.localGetSupportingVertex(pose_b.getBasis().transpose() *
                                                           (pose_a.getOrigin() - pose_b.getOrigin()));
  }
  return result.m_hasResult ? static_cast<double>(result.m_distance) : 0.0;
}

ClearanceQuery::ClearanceQuery()
    : statics_min_(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT),
      statics_max_(-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT) {}

ClearanceQuery::~ClearanceQuery() { static_tree_.clear(); }

void ClearanceQuery::add_static_obstacle(const btConvexShape& shape, const btTransform& pose, int id) {
  btVector3 lo, hi;
  shape.getAabb(pose, lo, hi);
  statics_min_.setMin(lo);
  statics_max_.setMax(hi);
  // The tree keeps an index, not a pointer: statics_ may still grow.
  static_tree_.insert(btDbvtVolume::FromMM(lo, hi), reinterpret_cast<void*>(statics_.size()));
  statics_.push_back({&shape, pose, id});
}

void ClearanceQuery::add_static_compound(const btCollisionObject& body, std::vector<int> children) {
  compounds_.push_back({&body, std::move(children)});
}

void ClearanceQuery::add_moving_obstacle(const btCollisionObject& body, int id) { moving_.push_back({&body, id}); }

void ClearanceQuery::add_ground(const btCollisionObject& body, const HeightGrid* grid) {
  Ground ground{&body, grid ? HeightBlocks(*grid) : HeightBlocks()};
  ground_.push_back(std::move(ground));
}

void ClearanceQuery::add_static_mesh(const btCollisionObject& body, int id, bool closed) {
  StaticMesh mesh{&body, id, closed, {}, {}};
  body.getCollisionShape()->getAabb(body.getWorldTransform(), mesh.lo, mesh.hi);
  meshes_.push_back(mesh);
}

void ClearanceQuery::find_vehicle(const btCollisionWorld& world, std::size_t vehicle) {
  if (searches_.size() <= vehicle) searches_.resize(vehicle + 1);
  search_ = &searches_[vehicle];
  vehicle_ = &search_->parts;
  const btCollisionObjectArray& objects = world.getCollisionObjectArray();
  if (objects.size() == search_->objects_seen) return;
  search_->objects_seen = objects.size();
  search_->parts.clear();
  search_->others.clear();
  for (int i = 0; i < objects.size(); ++i) {
    const int tag = objects[i]->getUserIndex();
    if (!is_vehicle_tag(tag)) continue;
    if (vehicle_of_tag(tag) == vehicle) {
      btVector3 centre;
      btScalar radius;
      objects[i]->getCollisionShape()->getBoundingSphere(centre, radius);
      search_->parts.push_back({objects[i], !is_wheel_tag(tag), centre.length() + radius});
    } else {
      search_->others.push_back({objects[i], vehicle_tag(vehicle_of_tag(tag), false)});
    }
  }
}

Clearance ClearanceQuery::measure(const btCollisionWorld& world, std::size_t vehicle, double obstacle_cutoff_m,
                                  double ground_cutoff_m, bool other_vehicles) {
  find_vehicle(world, vehicle);
  Clearance out;
  if (vehicle_->empty()) return out;
  ContactSeen seen;
  out.contact = in_contact(world, seen);
  nearest_moving(obstacle_cutoff_m, other_vehicles, out);
  rotations_.clear();
  for (const VehiclePart& part : *vehicle_) rotations_.push_back(part.body->getWorldTransform().getRotation());
  // Static obstacles and the ground do not move: while the vehicle has not
  // moved far enough since their last exact answer to come within the
  // cutoff, it cannot have. Each is measured a little beyond its cutoff, so
  // that the answer bounds the next steps.
  const double static_travel = travel_since(search_->static_floor);
  if (search_->static_floor.floor_m - static_travel < obstacle_cutoff_m) {
    Clearance statics;
    const double reach = obstacle_cutoff_m + kSlack_m;
    if (!recall(search_->static_memo, reach, statics.obstacle_m, statics.obstacle)) {
      // The obstacle that was nearest is now at most as far as it was plus the travel since
      // (above, by GJK's relative tolerance of 1e-6 at most, with room to spare): an obstacle
      // whose box lies farther cannot be the nearest, and is not measured.
      double within = kInfinity;
      if (reuse_ && search_->static_found) {
        const double upper = search_->static_floor.floor_m + static_travel;
        within = upper + 1e-3 * (1.0 + upper);
      }
      nearest_static(reach, statics, within);
      memorize(search_->static_memo, reach, statics.obstacle_m, statics.obstacle);
    }
    search_->static_found = std::isfinite(statics.obstacle_m) && statics.obstacle_m > 0.0;
    remember(search_->static_floor, std::min(statics.obstacle_m, reach));
    if (statics.obstacle_m < out.obstacle_m) {
      out.obstacle_m = statics.obstacle_m;
      out.obstacle = statics.obstacle;
    }
  }
  if (out.obstacle_m >= obstacle_cutoff_m) {
    out.obstacle_m = kInfinity;
    out.obstacle = -1;
  }
  if (search_->ground_floor.floor_m - travel_since(search_->ground_floor) < ground_cutoff_m) {
    const double reach = ground_cutoff_m + kSlack_m;
    int unused = -1;
    if (!recall(search_->ground_memo, reach, out.ground_m, unused)) {
      nearest_ground(reach, out);
      memorize(search_->ground_memo, reach, out.ground_m, -1);
    }
    remember(search_->ground_floor, std::min(out.ground_m, reach));
  }
  if (out.ground_m >= ground_cutoff_m) out.ground_m = kInfinity;
  if (out.touching()) out.touch = touch(out, seen);
  return out;
}

Touch ClearanceQuery::touch(const Clearance& c, const ContactSeen& seen) {
  // An overlap now is what the vehicle is in; a contact Bullet found before
  // the step's motion names what it was pressed against.
  if (c.obstacle_m <= 0.0 || c.ground_m <= 0.0) {
    return c.obstacle_m <= c.ground_m ? touch_obstacle(c.obstacle) : touch_ground(nullptr);
  }
  for (const Ground& g : ground_) {
    if (g.body == seen.other) return touch_ground(&g);
  }
  const std::vector<MovingObstacle>* lists[] = {&moving_, &search_->others};
  for (const std::vector<MovingObstacle>* list : lists) {
    for (const MovingObstacle& m : *list) {
      if (m.body == seen.other) return touch_obstacle(m.id);
    }
  }
  for (const StaticMesh& mesh : meshes_) {
    if (mesh.body == seen.other) return touch_obstacle(mesh.id);
  }
  for (const StaticCompound& compound : compounds_) {
    if (compound.body != seen.other) continue;
    if (seen.child >= 0 && static_cast<std::size_t>(seen.child) < compound.children.size()) {
      return touch_obstacle(compound.children[static_cast<std::size_t>(seen.child)]);
    }
  }
  // A contact with a body the query does not know as a child: the nearest static obstacle.
  Clearance nearest;
  nearest_static(kInfinity, nearest);
  return touch_obstacle(nearest.obstacle);
}

Touch ClearanceQuery::touch_obstacle(int id) const {
  const btConvexShape* shape = nullptr;
  btTransform pose = btTransform::getIdentity();
  for (const StaticObstacle& o : statics_) {
    if (o.id == id) {
      shape = o.shape;
      pose = o.pose;
    }
  }
  Touch t;
  t.body = id;
  double best = kInfinity;
  const auto nearest_on = [&](const btConvexShape& other, const btTransform& other_pose) {
    for (const VehiclePart& part : *vehicle_) {
      btVector3 point;
      const double d = signed_distance(*static_cast<const btConvexShape*>(part.body->getCollisionShape()),
                                       part.body->getWorldTransform(), other, other_pose, &point);
      if (d < best) {
        best = d;
        t.point_m = Eigen::Vector3d(point.x(), point.y(), point.z());
      }
    }
  };
  // Another vehicle is all its bodies (a rover's chassis and wheels).
  for (const MovingObstacle& m : search_->others) {
    if (m.id == id) nearest_on(*static_cast<const btConvexShape*>(m.body->getCollisionShape()), m.body->getWorldTransform());
  }
  for (const MovingObstacle& m : moving_) {
    if (m.id == id) {
      shape = static_cast<const btConvexShape*>(m.body->getCollisionShape());
      pose = m.body->getWorldTransform();
    }
  }
  if (shape) nearest_on(*shape, pose);
  for (const StaticMesh& mesh : meshes_) {
    if (mesh.id != id) continue;
    for (const VehiclePart& part : *vehicle_) {
      btVector3 point;
      const double d = const_cast<ClearanceQuery*>(this)->mesh_distance(mesh, part, kInfinity, &point);
      if (d < best) {
        best = d;
        t.point_m = Eigen::Vector3d(point.x(), point.y(), point.z());
      }
    }
  }
  return t;
}

Touch ClearanceQuery::touch_ground(const Ground* only) {
  Touch t;
  t.ground = true;
  double best = kInfinity;
  bool found = false;
  for (const Ground& g : ground_) {
    if (only && &g != only) continue;
    for (const VehiclePart& part : *vehicle_) {
      if (!part.ground_counts) continue;
      btVector3 point;
      const double d = ground_distance(g, part, kInfinity, &point);
      if (d < best || !found) {
        found = true;
        best = d;
        t.body = g.body->getUserIndex();
        t.point_m = Eigen::Vector3d(point.x(), point.y(), point.z());
      }
    }
  }
  return t;
}

const ClearanceQuery::VehiclePart* ClearanceQuery::part_of(const btCollisionObject* object) const {
  for (const VehiclePart& part : *vehicle_) {
    if (part.body == object) return &part;
  }
  return nullptr;
}

bool ClearanceQuery::in_contact(const btCollisionWorld& world, ContactSeen& seen) const {
  // Bullet's manifold accessors are not const; reading them changes nothing.
  btDispatcher* dispatcher = const_cast<btCollisionWorld&>(world).getDispatcher();
  for (int i = 0; i < dispatcher->getNumManifolds(); ++i) {
    const btPersistentManifold* m = dispatcher->getManifoldByIndexInternal(i);
    const VehiclePart* mine = part_of(m->getBody0());
    const btCollisionObject* other = m->getBody1();
    bool other_first = false;
    if (!mine) {
      mine = part_of(other);
      other = m->getBody0();
      other_first = true;
    }
    if (!mine || part_of(other)) continue;
    const bool ground = std::any_of(ground_.begin(), ground_.end(), [other](const Ground& g) { return g.body == other; });
    if (ground && !mine->ground_counts) continue;  // a wheel on the ground
    for (int c = 0; c < m->getNumContacts(); ++c) {
      const btManifoldPoint& point = m->getContactPoint(c);
      if (point.getDistance() <= Clearance::kContact_m) {
        // A compound's manifold point carries the child's index on its side.
        seen = {other, other_first ? point.m_index0 : point.m_index1};
        return true;
      }
    }
  }
  return false;
}

void ClearanceQuery::remember(Floor& floor, double floor_m) const {
  floor.floor_m = floor_m;
  floor.poses.clear();
  for (const VehiclePart& part : *vehicle_) floor.poses.push_back(part.body->getWorldTransform());
  floor.rotations = rotations_;
}

double ClearanceQuery::travel_since(const Floor& floor) const {
  if (floor.poses.size() != vehicle_->size()) return kInfinity;
  // No point of a body moves farther than its origin's displacement plus the
  // arc its farthest point turns through. (The rotations then and now are
  // kept, not found again from the poses: the same numbers, fewer instructions.)
  double travel = 0.0;
  for (std::size_t i = 0; i < vehicle_->size(); ++i) {
    const btTransform& now = (*vehicle_)[i].body->getWorldTransform();
    const btTransform& then = floor.poses[i];
    const btScalar angle = (rotations_[i] * floor.rotations[i].inverse()).getAngleShortestPath();
    travel = std::max(travel, static_cast<double>((now.getOrigin() - then.getOrigin()).length() +
                                                  (*vehicle_)[i].reach_m * angle));
  }
  return travel;
}

namespace {

// Bit for bit: -0 and +0, or two NaNs, are not the same pose to GJK.
bool same_pose(const btTransform& a, const btTransform& b) {
  const auto same = [](const btVector3& u, const btVector3& v) {
    for (int k = 0; k < 3; ++k) {
      if (std::bit_cast<std::uint64_t>(static_cast<double>(u[k])) != std::bit_cast<std::uint64_t>(static_cast<double>(v[k]))) {
        return false;
      }
    }
    return true;
  };
  for (int r = 0; r < 3; ++r) {
    if (!same(a.getBasis()[r], b.getBasis()[r])) return false;
  }
  return same(a.getOrigin(), b.getOrigin());
}

}  // namespace

// A search of things that do not move returns the least of the GJK
// distances of the pairs it measures; which pairs it measures depends on
// where its box starts (the hint) and on the cutoff, but not the least one's
// distance when apart: a pair left out is one whose lower bound (the boxes'
// distance, a triangle's plane) already reaches a distance measured
// (tests/physics/clearance_reuse_test.cpp compares the ways over random poses).
bool ClearanceQuery::recall(const Memo& memo, double reach_m, double& distance_m, int& id) const {
  if (!reuse_ || memo.poses.size() != vehicle_->size()) return false;
  // Found: the answer below any cutoff. Not found: none below a reach up to the memo's.
  if (!std::isfinite(memo.distance_m) && reach_m > memo.reach_m) return false;
  // An overlap is not reused: the search stops at the first overlapping pair
  // it measures (every other's box is as near), which depends on its box.
  if (memo.distance_m <= 0.0) return false;
  for (std::size_t i = 0; i < vehicle_->size(); ++i) {
    if (!same_pose((*vehicle_)[i].body->getWorldTransform(), memo.poses[i])) return false;
  }
  const bool below = memo.distance_m < reach_m;
  distance_m = below ? memo.distance_m : kInfinity;
  id = below ? memo.id : -1;
  return true;
}

void ClearanceQuery::memorize(Memo& memo, double reach_m, double distance_m, int id) const {
  if (!reuse_) return;
  memo.reach_m = reach_m;
  memo.distance_m = distance_m;
  memo.id = id;
  memo.poses.clear();
  for (const VehiclePart& part : *vehicle_) memo.poses.push_back(part.body->getWorldTransform());
}

void ClearanceQuery::vehicle_box(btVector3& lo, btVector3& hi) const {
  lo.setValue(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
  hi = -lo;
  for (const VehiclePart& part : *vehicle_) {
    btVector3 a, b;
    part.body->getCollisionShape()->getAabb(part.body->getWorldTransform(), a, b);
    lo.setMin(a);
    hi.setMax(b);
  }
}

void ClearanceQuery::measure_obstacle(const btVector3& lo, const btVector3& hi, const btConvexShape& shape,
                                      const btTransform& pose, int id, double bound, Clearance& out) const {
  btVector3 a, b;
  shape.getAabb(pose, a, b);
  if (box_distance(lo, hi, a, b) >= std::min(out.obstacle_m, bound)) return;
  for (const VehiclePart& part : *vehicle_) {
    const auto* mine = static_cast<const btConvexShape*>(part.body->getCollisionShape());
    if (vehicle_->size() > 1) {  // each part's own box first (a rover's wheels)
      btVector3 part_lo, part_hi;
      mine->getAabb(part.body->getWorldTransform(), part_lo, part_hi);
      if (box_distance(part_lo, part_hi, a, b) >= std::min(out.obstacle_m, bound)) continue;
    }
    const double d = signed_distance(*mine, part.body->getWorldTransform(), shape, pose);
    if (d < out.obstacle_m) {
      out.obstacle_m = d;
      out.obstacle = id;
    }
  }
}

// Moving obstacles (and the other vehicles' bodies) are few: each is measured exactly (within the cutoff).
void ClearanceQuery::nearest_moving(double cutoff_m, bool other_vehicles, Clearance& out) const {
  btVector3 lo, hi;
  vehicle_box(lo, hi);
  const std::vector<MovingObstacle>* lists[] = {&moving_, other_vehicles ? &search_->others : nullptr};
  for (const std::vector<MovingObstacle>* list : lists) {
    if (!list) continue;
    for (const MovingObstacle& m : *list) {
      measure_obstacle(lo, hi, *static_cast<const btConvexShape*>(m.body->getCollisionShape()),
                       m.body->getWorldTransform(), m.id, cutoff_m, out);
    }
  }
}

// Searches a box around the vehicle that grows until the nearest static
// obstacle found lies within it: everything outside the box is farther than
// its margin, so the answer is exact. It starts from the last answer, which
// moves little from one step to the next.
void ClearanceQuery::nearest_static(double cutoff_m, Clearance& out, double within_m) {
  btVector3 lo, hi;
  vehicle_box(lo, hi);
  struct Collect : btDbvt::ICollide {
    std::vector<int>* hits;
    void Process(const btDbvtNode* leaf) override {
      hits->push_back(static_cast<int>(reinterpret_cast<std::size_t>(leaf->data)));
    }
  };
  std::vector<int>& candidates = candidates_;
  double radius = std::min(cutoff_m, std::max(kMinSearch_m, 2.0 * search_->obstacle_hint_m));
  for (;;) {
    const btVector3 pad(radius, radius, radius);
    const bool everything = statics_.empty() || covers(lo - pad, hi + pad, statics_min_, statics_max_, 3);
    candidates.clear();
    Collect collect;
    collect.hits = &candidates;
    if (!statics_.empty()) static_tree_.collideTV(static_tree_.m_root, btDbvtVolume::FromMM(lo - pad, hi + pad), collect);
    for (const int k : candidates) {
      const StaticObstacle& o = statics_[static_cast<std::size_t>(k)];
      measure_obstacle(lo, hi, *o.shape, o.pose, o.id, std::min(radius, within_m), out);
    }
    if (out.obstacle_m <= radius || radius >= cutoff_m) break;
    // Nothing within the radius: grow the box until it covers every static obstacle.
    if (everything) break;
    radius = std::min(cutoff_m, 2.0 * radius);
  }
  nearest_mesh(cutoff_m, out);
  if (out.obstacle_m >= cutoff_m) {
    out.obstacle_m = kInfinity;
    out.obstacle = -1;
  }
  if (std::isfinite(out.obstacle_m)) search_->obstacle_hint_m = std::max(0.0, out.obstacle_m);
}

// Planes exactly from each body's support point; heightfields triangle by
// triangle within a box that grows as in nearest_obstacle.
void ClearanceQuery::nearest_ground(double cutoff_m, Clearance& out) {
  for (const Ground& g : ground_) {
    for (const VehiclePart& part : *vehicle_) {
      if (part.ground_counts) out.ground_m = std::min(out.ground_m, ground_distance(g, part, cutoff_m, nullptr));
    }
  }
  if (out.ground_m >= cutoff_m) out.ground_m = kInfinity;
  if (std::isfinite(out.ground_m)) search_->ground_hint_m = std::max(0.0, out.ground_m);
}

double ClearanceQuery::ground_distance(const Ground& g, const VehiclePart& part, double cutoff_m, btVector3* point) {
  const btCollisionObject* ground = g.body;
  const btCollisionShape* shape = ground->getCollisionShape();
  const btTransform& ground_pose = ground->getWorldTransform();
  const auto* mine = static_cast<const btConvexShape*>(part.body->getCollisionShape());
  const btTransform& pose = part.body->getWorldTransform();
  if (shape->getShapeType() == STATIC_PLANE_PROXYTYPE) {
    const auto* plane = static_cast<const btStaticPlaneShape*>(shape);
    const btVector3 normal = ground_pose.getBasis() * plane->getPlaneNormal();
    const btVector3 on_plane = ground_pose * (plane->getPlaneNormal() * plane->getPlaneConstant());
    const btVector3 lowest = pose * mine->localGetSupportingVertex(pose.getBasis().transpose() * -normal);
    const double d = normal.dot(lowest - on_plane);
    if (point) *point = lowest - normal * d;  // straight below the lowest point, on the plane
    return d;
  }
  const auto* terrain = static_cast<const btConcaveShape*>(shape);
  TriangleDistances triangles;
  triangles.body = mine;
  triangles.candidates = &triangle_scratch_;
  triangles.body_pose = ground_pose.inverse() * pose;
  mine->getAabb(triangles.body_pose, triangles.body_min, triangles.body_max);
  // Terrain under the reach of the cutoff that lies lower than the
  // cutoff below the body cannot be nearer than it.
  if (!g.blocks.empty() && std::isfinite(cutoff_m)) {
    const btVector3& lo = triangles.body_min;
    const btVector3& hi = triangles.body_max;
    const double top = g.blocks.highest(lo.x() - cutoff_m, hi.x() + cutoff_m, lo.y() - cutoff_m, hi.y() + cutoff_m);
    if (lo.z() - top >= cutoff_m) return kInfinity;
  }
  double radius = std::min(cutoff_m, std::max(kMinSearch_m, 2.0 * search_->ground_hint_m));
  for (;;) {
    triangles.cutoff = radius;
    const btVector3 pad(radius, radius, radius);
    // Bullet's own triangles, read from the heights it was given
    // without its per-vertex virtual calls.
    if (!g.blocks.empty()) {
      // Cells as far as the radius (or the nearest triangle yet) hold no triangle processTriangle keeps.
      const HeightBlocks::Near near{triangles.body_min, triangles.body_max, std::min(triangles.best, triangles.cutoff)};
      g.blocks.triangles_under(triangles.body_min - pad, triangles.body_max + pad, triangles, &near);
    } else {
      terrain->processAllTriangles(&triangles, triangles.body_min - pad, triangles.body_max + pad);
    }
    triangles.measure();
    if (triangles.best <= radius || radius >= cutoff_m) break;
    btVector3 all_min, all_max;
    terrain->getAabb(btTransform::getIdentity(), all_min, all_max);
    // Every triangle lies under a box that covers the terrain's footprint.
    if (covers(triangles.body_min - pad, triangles.body_max + pad, all_min, all_max, 2)) break;
    radius = std::min(cutoff_m, 2.0 * radius);
  }
  if (point) *point = ground_pose * triangles.best_point;
  return triangles.best;
}

}  // namespace campo

namespace campo {

// Each static mesh whose box is within reach, part by part.
void ClearanceQuery::nearest_mesh(double cutoff_m, Clearance& out) {
  if (meshes_.empty()) return;
  for (const StaticMesh& mesh : meshes_) {
    for (const VehiclePart& part : *vehicle_) {
      btVector3 lo, hi;
      part.body->getCollisionShape()->getAabb(part.body->getWorldTransform(), lo, hi);
      const double reach = std::min(out.obstacle_m, cutoff_m);
      // Outside the mesh's box, farther than the reach: nothing of it is nearer (and not inside it).
      if (box_distance(lo, hi, mesh.lo, mesh.hi) >= reach) continue;
      const double d = mesh_distance(mesh, part, reach, nullptr);
      if (d < out.obstacle_m) {
        out.obstacle_m = d;
        out.obstacle = mesh.id;
      }
    }
  }
}

double ClearanceQuery::mesh_distance(const StaticMesh& m, const VehiclePart& part, double cutoff_m, btVector3* point) {
  const auto* mesh = static_cast<const btConcaveShape*>(m.body->getCollisionShape());
  const btTransform& mesh_pose = m.body->getWorldTransform();
  TriangleDistances triangles;
  triangles.body = static_cast<const btConvexShape*>(part.body->getCollisionShape());
  triangles.two_sided = true;
  triangles.candidates = &triangle_scratch_;
  triangles.body_pose = mesh_pose.inverse() * part.body->getWorldTransform();
  triangles.body->getAabb(triangles.body_pose, triangles.body_min, triangles.body_max);
  btVector3 all_min, all_max;
  mesh->getAabb(btTransform::getIdentity(), all_min, all_max);
  // Inside a closed surface, inside the solid: the parity of the faces a ray
  // from the body's origin crosses says which (the ray's direction skewed so
  // that it meets no edge of an axis-aligned mesh). Inside, the nearest face
  // is wanted however far.
  bool inside = false;
  const btVector3 origin = triangles.body_pose.getOrigin();
  if (m.closed && covers(all_min, all_max, origin, origin, 3)) {
    RayCrossings ray;
    ray.origin = origin;
    ray.direction = btVector3(0.01297, 0.00731, 1.0).normalized();
    ray.length = (all_max - all_min).length() + 1.0;
    const btVector3 end = origin + ray.direction * ray.length;
    btVector3 lo = origin, hi = origin;
    lo.setMin(end);
    hi.setMax(end);
    mesh->processAllTriangles(&ray, lo, hi);
    inside = ray.crossings % 2 == 1;
    if (inside) cutoff_m = kInfinity;
  }
  // The search box grows from the last answer until the nearest triangle found lies within it.
  double radius = std::min(cutoff_m, std::max(kMinSearch_m, 2.0 * search_->obstacle_hint_m));
  for (;;) {
    triangles.cutoff = radius;
    const btVector3 pad(radius, radius, radius);
    mesh->processAllTriangles(&triangles, triangles.body_min - pad, triangles.body_max + pad);
    triangles.measure();
    if (triangles.best <= radius || radius >= cutoff_m) break;
    if (covers(triangles.body_min - pad, triangles.body_max + pad, all_min, all_max, 3)) break;
    radius = std::min(cutoff_m, 2.0 * radius);
  }
  // Clear of every face but inside: minus the distance to the nearest face.
  const double d = inside && triangles.best > 0.0 ? -triangles.best : triangles.best;
  if (point) *point = mesh_pose * triangles.best_point;
  return d;
}

}  // namespace campo
