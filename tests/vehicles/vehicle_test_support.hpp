#pragma once
// What the vehicle tests share: scenes written inline, start poses and angle wrapping.
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "campo/scene.hpp"
#include "campo/scene_loader.hpp"

namespace campo::test {

/// A scene from JSON text (an inline test world), as the loader reads a file.
inline Scene parse(const std::string& text) {
  return parse_scene(nlohmann::json::parse(text), "inline.json", std::filesystem::temp_directory_path());
}

/// A scene of nothing but the ground plane.
inline constexpr const char* kGround = R"j({"objects": [{"alias": "ground", "type": "plane"}]})j";

/// The pose at `p` heading `yaw` radians from +x.
inline Eigen::Isometry3d at(const Eigen::Vector3d& p, double yaw = 0.0) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  t.translation() = p;
  return t;
}

/// `angle` in [-pi, pi].
inline double wrap(double angle) { return std::remainder(angle, 2.0 * std::numbers::pi); }

}  // namespace campo::test
