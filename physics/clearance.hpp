#pragma once
/// True clearance (private to physics/): signed distances between a vehicle's
/// collision shapes and the world's other collision shapes, from Bullet's
/// GJK (EPA when they overlap), the shapes the physics collides with. World
/// owns one query and answers World::vehicle_clearance with it.
#include <limits>
#include <vector>

#include <BulletCollision/BroadphaseCollision/btDbvt.h>
#include <LinearMath/btTransform.h>

#include "campo/world.hpp"
#include "physics/height_blocks.hpp"

class btCollisionObject;
class btCollisionWorld;
class btConvexShape;
class btTriangleCallback;

namespace campo {

/// Signed distance between two convex shapes placed at `pose_a` and
/// `pose_b`, collision margins included: > 0 apart, 0 touching, < 0 the
/// depth of their overlap.
/// `point_on_b`, when given, is set to the point of b's surface nearest a
/// (the deepest when they overlap), in the frame of the poses.
double signed_distance(const btConvexShape& a, const btTransform& pose_a, const btConvexShape& b,
                       const btTransform& pose_b, btVector3* point_on_b = nullptr);

/// A heightfield triangle gathered by the ground search, with a lower bound
/// of its distance to the body (clearance.cpp).
struct TriangleCandidate {
  double bound_m;
  btVector3 v[3];
};

/// The obstacles and the ground of a world, and the search for the nearest
/// of each from one vehicle's bodies (found by their user index when asked,
/// since vehicles join the world after it is built). Each vehicle has its
/// own search state; the other vehicles' bodies are moving obstacles to it.
class ClearanceQuery {
 public:
  ClearanceQuery();
  ~ClearanceQuery();
  ClearanceQuery(const ClearanceQuery&) = delete;
  ClearanceQuery& operator=(const ClearanceQuery&) = delete;

  /// A static obstacle (a child of a static compound), never moving.
  void add_static_obstacle(const btConvexShape& shape, const btTransform& pose, int id);
  /// The Bullet body that holds static obstacles as the children of its
  /// compound shape: `children[i]` is the id given add_static_obstacle for child i.
  void add_static_compound(const btCollisionObject& body, std::vector<int> children);
  /// A body that moves (dynamic shape, mover): read where it is at each query.
  void add_moving_obstacle(const btCollisionObject& body, int id);
  /// A plane or heightfield body; a heightfield's `grid` (the heights Bullet
  /// was given) lets the search skip terrain that is out of reach.
  void add_ground(const btCollisionObject& body, const HeightGrid* grid = nullptr);
  /// A static triangle mesh, its own body (a btBvhTriangleMeshShape): measured
  /// triangle by triangle near the vehicle, through the shape's BVH. Inside a
  /// `closed` mesh (a body's origin inside the surface) the distance is
  /// minus the distance to the nearest face.
  void add_static_mesh(const btCollisionObject& body, int id, bool closed);

  /// Clearance of the bodies tagged vehicle_tag(vehicle, ...) in `world`:
  /// exact below each cutoff, +infinity when nothing is nearer; whether
  /// Bullet's narrow phase has them in contact; and when they touch, what and
  /// where (Clearance::touch).
  /// Without `other_vehicles` their distances are left to the caller (who
  /// measures each pair once); a contact with one still counts and is named.
  Clearance measure(const btCollisionWorld& world, std::size_t vehicle, double obstacle_cutoff_m,
                    double ground_cutoff_m, bool other_vehicles = true);

  /// Whether a query may reuse the static obstacles' and the ground's answer
  /// of the vehicle's last query when its bodies have not moved since (bit
  /// for bit): the closed loop measures each state twice, after the physics
  /// step and again, with no cutoff, at a control tick. Off, every query
  /// searches (the reference the tests compare with).
  void set_reuse(bool reuse) { reuse_ = reuse; }

 private:
  struct StaticObstacle {
    const btConvexShape* shape;
    btTransform pose;
    int id;
  };
  struct MovingObstacle {
    const btCollisionObject* body;
    int id;
  };
  struct StaticCompound {
    const btCollisionObject* body;
    std::vector<int> children;
  };
  struct Ground {
    const btCollisionObject* body;
    HeightBlocks blocks;  // empty for planes
  };
  struct StaticMesh {
    const btCollisionObject* body;
    int id;
    bool closed;
    btVector3 lo, hi;  // the mesh's box, world frame
  };
  // The first contact in_contact found: the body the vehicle touches and,
  // for a compound, the child's index (Bullet's index on that side).
  struct ContactSeen {
    const btCollisionObject* other = nullptr;
    int child = -1;
  };
  struct VehiclePart {
    const btCollisionObject* body;
    bool ground_counts;  // kVehicleBodyTag: touching the ground is a collision
    double reach_m;      // from the body's origin to its farthest point (bounding sphere)
  };
  // A lower bound of a distance to things that do not move, valid with the
  // vehicle's bodies at `poses` (and their rotations, for travel_since).
  struct Floor {
    double floor_m = -std::numeric_limits<double>::infinity();
    std::vector<btTransform> poses;
    std::vector<btQuaternion> rotations;
  };
  // The answer of the last search of things that do not move (static
  // obstacles, or the ground), made with the vehicle's bodies at `poses` and
  // exact below `reach_m`: the same bodies at the same poses get the same
  // answer, which is that one below any cutoff when it was found (finite),
  // and none below a cutoff up to reach_m when it was not.
  struct Memo {
    double reach_m = -std::numeric_limits<double>::infinity();  // none yet
    double distance_m = std::numeric_limits<double>::infinity();
    int id = -1;
    std::vector<btTransform> poses;
  };
  // What one vehicle's searches keep from one query to the next.
  struct Search {
    std::vector<VehiclePart> parts;       // its bodies
    std::vector<MovingObstacle> others;   // the other vehicles' bodies, id their vehicle_tag
    int objects_seen = -1;                // collision objects in the world when parts were found
    double obstacle_hint_m = 1.0;         // the last nearest obstacle distance: where the search starts
    double ground_hint_m = 1.0;
    Floor static_floor;
    Floor ground_floor;
    Memo static_memo;
    Memo ground_memo;
    bool static_found = false;  // static_floor is the distance of an obstacle apart from the vehicle, not a reach
  };
  void find_vehicle(const btCollisionWorld& world, std::size_t vehicle);
  void vehicle_box(btVector3& lo, btVector3& hi) const;
  void measure_obstacle(const btVector3& lo, const btVector3& hi, const btConvexShape& shape, const btTransform& pose,
                        int id, double bound, Clearance& out) const;
  void nearest_moving(double cutoff_m, bool other_vehicles, Clearance& out) const;
  // `within_m`: a distance the answer is known not to exceed by more than
  // GJK's tolerance; obstacles whose boxes lie farther are not measured.
  void nearest_static(double cutoff_m, Clearance& out, double within_m = std::numeric_limits<double>::infinity());
  void nearest_ground(double cutoff_m, Clearance& out);
  // Distance from one vehicle part to one ground body, exact below the
  // cutoff (+infinity beyond), and the ground's point nearest it (world frame).
  double ground_distance(const Ground& g, const VehiclePart& part, double cutoff_m, btVector3* point);
  // Distance from one vehicle part to a static mesh, exact below the cutoff
  // (+infinity beyond), and the mesh's point nearest it (world frame).
  double mesh_distance(const StaticMesh& m, const VehiclePart& part, double cutoff_m, btVector3* point);
  void nearest_mesh(double cutoff_m, Clearance& out);
  void remember(Floor& floor, double floor_m) const;
  const VehiclePart* part_of(const btCollisionObject* object) const;
  bool in_contact(const btCollisionWorld& world, ContactSeen& seen) const;
  // What the vehicle touches and where, from the contact seen or the overlap measured.
  Touch touch(const Clearance& c, const ContactSeen& seen);
  Touch touch_obstacle(int id) const;
  Touch touch_ground(const Ground* only);
  // How far any point of the vehicle's bodies may have moved since `floor` was set.
  double travel_since(const Floor& floor) const;
  // The memo's answer below `reach_m` when it holds for the vehicle's bodies where they are now.
  bool recall(const Memo& memo, double reach_m, double& distance_m, int& id) const;
  void memorize(Memo& memo, double reach_m, double distance_m, int id) const;

  std::vector<StaticObstacle> statics_;
  btDbvt static_tree_;  // leaves: index into statics_
  btVector3 statics_min_, statics_max_;
  std::vector<StaticCompound> compounds_;
  std::vector<MovingObstacle> moving_;
  std::vector<Ground> ground_;
  std::vector<StaticMesh> meshes_;
  std::vector<Search> searches_;  // by vehicle number
  // The search of the vehicle measure() is measuring; its parts.
  Search* search_ = nullptr;
  const std::vector<VehiclePart>* vehicle_ = nullptr;
  std::vector<int> candidates_;  // scratch of nearest_obstacle, reused
  std::vector<TriangleCandidate> triangle_scratch_;  // scratch of nearest_ground, reused
  std::vector<btQuaternion> rotations_;  // of the vehicle's bodies now: measure() sets them for travel_since
  bool reuse_ = true;
  static constexpr double kSlack_m = 0.5;  // measured beyond a cutoff, to skip the next steps
};

}  // namespace campo
