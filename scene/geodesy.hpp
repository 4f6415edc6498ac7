#pragma once
/// WGS84 geodetic <-> ECEF <-> local ENU (x east, y north, z up) conversions
/// (000 §3.1.1, 001 §4.2.3), with the proper cos(latitude) scaling.
#include <Eigen/Core>

namespace campo {

/// Latitude and longitude in degrees, height above the WGS84 ellipsoid in metres.
struct Geodetic {
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
  double altitude_m = 0.0;
};

Eigen::Vector3d geodetic_to_ecef(const Geodetic& g);
Geodetic ecef_to_geodetic(const Eigen::Vector3d& ecef_m);

/// ENU coordinates of `point` in the tangent frame at `origin`.
Eigen::Vector3d geodetic_to_enu(const Geodetic& point, const Geodetic& origin);
/// Inverse of geodetic_to_enu.
Geodetic enu_to_geodetic(const Eigen::Vector3d& enu_m, const Geodetic& origin);

/// Earth radius of seed 001's conversion (001 §4.2.3: R_Terra = 6371000 m).
inline constexpr double kSphereRadius001M = 6371000.0;

/// Seed 001's own conversion (001 §4.2.3): east = deg2rad(lon - lon_ref) R,
/// north = deg2rad(lat - lat_ref) R on a sphere of radius `radius_m`, with no
/// cos(latitude) factor on the longitude (at 40.8 deg north it stretches
/// east-west distances by 1 / cos(40.8 deg) = 1.32), and up = alt - alt_ref.
Eigen::Vector3d geodetic_to_sphere_no_coslat(const Geodetic& point, const Geodetic& origin,
                                             double radius_m = kSphereRadius001M);

}  // namespace campo
