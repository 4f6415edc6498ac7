#include "sim/world.hpp"

#include <bit>
#include <cstring>
#include <stdexcept>

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>

namespace campo {

namespace {

btVector3 to_bt(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
Eigen::Vector3d from_bt(const btVector3& v) { return {v.x(), v.y(), v.z()}; }

btTransform to_bt(const Eigen::Isometry3d& t) {
  const Eigen::Matrix3d& r = t.linear();
  btMatrix3x3 basis(r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2));
  return btTransform(basis, to_bt(t.translation()));
}

// Mover shapes are tagged with negative user indices so hits can name them.
int mover_tag(std::size_t mover_index) { return -1 - static_cast<int>(mover_index); }

}  // namespace

struct World::Impl {
  // Declaration order is destruction order in reverse: the dynamics world goes
  // first, then bodies, then shapes, then the infrastructure it used.
  btDefaultCollisionConfiguration collision_config;
  btCollisionDispatcher dispatcher{&collision_config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> motion_states;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::vector<btRigidBody*> shape_bodies;  // by Scene::shapes index
  std::vector<btRigidBody*> mover_bodies;  // by Scene::movers index
  std::unique_ptr<btDiscreteDynamicsWorld> dynamics;
  std::int64_t steps = 0;

  Impl() {
    dynamics = std::make_unique<btDiscreteDynamicsWorld>(&dispatcher, &broadphase, &solver,
                                                         &collision_config);
  }
  ~Impl() {
    for (auto& body : bodies) dynamics->removeRigidBody(body.get());
    dynamics.reset();
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
        const HeightGrid& grid = *shape.terrain;
        auto terrain = std::make_unique<btHeightfieldTerrainShape>(
            grid.cols, grid.rows, grid.heights_m.data(), grid.min_height_m(), grid.max_height_m(),
            2, false);
        terrain->setLocalScaling(btVector3(grid.spacing_x_m, grid.spacing_y_m, 1.0));
        terrain->buildAccelerator();
        return terrain;
      }
    }
    throw std::logic_error("unhandled shape type");
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
    // Bullet pads cylinders and cones with a collision margin (4 cm), which
    // would make static obstacles fatter than what the LIDAR sees; moving
    // bodies keep it for contact stability.
    const bool padded = shape.type == ShapeType::cylinder || shape.type == ShapeType::cone;
    if (padded && (shape.is_static || kinematic)) collision_shape->setMargin(0.0);
    const bool dynamic = !shape.is_static && !kinematic;
    const double mass = dynamic ? shape.mass_kg : 0.0;
    btVector3 inertia(0, 0, 0);
    if (dynamic) collision_shape->calculateLocalInertia(mass, inertia);
    motion_states.push_back(std::make_unique<btDefaultMotionState>(body_transform(shape)));
    btRigidBody::btRigidBodyConstructionInfo info(mass, motion_states.back().get(),
                                                  collision_shape, inertia);
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
  for (std::size_t i = 0; i < scene.shapes.size(); ++i) {
    impl_->shape_bodies.push_back(impl_->add_body(scene.shapes[i], static_cast<int>(i), false));
  }
  for (std::size_t i = 0; i < scene.movers.size(); ++i) {
    impl_->mover_bodies.push_back(impl_->add_body(scene.movers[i].shape, mover_tag(i), true));
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
}

std::optional<double> World::terrain_height(double x_m, double y_m) const {
  return scene_.ground_height(x_m, y_m);
}

std::optional<WorldRayHit> World::ray_test(const Eigen::Vector3d& from,
                                           const Eigen::Vector3d& to) const {
  btCollisionWorld::ClosestRayResultCallback callback(to_bt(from), to_bt(to));
  impl_->dynamics->rayTest(to_bt(from), to_bt(to), callback);
  if (!callback.hasHit()) return std::nullopt;
  WorldRayHit hit;
  hit.point_m = from_bt(callback.m_hitPointWorld);
  hit.normal = from_bt(callback.m_hitNormalWorld).normalized();
  hit.distance_m = (hit.point_m - from).norm();
  hit.shape = callback.m_collisionObject->getUserIndex();
  return hit;
}

BodyState World::shape_state(int shape_index) const {
  const btRigidBody* body = impl_->shape_bodies.at(static_cast<std::size_t>(shape_index));
  const btTransform& t = body->getWorldTransform();
  BodyState state;
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
