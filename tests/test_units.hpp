#pragma once
// The units the tests write their numbers in (30 * kDeg radians, 5 * kMm
// metres), shared so that the sources of one test program can be compiled
// together (unity builds) without defining them twice.
#include <numbers>

namespace campo::test_units {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kDeg = std::numbers::pi / 180.0;  // radians per degree
inline constexpr double kMm = 1e-3;                        // metres per millimetre

}  // namespace campo::test_units
