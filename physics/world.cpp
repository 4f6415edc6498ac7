#include "campo/world.hpp"
#include "physics/bullet_convert.hpp"
#include "physics/clearance.hpp"
#include "physics/terrain_shape.hpp"
#include "physics/wind.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h>
#include <LinearMath/btConvexHullComputer.h>

namespace campo {

namespace {

// Mover shapes are tagged with negative user indices so hits can name them.
int mover_tag(std::size_t mover_index) { return -1 - static_cast<int>(mover_index); }

// Compounds of static obstacles get tags far below movers and above vehicles.
constexpr int kCompoundTagBase = -1000000000;
int compound_tag(std::size_t k) { return kCompoundTagBase - static_cast<int>(k); }

// Static obstacles are grouped into compounds per friction value and per
// square cell of this size.
constexpr double kCompoundCell_m = 8.0;
struct CompoundKey {
  double friction;
  long cell_x;
  long cell_y;
  bool operator==(const CompoundKey&) const = default;
};

// Closest hit that also remembers which child of a compound was hit.
struct ClosestRayWithChild : btCollisionWorld::ClosestRayResultCallback {
  using ClosestRayResultCallback::ClosestRayResultCallback;
  int child = -1;
  btScalar addSingleResult(btCollisionWorld::LocalRayResult& r, bool normal_in_world) override {
    child = r.m_localShapeInfo ? r.m_localShapeInfo->m_triangleIndex : -1;
    return ClosestRayResultCallback::addSingleResult(r, normal_in_world);
  }
};

}  // namespace

struct World::Impl {
  // Declaration order is destruction order in reverse: the dynamics world goes
  // first, then bodies, then shapes, then the infrastructure it used.
  btDefaultCollisionConfiguration collision_config;
  btCollisionDispatcher dispatcher{&collision_config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  // The vertices and indices static meshes' shapes point into (Bullet keeps
  // pointers, not copies): declared before the shapes, destroyed after them.
  struct MeshArrays {
    std::vector<btScalar> vertices;
    std::vector<int> indices;
    btTriangleIndexVertexArray array;
  };
  std::vector<std::unique_ptr<MeshArrays>> mesh_arrays;
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  // Static obstacles share compound bodies (one per friction value): Bullet
  // walks every collision object each step, so hundreds of posts as separate
  // bodies would cost more than the vehicle. Child i of compounds[k] is
  // scene shape compound_children[k][i].
  std::vector<std::unique_ptr<btCompoundShape>> compounds;
  std::vector<std::vector<int>> compound_children;
  std::vector<std::unique_ptr<btDefaultMotionState>> motion_states;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::vector<btRigidBody*> shape_bodies;  // by Scene::shapes index; null inside a compound
  std::vector<btRigidBody*> mover_bodies;  // by Scene::movers index
  std::vector<btRigidBody*> moving_bodies;  // in moving_bodies(scene) order: dynamic shapes, then movers
  ClearanceQuery clearance;
  std::unique_ptr<btDiscreteDynamicsWorld> dynamics;
  std::int64_t steps = 0;
  std::size_t vehicles_joined = 0;
  std::optional<WindField> wind;  // set by World::World; advanced once per step

  // Each vehicle's bodies, in the order they joined the world, with their
  // bounding spheres (local centre, radius); found again when bodies join or leave.
  struct VehicleBody {
    const btCollisionObject* body;
    bool wheel;
    btVector3 centre;
    btScalar radius;
  };
  mutable std::vector<std::vector<VehicleBody>> vehicle_bodies;
  mutable int objects_seen = -1;

  const std::vector<VehicleBody>& bodies_of(std::size_t vehicle) const {
    const btCollisionObjectArray& objects = dynamics->getCollisionObjectArray();
    if (objects.size() != objects_seen) {
      objects_seen = objects.size();
      vehicle_bodies.clear();
      for (int i = 0; i < objects.size(); ++i) {
        const int tag = objects[i]->getUserIndex();
        if (!is_vehicle_tag(tag)) continue;
        const std::size_t v = vehicle_of_tag(tag);
        if (vehicle_bodies.size() <= v) vehicle_bodies.resize(v + 1);
        VehicleBody body{objects[i], is_wheel_tag(tag), {}, 0};
        objects[i]->getCollisionShape()->getBoundingSphere(body.centre, body.radius);
        vehicle_bodies[v].push_back(body);
      }
    }
    static const std::vector<VehicleBody> kNone;
    return vehicle < vehicle_bodies.size() ? vehicle_bodies[vehicle] : kNone;
  }

  template <typename F>
  void for_each_vehicle_body(std::size_t vehicle, F&& f) const {
    for (const VehicleBody& b : bodies_of(vehicle)) f(*b.body, b.wheel);
  }

  Impl() {
    dynamics = std::make_unique<btDiscreteDynamicsWorld>(&dispatcher, &broadphase, &solver,
                                                         &collision_config);
    // Static bodies never move: refresh only the bounding boxes of active ones
    // (by default Bullet recomputes every box every step).
    dynamics->setForceUpdateAllAabbs(false);
  }
  ~Impl() {
    for (auto& body : bodies) dynamics->removeRigidBody(body.get());
    dynamics.reset();
  }

  // Bullet pads cylinders and cones with a collision margin (4 cm) and
  // rounds the edges of boxes with it, which would make obstacles differ
  // from what the LIDAR sees and what clearance measures; dynamic bodies
  // keep it for contact stability.
  static void set_exact(btCollisionShape& shape) {
    if (shape.getShapeType() != SPHERE_SHAPE_PROXYTYPE) shape.setMargin(0.0);
  }

  std::unique_ptr<btCollisionShape> make_shape(const Shape& shape) {
    switch (shape.type) {
      case ShapeType::cuboid:
        return std::make_unique<btBoxShape>(to_bt(shape.size_m * 0.5));
      case ShapeType::cylinder:
        return std::make_unique<btCylinderShapeZ>(
            btVector3(shape.radius_m, shape.radius_m, shape.height_m * 0.5));
      case ShapeType::sphere:
        return std::make_unique<btSphereShape>(shape.radius_m);
      case ShapeType::cone:
        return std::make_unique<btConeShapeZ>(shape.radius_m, shape.height_m);
      case ShapeType::plane:
        return std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0.0);
      case ShapeType::heightfield: {
        return std::make_unique<TerrainShape>(*shape.terrain);
      }
      case ShapeType::mesh:
        return shape.is_static ? static_mesh_shape(*shape.mesh) : convex_hull_shape(*shape.mesh);
    }
    throw std::logic_error("unhandled shape type");
  }

  // A static mesh collides as its triangles, through a bounding-volume tree.
  std::unique_ptr<btCollisionShape> static_mesh_shape(const TriangleMesh& mesh) {
    auto arrays = std::make_unique<MeshArrays>();
    arrays->vertices.reserve(3 * mesh.vertices_m.size());
    for (const Eigen::Vector3d& v : mesh.vertices_m) {
      for (int k = 0; k < 3; ++k) arrays->vertices.push_back(static_cast<btScalar>(v[k]));
    }
    arrays->indices.reserve(3 * mesh.triangles.size());
    for (const auto& t : mesh.triangles) {
      for (const std::uint32_t i : t) arrays->indices.push_back(static_cast<int>(i));
    }
    btIndexedMesh part;
    part.m_numTriangles = static_cast<int>(mesh.triangles.size());
    part.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(arrays->indices.data());
    part.m_triangleIndexStride = 3 * sizeof(int);
    part.m_numVertices = static_cast<int>(mesh.vertices_m.size());
    part.m_vertexBase = reinterpret_cast<const unsigned char*>(arrays->vertices.data());
    part.m_vertexStride = 3 * sizeof(btScalar);
    arrays->array.addIndexedMesh(part, PHY_INTEGER);
    auto shape = std::make_unique<btBvhTriangleMeshShape>(&arrays->array, true, true);
    mesh_arrays.push_back(std::move(arrays));
    return shape;
  }

  // A dynamic mesh collides as its convex hull, shrunk by Bullet's margin so
  // that hull and margin together have the mesh's extents (as a dynamic box's
  // margin lies within its size).
  static std::unique_ptr<btCollisionShape> convex_hull_shape(const TriangleMesh& mesh) {
    btConvexHullComputer hull;
    hull.compute(mesh.vertices_m.data()->data(), static_cast<int>(sizeof(Eigen::Vector3d)),
                 static_cast<int>(mesh.vertices_m.size()), CONVEX_DISTANCE_MARGIN, 0.25);
    if (hull.vertices.size() == 0) {  // flat: no volume to shrink
      hull.compute(mesh.vertices_m.data()->data(), static_cast<int>(sizeof(Eigen::Vector3d)),
                   static_cast<int>(mesh.vertices_m.size()), 0.0, 0.0);
    }
    return std::make_unique<btConvexHullShape>(&hull.vertices[0].x(), hull.vertices.size(), sizeof(btVector3));
  }

  btTransform body_transform(const Shape& shape) const {
    btTransform t = to_bt(shape.pose);
    if (shape.type == ShapeType::heightfield) {
      // Bullet centres a heightfield vertically on the middle of its height range.
      const double mid = 0.5 * (shape.terrain->min_height_m() + shape.terrain->max_height_m());
      t.setOrigin(t.getOrigin() + t.getBasis().getColumn(2) * mid);
    }
    return t;
  }

  btRigidBody* add_body(const Shape& shape, int tag, bool kinematic) {
    shapes.push_back(make_shape(shape));
    btCollisionShape* collision_shape = shapes.back().get();
    if (shape.is_static || kinematic) set_exact(*collision_shape);
    const bool dynamic = !shape.is_static && !kinematic;
    const double mass = dynamic ? shape.mass_kg : 0.0;
    btVector3 inertia(0, 0, 0);
    if (dynamic) collision_shape->calculateLocalInertia(mass, inertia);
    // A motion state only where Bullet reads one (a kinematic mover, placed through it);
    // campo reads the other bodies' own transforms, and Bullet would interpolate a
    // motion state for every dynamic body every step.
    btMotionState* motion_state = nullptr;
    if (kinematic) {
      motion_states.push_back(std::make_unique<btDefaultMotionState>(body_transform(shape)));
      motion_state = motion_states.back().get();
    }
    btRigidBody::btRigidBodyConstructionInfo info(mass, motion_state, collision_shape, inertia);
    info.m_startWorldTransform = body_transform(shape);
    info.m_friction = shape.friction;
    bodies.push_back(std::make_unique<btRigidBody>(info));
    btRigidBody* body = bodies.back().get();
    body->setUserIndex(tag);
    if (kinematic) {
      body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
      body->setActivationState(DISABLE_DEACTIVATION);
    }
    dynamics->addRigidBody(body);
    return body;
  }
};

World::World(const Scene& scene) : scene_(scene), impl_(std::make_unique<Impl>()) {
  impl_->dynamics->setGravity(to_bt(scene.world.gravity_mps2));
  Impl& d = *impl_;
  d.wind.emplace(scene.world.wind, scene.world.seed, scene.world.physics_step_s);
  d.shape_bodies.assign(scene.shapes.size(), nullptr);
  std::vector<double> compound_friction;
  std::vector<CompoundKey> compound_keys;
  for (std::size_t i = 0; i < scene.shapes.size(); ++i) {
    const Shape& shape = scene.shapes[i];
    // Static meshes are bodies of their own (a compound's ray hits would name a triangle, not the child).
    const bool obstacle = shape.is_static && shape.type != ShapeType::plane && shape.type != ShapeType::heightfield &&
                          shape.type != ShapeType::mesh;
    if (!obstacle) {
      d.shape_bodies[i] = d.add_body(shape, static_cast<int>(i), false);
      if (shape.type == ShapeType::mesh && shape.is_static) {
        d.clearance.add_static_mesh(*d.shape_bodies[i], static_cast<int>(i), shape.mesh->closed);
      }
      continue;
    }
    // Group by friction and by a coarse grid cell of the position, so a
    // vehicle's box overlaps few compounds with few children each.
    const Eigen::Vector3d p = shape.pose.translation();
    const CompoundKey key{shape.friction, static_cast<long>(std::floor(p.x() / kCompoundCell_m)),
                          static_cast<long>(std::floor(p.y() / kCompoundCell_m))};
    auto k = static_cast<std::size_t>(std::find(compound_keys.begin(), compound_keys.end(), key) - compound_keys.begin());
    if (k == compound_keys.size()) {
      compound_keys.push_back(key);
      compound_friction.push_back(shape.friction);
      d.compounds.push_back(std::make_unique<btCompoundShape>());
      d.compound_children.emplace_back();
    }
    d.shapes.push_back(d.make_shape(shape));
    d.set_exact(*d.shapes.back());
    d.compounds[k]->addChildShape(to_bt(shape.pose), d.shapes.back().get());
    d.clearance.add_static_obstacle(static_cast<const btConvexShape&>(*d.shapes.back()), to_bt(shape.pose),
                                    static_cast<int>(i));
    d.compound_children[k].push_back(static_cast<int>(i));
  }
  for (std::size_t k = 0; k < d.compounds.size(); ++k) {
    btRigidBody::btRigidBodyConstructionInfo info(0.0, nullptr, d.compounds[k].get());
    info.m_friction = compound_friction[k];
    d.bodies.push_back(std::make_unique<btRigidBody>(info));
    d.bodies.back()->setUserIndex(compound_tag(k));
    d.dynamics->addRigidBody(d.bodies.back().get());
    d.clearance.add_static_compound(*d.bodies.back(), d.compound_children[k]);
  }
  for (std::size_t i = 0; i < scene.movers.size(); ++i) {
    impl_->mover_bodies.push_back(impl_->add_body(scene.movers[i].shape, mover_tag(i), true));
  }
  // What clearance measures against: every shape but the vehicles'.
  for (const MovingBody& body : moving_bodies(scene)) {
    btRigidBody* rigid = body.id >= 0 ? d.shape_bodies[static_cast<std::size_t>(body.id)]
                                      : d.mover_bodies[static_cast<std::size_t>(-1 - body.id)];
    d.moving_bodies.push_back(rigid);
    d.clearance.add_moving_obstacle(*rigid, body.id);
  }
  for (std::size_t i = 0; i < scene.shapes.size(); ++i) {
    const ShapeType type = scene.shapes[i].type;
    if (type == ShapeType::plane || type == ShapeType::heightfield) {
      d.clearance.add_ground(*d.shape_bodies[i], scene.shapes[i].terrain.get());
    }
  }
}

World::~World() = default;

double World::time_s() const {
  return static_cast<double>(impl_->steps) * scene_.world.physics_step_s;
}

std::int64_t World::step_count() const { return impl_->steps; }

void World::step() {
  const double dt = scene_.world.physics_step_s;
  const double t_next = static_cast<double>(impl_->steps + 1) * dt;
  // Kinematic movers: Bullet reads their motion state to derive velocities.
  for (std::size_t i = 0; i < scene_.movers.size(); ++i) {
    const Mover& mover = scene_.movers[i];
    btTransform t = impl_->body_transform(mover.shape);
    t.setOrigin(to_bt(mover.position_at(t_next)));
    impl_->mover_bodies[i]->getMotionState()->setWorldTransform(t);
  }
  impl_->dynamics->stepSimulation(dt, 1, dt);
  ++impl_->steps;
  impl_->wind->advance();
}

Eigen::Vector3d World::wind_mps(const Eigen::Vector3d& /*position_m*/) const {
  // Uniform in space (physics/wind.hpp): the same air everywhere at a given time.
  return impl_->wind->velocity_mps(time_s());
}

std::optional<double> World::terrain_height(double x_m, double y_m) const {
  return scene_.ground_height(x_m, y_m);
}

std::optional<WorldRayHit> World::ray_test(const Eigen::Vector3d& from,
                                           const Eigen::Vector3d& to) const {
  ClosestRayWithChild callback(to_bt(from), to_bt(to));
  impl_->dynamics->rayTest(to_bt(from), to_bt(to), callback);
  if (!callback.hasHit()) return std::nullopt;
  WorldRayHit hit;
  hit.point_m = from_bt(callback.m_hitPointWorld);
  hit.normal = from_bt(callback.m_hitNormalWorld).normalized();
  hit.distance_m = (hit.point_m - from).norm();
  hit.shape = callback.m_collisionObject->getUserIndex();
  if (hit.shape <= kCompoundTagBase && hit.shape > kVehicleBodyTag) {
    const auto& children = impl_->compound_children[static_cast<std::size_t>(kCompoundTagBase - hit.shape)];
    hit.shape = children.at(static_cast<std::size_t>(callback.child));
  }
  return hit;
}

void World::moving_body_poses(std::vector<Eigen::Isometry3d>& out) const {
  out.resize(impl_->moving_bodies.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const btTransform& t = impl_->moving_bodies[i]->getWorldTransform();
    const btMatrix3x3& b = t.getBasis();
    Eigen::Matrix3d r;
    for (int row = 0; row < 3; ++row) r.row(row) << b[row].x(), b[row].y(), b[row].z();
    out[i].linear() = r;
    out[i].translation() = from_bt(t.getOrigin());
  }
}

std::size_t World::join_vehicle() {
  if (impl_->vehicles_joined >= kMaxVehicles) {
    throw std::invalid_argument("a world holds at most " + std::to_string(kMaxVehicles) + " vehicles");
  }
  return impl_->vehicles_joined++;
}

Clearance World::vehicle_clearance(std::size_t vehicle, double obstacle_cutoff_m, double ground_cutoff_m,
                                  bool other_vehicles) const {
  return impl_->clearance.measure(*impl_->dynamics, vehicle, obstacle_cutoff_m, ground_cutoff_m, other_vehicles);
}

double World::vehicle_distance(std::size_t a, std::size_t b, double cutoff_m, Eigen::Vector3d* point_on_b) const {
  double best = std::numeric_limits<double>::infinity();
  const auto& bodies_b = impl_->bodies_of(b);
  for (const Impl::VehicleBody& body_a : impl_->bodies_of(a)) {
    const btVector3 world_a = body_a.body->getWorldTransform() * body_a.centre;
    for (const Impl::VehicleBody& body_b : bodies_b) {
      // The bounding spheres' gap bounds the shapes' distance from below ...
      const btVector3 between = body_b.body->getWorldTransform() * body_b.centre - world_a;
      const double centres_m = between.length();
      const double limit = std::min(best, cutoff_m);
      if (centres_m - body_a.radius - body_b.radius >= limit) continue;
      // ... and so does the gap between their projections on the line through the centres (a
      // separating axis): exact for boxes face to face, as vehicles side by side in lanes are.
      if (centres_m > 0.0) {
        const btVector3 u = between / centres_m;
        const auto reach = [](const Impl::VehicleBody& body, const btVector3& towards, const btVector3& centre) {
          const btTransform& pose = body.body->getWorldTransform();
          const auto* convex = static_cast<const btConvexShape*>(body.body->getCollisionShape());
          const btVector3 far = pose * convex->localGetSupportingVertex(pose.getBasis().transpose() * towards);
          return static_cast<double>(towards.dot(far - centre));
        };
        const btVector3 centre_b = body_b.body->getWorldTransform() * body_b.centre;
        if (centres_m - reach(body_a, u, world_a) - reach(body_b, -u, centre_b) >= limit) continue;
      }
      btVector3 point;
      const double d = signed_distance(*static_cast<const btConvexShape*>(body_a.body->getCollisionShape()),
                                       body_a.body->getWorldTransform(),
                                       *static_cast<const btConvexShape*>(body_b.body->getCollisionShape()),
                                       body_b.body->getWorldTransform(), point_on_b ? &point : nullptr);
      if (d < best) {
        best = d;
        if (point_on_b) *point_on_b = from_bt(point);
      }
    }
  }
  return best < cutoff_m ? best : std::numeric_limits<double>::infinity();
}

std::vector<Shape> World::vehicle_shapes(std::size_t vehicle, const std::string& alias) const {
  std::vector<Shape> shapes;
  int wheels = 0;
  impl_->for_each_vehicle_body(vehicle, [&](const btCollisionObject& body, bool wheel) {
    Shape s;
    s.alias = alias + (wheel ? "/wheel" + std::to_string(wheels++) : "/body");
    s.color = {0.85, 0.45, 0.1};
    const btCollisionShape& shape = *body.getCollisionShape();
    if (shape.getShapeType() == SPHERE_SHAPE_PROXYTYPE) {
      s.type = ShapeType::sphere;
      s.radius_m = static_cast<const btSphereShape&>(shape).getRadius();
    } else if (shape.getShapeType() == BOX_SHAPE_PROXYTYPE) {
      s.type = ShapeType::cuboid;
      s.size_m = 2.0 * from_bt(static_cast<const btBoxShape&>(shape).getHalfExtentsWithMargin());
    } else {  // any other convex shape: its bounding box
      btVector3 lo, hi;
      shape.getAabb(btTransform::getIdentity(), lo, hi);
      s.type = ShapeType::cuboid;
      s.size_m = from_bt(hi - lo);
    }
    s.is_static = false;
    shapes.push_back(std::move(s));
  });
  std::vector<Eigen::Isometry3d> poses;
  append_vehicle_poses(vehicle, poses);
  for (std::size_t i = 0; i < shapes.size(); ++i) shapes[i].pose = poses[i];
  return shapes;
}

void World::append_vehicle_poses(std::size_t vehicle, std::vector<Eigen::Isometry3d>& out) const {
  impl_->for_each_vehicle_body(vehicle, [&out](const btCollisionObject& body, bool) {
    const btTransform& t = body.getWorldTransform();
    const btMatrix3x3& b = t.getBasis();
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    for (int row = 0; row < 3; ++row) pose.linear().row(row) << b[row].x(), b[row].y(), b[row].z();
    pose.translation() = from_bt(t.getOrigin());
    out.push_back(pose);
  });
}

BodyState World::shape_state(int shape_index) const {
  const btRigidBody* body = impl_->shape_bodies.at(static_cast<std::size_t>(shape_index));
  BodyState state;
  if (!body) {  // a static obstacle: where the scene put it, at rest
    const Eigen::Isometry3d& pose = scene_.shapes[static_cast<std::size_t>(shape_index)].pose;
    state.position_m = pose.translation();
    state.orientation = Eigen::Quaterniond(pose.linear());
    return state;
  }
  const btTransform& t = body->getWorldTransform();
  state.position_m = from_bt(t.getOrigin());
  const btQuaternion q = t.getRotation();
  state.orientation = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z());
  state.linear_velocity_mps = from_bt(body->getLinearVelocity());
  state.angular_velocity_radps = from_bt(body->getAngularVelocity());
  return state;
}

std::uint64_t World::state_hash() const {
  // FNV-1a over the exact bit patterns: any difference in any body shows.
  std::uint64_t h = 0xcbf29ce484222325ULL;
  const auto mix = [&h](double v) {
    const auto bits = std::bit_cast<std::uint64_t>(v);
    for (int i = 0; i < 8; ++i) {
      h ^= (bits >> (8 * i)) & 0xffU;
      h *= 0x100000001b3ULL;
    }
  };
  const auto mix_vector = [&mix](const btVector3& v) {
    mix(v.x());
    mix(v.y());
    mix(v.z());
  };
  // Every body in the dynamics world, vehicles' included, in insertion order.
  const btCollisionObjectArray& objects = impl_->dynamics->getCollisionObjectArray();
  for (int i = 0; i < objects.size(); ++i) {
    const btCollisionObject* object = objects[i];
    const btTransform& t = object->getWorldTransform();
    mix_vector(t.getOrigin());
    for (int r = 0; r < 3; ++r) mix_vector(t.getBasis().getRow(r));
    if (const btRigidBody* body = btRigidBody::upcast(object)) {
      mix_vector(body->getLinearVelocity());
      mix_vector(body->getAngularVelocity());
    }
  }
  return h;
}

btDiscreteDynamicsWorld& World::bullet() { return *impl_->dynamics; }

}  // namespace campo
