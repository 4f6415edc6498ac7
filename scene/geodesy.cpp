#include "scene/geodesy.hpp"

#include <cmath>
#include <numbers>

namespace campo {

namespace {

constexpr double kA = 6378137.0;                  // WGS84 semi-major axis, m
constexpr double kF = 1.0 / 298.257223563;        // flattening
constexpr double kE2 = kF * (2.0 - kF);           // first eccentricity squared
constexpr double kB = kA * (1.0 - kF);            // semi-minor axis, m
constexpr double kEp2 = (kA * kA - kB * kB) / (kB * kB);  // second eccentricity squared
constexpr double kDeg = std::numbers::pi / 180.0;

// Rows are the east, north and up unit vectors at (lat, lon), in ECEF.
Eigen::Matrix3d ecef_to_enu_rotation(double lat, double lon) {
  const double sl = std::sin(lat), cl = std::cos(lat), so = std::sin(lon), co = std::cos(lon);
  Eigen::Matrix3d r;
  r << -so, co, 0.0,
       -sl * co, -sl * so, cl,
       cl * co, cl * so, sl;
  return r;
}

}  // namespace

Eigen::Vector3d geodetic_to_ecef(const Geodetic& g) {
  const double lat = g.latitude_deg * kDeg, lon = g.longitude_deg * kDeg;
  const double n = kA / std::sqrt(1.0 - kE2 * std::sin(lat) * std::sin(lat));
  return {(n + g.altitude_m) * std::cos(lat) * std::cos(lon),
          (n + g.altitude_m) * std::cos(lat) * std::sin(lon),
          (n * (1.0 - kE2) + g.altitude_m) * std::sin(lat)};
}

Geodetic ecef_to_geodetic(const Eigen::Vector3d& e) {
  // Bowring's method followed by two Newton refinements of latitude.
  const double p = std::hypot(e.x(), e.y());
  const double lon = std::atan2(e.y(), e.x());
  const double theta = std::atan2(e.z() * kA, p * kB);
  double lat = std::atan2(e.z() + kEp2 * kB * std::pow(std::sin(theta), 3),
                          p - kE2 * kA * std::pow(std::cos(theta), 3));
  for (int i = 0; i < 2; ++i) {
    const double n = kA / std::sqrt(1.0 - kE2 * std::sin(lat) * std::sin(lat));
    const double h = p / std::cos(lat) - n;
    lat = std::atan2(e.z(), p * (1.0 - kE2 * n / (n + h)));
  }
  const double n = kA / std::sqrt(1.0 - kE2 * std::sin(lat) * std::sin(lat));
  const double alt = std::abs(std::cos(lat)) > 1e-9 ? p / std::cos(lat) - n
                                                    : std::abs(e.z()) - kB;
  return {lat / kDeg, lon / kDeg, alt};
}

Eigen::Vector3d geodetic_to_enu(const Geodetic& point, const Geodetic& origin) {
  const Eigen::Vector3d d = geodetic_to_ecef(point) - geodetic_to_ecef(origin);
  return ecef_to_enu_rotation(origin.latitude_deg * kDeg, origin.longitude_deg * kDeg) * d;
}

Geodetic enu_to_geodetic(const Eigen::Vector3d& enu_m, const Geodetic& origin) {
  const Eigen::Matrix3d r =
      ecef_to_enu_rotation(origin.latitude_deg * kDeg, origin.longitude_deg * kDeg);
  return ecef_to_geodetic(geodetic_to_ecef(origin) + r.transpose() * enu_m);
}

Eigen::Vector3d geodetic_to_sphere_no_coslat(const Geodetic& point, const Geodetic& origin, double radius_m) {
  const double deg = std::numbers::pi / 180.0;
  return {(point.longitude_deg - origin.longitude_deg) * deg * radius_m,
          (point.latitude_deg - origin.latitude_deg) * deg * radius_m, point.altitude_m - origin.altitude_m};
}

}  // namespace campo
