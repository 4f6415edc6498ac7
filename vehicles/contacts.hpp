#pragma once
/// Contact queries for vehicle collision checks.
#include <vector>

class btCollisionObject;
class btDiscreteDynamicsWorld;

namespace campo {

/// Bullet user indices of the objects touching `body` (penetrating or within
/// `margin_m`) after the last physics step, each listed once.
std::vector<int> touching_objects(const btDiscreteDynamicsWorld& world, const btCollisionObject& body,
                                  double margin_m = 1e-3);

}  // namespace campo
