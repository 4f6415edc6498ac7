#include "vehicles/contacts.hpp"

#include <algorithm>

#include <btBulletDynamicsCommon.h>

namespace campo {

std::vector<int> touching_objects(const btDiscreteDynamicsWorld& world, const btCollisionObject& body,
                                  double margin_m) {
  std::vector<int> out;
  // Bullet's manifold accessors are not const; reading them changes nothing.
  btDispatcher* dispatcher = const_cast<btDiscreteDynamicsWorld&>(world).getDispatcher();
  for (int i = 0; i < dispatcher->getNumManifolds(); ++i) {
    const btPersistentManifold* m = dispatcher->getManifoldByIndexInternal(i);
    const btCollisionObject* other = nullptr;
    if (m->getBody0() == &body) other = m->getBody1();
    else if (m->getBody1() == &body) other = m->getBody0();
    if (!other) continue;
    for (int c = 0; c < m->getNumContacts(); ++c) {
      if (m->getContactPoint(c).getDistance() <= margin_m) {
        if (std::find(out.begin(), out.end(), other->getUserIndex()) == out.end()) {
          out.push_back(other->getUserIndex());
        }
        break;
      }
    }
  }
  return out;
}

}  // namespace campo
