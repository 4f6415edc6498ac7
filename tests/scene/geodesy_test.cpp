#include "scene/geodesy.hpp"
#include "tests/test_units.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace campo {
namespace {

constexpr double kWgs84SemiMajor_m = 6378137.0;
constexpr double kF = 1.0 / 298.257223563;
using namespace campo::test_units;

TEST(Geodesy, EcefOfReferencePoints) {
  EXPECT_TRUE(geodetic_to_ecef({0, 0, 0}).isApprox(Eigen::Vector3d(kWgs84SemiMajor_m, 0, 0), 1e-12));
  EXPECT_TRUE(geodetic_to_ecef({0, 90, 0}).isApprox(Eigen::Vector3d(0, kWgs84SemiMajor_m, 0), 1e-12));
  const Eigen::Vector3d pole = geodetic_to_ecef({90, 0, 100});
  EXPECT_NEAR(pole.z(), kWgs84SemiMajor_m * (1 - kF) + 100, 1e-6);
  EXPECT_NEAR(pole.head<2>().norm(), 0.0, 1e-6);
}

// The worked examples of IOGP/EPSG Guidance Note 7-2 (WGS 84): geographic
// 3D to geocentric (method 9602) and geocentric to topocentric (method 9836).
TEST(Geodesy, PublishedEpsgExamples) {
  const auto dms = [](double d, double m, double s) { return d + m / 60.0 + s / 3600.0; };
  const Geodetic point{dms(53, 48, 33.820), dms(2, 7, 46.380), 73.0};
  const Eigen::Vector3d ecef = geodetic_to_ecef(point);
  EXPECT_NEAR(ecef.x(), 3771793.968, 1e-3);
  EXPECT_NEAR(ecef.y(), 140253.342, 1e-3);
  EXPECT_NEAR(ecef.z(), 5124304.349, 1e-3);
  const Eigen::Vector3d enu = geodetic_to_enu(point, {55.0, 5.0, 200.0});
  EXPECT_NEAR(enu.x(), -189013.869, 1e-3);
  EXPECT_NEAR(enu.y(), -128642.040, 1e-3);
  EXPECT_NEAR(enu.z(), -4220.171, 1e-3);
}

TEST(Geodesy, EcefRoundTrip) {
  for (double lat : {-89.0, -45.5, 0.0, 12.3, 40.821, 89.9}) {
    for (double lon : {-179.0, -20.0, 0.0, 14.7035, 120.0}) {
      for (double alt : {-100.0, 0.0, 8848.0}) {
        const Geodetic g = ecef_to_geodetic(geodetic_to_ecef({lat, lon, alt}));
        EXPECT_NEAR(g.latitude_deg, lat, 1e-9);
        EXPECT_NEAR(g.longitude_deg, lon, 1e-9);
        EXPECT_NEAR(g.altitude_m, alt, 1e-5);
      }
    }
  }
}

TEST(Geodesy, SmallOffsetsMatchTheRadiiOfCurvature) {
  const Geodetic origin{40.821, 14.7035, 0};
  const double phi = origin.latitude_deg * kDeg;
  const double e2 = kF * (2 - kF);
  const double w = std::sqrt(1 - e2 * std::sin(phi) * std::sin(phi));
  const double meridian = kWgs84SemiMajor_m * (1 - e2) / (w * w * w);  // north-south radius
  const double normal = kWgs84SemiMajor_m / w;                         // east-west radius (times cos phi)
  const double d = 1e-4;                                // degrees: ~11 m, curvature negligible
  const Eigen::Vector3d north = geodetic_to_enu({origin.latitude_deg + d, origin.longitude_deg, 0}, origin);
  EXPECT_NEAR(north.y(), meridian * d * kDeg, 1e-3);
  EXPECT_NEAR(north.x(), 0.0, 1e-9);
  const Eigen::Vector3d east = geodetic_to_enu({origin.latitude_deg, origin.longitude_deg + d, 0}, origin);
  // The proper cos(latitude) factor that seed 001 left out.
  EXPECT_NEAR(east.x(), normal * std::cos(phi) * d * kDeg, 1e-3);
  EXPECT_NEAR(geodetic_to_enu({origin.latitude_deg, origin.longitude_deg, 25}, origin).z(), 25.0, 1e-6);
}

TEST(Geodesy, EnuRoundTrip) {
  const Geodetic origin{40.821, 14.7035, 30};
  for (const Eigen::Vector3d enu : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(150, -20, 42),
                                    Eigen::Vector3d(-5000, 12000, -3)}) {
    const Eigen::Vector3d back = geodetic_to_enu(enu_to_geodetic(enu, origin), origin);
    EXPECT_NEAR((back - enu).norm(), 0.0, 1e-6);
  }
}

// Seed 001's conversion (001 §4.2.3): one degree is R pi / 180 = 111194.93 m
// on the sphere of 6371000 m, along a meridian and, without cos(latitude),
// along a parallel too.
TEST(Geodesy, SphereWithoutCosLatitudeIsSeed001sConversion) {
  const Geodetic origin{40.82233, 14.70328, 10.0};
  const Eigen::Vector3d one_degree = geodetic_to_sphere_no_coslat({41.82233, 15.70328, 25.0}, origin);
  EXPECT_NEAR(one_degree.x(), 111194.9266, 1e-4);
  EXPECT_NEAR(one_degree.y(), 111194.9266, 1e-4);
  EXPECT_DOUBLE_EQ(one_degree.z(), 15.0);
  // 001's own node indices, cooy = round(deg2rad(lat_ref - lat) R / 1.5) and
  // coox = round(deg2rad(lon - lon_ref) R / 1.5), of Tabella 5.2's first
  // waypoint (40.8210, 14.7035): 99 cells south (147.89 m), 16 east (24.46 m).
  const Eigen::Vector3d first = geodetic_to_sphere_no_coslat({40.8210, 14.7035, 0.0}, origin);
  EXPECT_NEAR(first.x(), 24.4629, 1e-4);
  EXPECT_NEAR(first.y(), -147.8893, 1e-4);
  EXPECT_EQ(std::lround(first.x() / 1.5), 16);
  EXPECT_EQ(std::lround(-first.y() / 1.5), 99);
  // WGS84 ENU puts the same point 5.90 m further west (cos 40.82 deg = 0.757) and 0.19 m further north.
  const Eigen::Vector3d enu = geodetic_to_enu({40.8210, 14.7035, 10.0}, origin);
  EXPECT_NEAR(first.x() - enu.x(), 5.90, 0.01);
  EXPECT_NEAR(first.y() - enu.y(), -0.19, 0.01);
}

}  // namespace
}  // namespace campo
