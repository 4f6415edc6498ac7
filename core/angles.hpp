#pragma once
/// Angle constants shared by the sources of one room (one definition, so the
/// room's sources can be compiled together in a unity build).

#include <numbers>

namespace campo {

/// Radians in a degree: an angle in degrees times this is the angle in radians.
inline constexpr double kDegToRad = std::numbers::pi / 180.0;

}  // namespace campo
