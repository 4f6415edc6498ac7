// Heightfields from digital elevation models (scene/dem_source, the loader's
// "dem" heightfield): GeoTIFFs written here from ASCII grids with GDAL's
// gdal_translate (Debian gdal-bin, tools/setup.sh --tests), checked against a CSV of
// the same heights, hand-computed bilinear values, a meridian-arc inversion
// of UTM northings, and the limits on hostile files.
#include "scene/dem_source.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/scene_loader.hpp"
#include "scene/heightfield_sources.hpp"
#include "tests/test_units.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using namespace campo::test_units;
constexpr double kA = 6378137.0;                 // WGS84 semi-major axis, m
constexpr double kE2 = 0.00669437999014132;      // WGS84 first eccentricity squared

// Heights of a 5 x 4 grid (first line north), with decimals no float holds exactly.
const char* const kHeights5x4[] = {"101.25 102.7 103.33 99.1 98.05", "100.0 101.5 104.8 97.6 96.123",
                                   "99.9 100.01 102.2 96.0 95.5", "98.7 99.4 100.6 95.05 94.2"};

class DemSource : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("campo_dem_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }

  // A GeoTIFF of `type` from an ASCII grid (AAIGrid) with the CRS `srs` ("" for none).
  fs::path geotiff(const std::string& name, const std::string& ascii_grid, const std::string& srs,
                   const std::string& type = "Float64") const {
    const fs::path asc = write(name + ".asc", ascii_grid);
    const fs::path tif = dir_ / (name + ".tif");
    const std::string command = "gdal_translate -q -of GTiff -oo DATATYPE=Float64 -ot " + type +
                                (srs.empty() ? "" : " -a_srs " + srs) + " '" + asc.string() + "' '" + tif.string() +
                                "'";
    if (std::system(command.c_str()) != 0) throw std::runtime_error("failed: " + command + " (is gdal-bin installed?)");
    fs::remove(asc);
    return tif;
  }

  fs::path grid_5x4(const std::string& srs) const {
    std::string text = "ncols 5\nnrows 4\nxllcorner 438000\nyllcorner 4522000\ncellsize 2.5\n";
    for (const char* line : kHeights5x4) text += std::string(line) + "\n";
    return geotiff("grid", text, srs);
  }

  // The scene file `name` holding `objects` (and `world` if given), loaded.
  Scene load(const std::string& objects, const std::string& world = "") const {
    const fs::path path = write("scene.json", "{\"campo_scene\": 1, " +
                                                  (world.empty() ? "" : "\"world\": " + world + ", ") +
                                                  "\"objects\": [" + objects + "]}");
    return load_scene(path);
  }
  std::string load_error(const std::string& objects, const std::string& world = "") const {
    try {
      load(objects, world);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

std::string dem_error_of(const fs::path& path, const DemOptions& options = {}) {
  try {
    heightgrid_from_dem(path, options);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

// Latitude whose UTM northing on the central meridian is `northing_m`:
// k0 times the meridian arc, integrated here (Simpson) and inverted by bisection.
double utm_central_meridian_latitude_deg(double northing_m) {
  const auto arc = [](double phi) {
    const int n = 4000;
    const auto m = [](double p) { return kA * (1 - kE2) / std::pow(1 - kE2 * std::sin(p) * std::sin(p), 1.5); };
    double sum = m(0) + m(phi);
    for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * m(phi * i / n);
    return sum * phi / n / 3;
  };
  double lo = 0.0, hi = 89.0 * kDeg;
  for (int i = 0; i < 80; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.9996 * arc(mid) < northing_m ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi) / kDeg;
}

// --- the same terrain as a CSV -----------------------------------------------------------

TEST_F(DemSource, WholeRasterIsTheCsvOfTheSameHeightsToTheFloat) {
  std::string csv;
  for (const char* line : kHeights5x4) {
    std::string row(line);
    for (char& c : row) c = c == ' ' ? ',' : c;
    csv += row + "\n";
  }
  const HeightGrid from_csv = heightgrid_from_csv(write("grid.csv", csv), 2.5);
  for (const std::string srs : {"EPSG:32633", ""}) {
    const DemTerrain dem = heightgrid_from_dem(grid_5x4(srs), {});
    EXPECT_EQ(dem.grid.cols, from_csv.cols);
    EXPECT_EQ(dem.grid.rows, from_csv.rows);
    EXPECT_EQ(dem.grid.spacing_x_m, from_csv.spacing_x_m);
    EXPECT_EQ(dem.grid.spacing_y_m, from_csv.spacing_y_m);
    EXPECT_EQ(dem.grid.heights_m, from_csv.heights_m) << srs;
    // Row 0 is the south edge (the file's last line), column 0 the west.
    EXPECT_EQ(dem.grid.at(0, 0), 98.7);
    EXPECT_EQ(dem.grid.at(4, 3), 98.05);
    EXPECT_FALSE(dem.east_north_axes);
    EXPECT_EQ(dem.raster_cols, 5);
    EXPECT_EQ(dem.geotransform[1], 2.5);
  }
  // What the file declares.
  const DemTerrain utm = heightgrid_from_dem(grid_5x4("EPSG:32633"), {});
  EXPECT_EQ(utm.crs, DemCrs::projected);
  EXPECT_EQ(utm.epsg, 32633);
  EXPECT_THAT(utm.crs_wkt, HasSubstr("UTM zone 33N"));
  EXPECT_EQ(utm.metres_per_unit, 1.0);
  EXPECT_FALSE(utm.nodata_value.has_value());
}

TEST_F(DemSource, LoadedLikeAnyHeightfieldCentredOnItsPose) {
  std::string csv;
  for (const char* line : kHeights5x4) {
    std::string row(line);
    for (char& c : row) c = c == ' ' ? ',' : c;
    csv += row + "\n";
  }
  write("grid.csv", csv);
  grid_5x4("");
  const std::string pose = R"("pose": {"position_m": [3, -2, 1.5], "rpy_deg": [0, 0, 30]})";
  const Scene from_csv = load(R"({"alias": "t", "type": "heightfield", "csv": "grid.csv", "spacing_m": 2.5, )" + pose + "}");
  const Scene from_dem = load(R"({"alias": "t", "type": "heightfield", "dem": "grid.tif", )" + pose + "}");
  ASSERT_EQ(from_dem.shapes.size(), 1u);
  EXPECT_EQ(from_dem.shapes[0].terrain->heights_m, from_csv.shapes[0].terrain->heights_m);
  EXPECT_EQ(from_dem.shapes[0].terrain->cols, from_csv.shapes[0].terrain->cols);
  EXPECT_EQ(from_dem.shapes[0].terrain->spacing_x_m, from_csv.shapes[0].terrain->spacing_x_m);
  EXPECT_TRUE(from_dem.shapes[0].pose.isApprox(from_csv.shapes[0].pose, 0.0));
  // A file without a CRS leaves the geo reference alone.
  EXPECT_EQ(from_dem.world.geo_reference.latitude_deg, 0.0);
  EXPECT_EQ(from_dem.world.geo_reference.longitude_deg, 0.0);
}

// --- projected CRS: UTM 33N on its central meridian ----------------------------------------

// 6 x 5 pixels of 10 m, pixel centres at eastings 499975 ... 500025 and
// northings 4522020 (first row) ... 4521980; height = col² + 10 row.
std::string utm_6x5() {
  std::string text = "ncols 6\nnrows 5\nxllcorner 499970\nyllcorner 4521975\ncellsize 10\n";
  for (int row = 0; row < 5; ++row) {
    for (int col = 0; col < 6; ++col) text += std::to_string(col * col + 10 * row) + (col < 5 ? " " : "\n");
  }
  return text;
}

TEST_F(DemSource, ProjectedCropLandsWhereHandComputed) {
  const fs::path tif = geotiff("utm", utm_6x5(), "EPSG:32633");
  DemOptions options;
  options.spacing_m = 7.5;
  options.crop.form = DemCropForm::projected_box;
  options.crop.min_x = 499985;
  options.crop.max_x = 500015;
  options.crop.min_y = 4521985;
  options.crop.max_y = 4522015;
  const DemTerrain dem = heightgrid_from_dem(tif, options);
  ASSERT_EQ(dem.grid.cols, 5);
  ASSERT_EQ(dem.grid.rows, 5);
  EXPECT_EQ(dem.grid.spacing_x_m, 7.5);
  EXPECT_FALSE(dem.east_north_axes);
  // South-west vertex (499985, 4521985): pixel column 1, between rows 3 and 4: (31 + 41) / 2.
  EXPECT_NEAR(dem.grid.at(0, 0), 36.0, 1e-12);
  // (499992.5, 4522000): row 2, a quarter of the way from column 2 back to 1... 21 + 0.75 (24 - 21).
  EXPECT_NEAR(dem.grid.at(1, 2), 23.25, 1e-12);
  // (500007.5, 4522007.5): column 3.25, row 1.25: rows 20.75 and 30.75, a quarter between.
  EXPECT_NEAR(dem.grid.at(3, 3), 23.25, 1e-12);
  // North-east vertex (500015, 4522015): column 4, halfway between rows 0 and 1: (16 + 26) / 2.
  EXPECT_NEAR(dem.grid.at(4, 4), 21.0, 1e-12);
  // The centre (500000, 4522000) on the central meridian: longitude 15, latitude from the meridian arc.
  ASSERT_TRUE(dem.centre_lat_lon_deg);
  EXPECT_NEAR(dem.centre_lat_lon_deg->y(), 15.0, 1e-9);
  EXPECT_NEAR(dem.centre_lat_lon_deg->x(), utm_central_meridian_latitude_deg(4522000.0), 1e-7);
}

TEST_F(DemSource, ProjectedCropFillsTheGeoReferenceSoGeodeticWaypointsLandOnIt) {
  geotiff("utm", utm_6x5(), "EPSG:32633");
  const double latitude = utm_central_meridian_latitude_deg(4522000.0);
  char waypoint[160];
  std::snprintf(waypoint, sizeof waypoint, R"({"geodetic": [%.12f, 15.0], "agl_m": 10})", latitude);
  const Scene scene = load(
      R"({"alias": "t", "type": "heightfield", "dem": "utm.tif", "spacing_m": 7.5,
          "crop": {"min_x": 499985, "min_y": 4521985, "max_x": 500015, "max_y": 4522015},
          "pose": {"position_m": [40, 50, 2]}},
         {"alias": "d", "type": "quadrotor", "pose": {"position_m": [40, 50, 40]}, "planner": {"name": "straight"},
          "mission": {"waypoints": [)" + std::string(waypoint) + "]}}");
  const GeoReference& ref = scene.world.geo_reference;
  EXPECT_NEAR(ref.latitude_deg, latitude, 1e-7);
  EXPECT_NEAR(ref.longitude_deg, 15.0, 1e-7);
  EXPECT_EQ(ref.altitude_m, -2.0);
  EXPECT_EQ(ref.position_m, Eigen::Vector2d(40, 50));
  EXPECT_EQ(ref.projection, GeoProjection::wgs84_enu);
  // The waypoint over the crop's centre: (500000, 4522000) is column 2.5 of row 2: (24 + 29) / 2 = 26.5 m,
  // plus the pose's 2 m and 10 m above ground.
  const Eigen::Vector3d& p = scene.vehicles.at(0).mission.at(0).position_m;
  EXPECT_NEAR(p.x(), 40.0, 1e-6);
  EXPECT_NEAR(p.y(), 50.0, 1e-6);
  EXPECT_NEAR(p.z(), 26.5 + 2.0 + 10.0, 1e-6);
}

// --- geographic CRS (EPSG:4326) -----------------------------------------------------------

// 5 x 5 pixels of 0.001°, pixel centres at longitudes 14.2685 ... 14.2725 and
// latitudes 40.8525 (first row) ... 40.8485; height = 50 + 2 col² + 3 row² - col row.
double wgs84_height(int col, int row) { return 50.0 + 2.0 * col * col + 3.0 * row * row - col * row; }
std::string wgs84_5x5() {
  std::string text = "ncols 5\nnrows 5\nxllcorner 14.268\nyllcorner 40.848\ncellsize 0.001\n";
  for (int row = 0; row < 5; ++row) {
    for (int col = 0; col < 5; ++col) text += std::to_string(wgs84_height(col, row)) + (col < 4 ? " " : "\n");
  }
  return text;
}

// Bilinear interpolation of wgs84_height at a latitude and longitude.
double wgs84_bilinear(double latitude_deg, double longitude_deg) {
  const double px = (longitude_deg - 14.268) / 0.001 - 0.5, py = (40.853 - latitude_deg) / 0.001 - 0.5;
  const int c = static_cast<int>(std::floor(px)), r = static_cast<int>(std::floor(py));
  const double fx = px - c, fy = py - r;
  return (1 - fy) * ((1 - fx) * wgs84_height(c, r) + fx * wgs84_height(c + 1, r)) +
         fy * ((1 - fx) * wgs84_height(c, r + 1) + fx * wgs84_height(c + 1, r + 1));
}

TEST_F(DemSource, GeographicCropIsResampledOnEastNorthAxesAtTheSpacing) {
  const fs::path tif = geotiff("wgs84", wgs84_5x5(), "EPSG:4326");
  DemOptions options;
  options.spacing_m = 50.0;
  options.crop.form = DemCropForm::lat_long_centre;
  options.crop.centre_latitude_deg = 40.8506;
  options.crop.centre_longitude_deg = 14.2702;
  options.crop.size_m = {100.0, 100.0};
  const DemTerrain dem = heightgrid_from_dem(tif, options);
  EXPECT_EQ(dem.crs, DemCrs::geographic);
  EXPECT_EQ(dem.epsg, 4326);
  EXPECT_TRUE(dem.east_north_axes);
  ASSERT_EQ(dem.grid.cols, 3);
  ASSERT_EQ(dem.grid.rows, 3);
  EXPECT_EQ(dem.grid.spacing_x_m, 50.0);
  EXPECT_EQ(dem.grid.spacing_y_m, 50.0);
  // The centre vertex at the crop's centre: pixel (1.7, 1.9); rows 1 and 2 give
  // 54 + 0.7 (59 - 54) = 57.5 and 62 + 0.7 (66 - 62) = 64.8; 57.5 + 0.9 (64.8 - 57.5) = 64.07.
  EXPECT_NEAR(dem.grid.at(1, 1), 64.07, 1e-9);
  // Off-centre vertices: 50 m east is 50 / (N cos(lat)) radians of longitude, 50 m north
  // 50 / M radians of latitude (N, M: the ellipsoid's radii of curvature; the tangent
  // plane departs from the ellipsoid by under a millimetre here).
  const double lat = 40.8506 * kDeg;
  const double w = 1 - kE2 * std::sin(lat) * std::sin(lat);
  const double n = kA / std::sqrt(w), m = kA * (1 - kE2) / std::pow(w, 1.5);
  const double east_deg = 50.0 / (n * std::cos(lat)) / kDeg, north_deg = 50.0 / m / kDeg;
  EXPECT_NEAR(dem.grid.at(2, 1), wgs84_bilinear(40.8506, 14.2702 + east_deg), 1e-4);
  EXPECT_NEAR(dem.grid.at(1, 2), wgs84_bilinear(40.8506 + north_deg, 14.2702), 1e-4);
  EXPECT_NEAR(dem.grid.at(0, 0), wgs84_bilinear(40.8506 - north_deg, 14.2702 - east_deg), 1e-3);
  EXPECT_NEAR(dem.centre_lat_lon_deg->x(), 40.8506, 1e-12);
  EXPECT_NEAR(dem.centre_lat_lon_deg->y(), 14.2702, 1e-12);
}

TEST_F(DemSource, GeographicBoxCropSpansTheBoxThroughItsEdgeMidpoints) {
  const fs::path tif = geotiff("wgs84", wgs84_5x5(), "EPSG:4326");
  DemOptions options;
  options.spacing_m = 12.6;  // 20 x 26 cells: a vertex at the centre
  options.crop = {DemCropForm::lat_long_box, 40.849, 14.269, 40.852, 14.272};
  const DemTerrain dem = heightgrid_from_dem(tif, options);
  const double lat = 40.8505 * kDeg, w = 1 - kE2 * std::sin(lat) * std::sin(lat);
  const double width = 0.003 * kDeg * kA / std::sqrt(w) * std::cos(lat);
  const double height = 0.003 * kDeg * kA * (1 - kE2) / std::pow(w, 1.5);
  // Whole cells of about 12.6 m spanning the box's width and height (to within the arc's curvature).
  EXPECT_NEAR(dem.grid.size_x_m(), width, 0.01);
  EXPECT_NEAR(dem.grid.size_y_m(), height, 0.01);
  ASSERT_EQ(dem.grid.cols, 21);
  ASSERT_EQ(dem.grid.rows, 27);
  EXPECT_NEAR(dem.grid.at(10, 13), wgs84_bilinear(40.8505, 14.2705), 1e-9);
}

TEST_F(DemSource, WholeGeographicRasterFillsTheGeoReferenceWithItsCentre) {
  geotiff("wgs84", wgs84_5x5(), "EPSG:4326");
  const Scene scene = load(R"({"alias": "t", "type": "heightfield", "dem": "wgs84.tif", "spacing_m": 28})");
  EXPECT_NEAR(scene.world.geo_reference.latitude_deg, 40.8505, 1e-7);
  EXPECT_NEAR(scene.world.geo_reference.longitude_deg, 14.2705, 1e-7);
  EXPECT_EQ(scene.world.geo_reference.altitude_m, 0.0);
  const HeightGrid& grid = *scene.shapes.at(0).terrain;
  // Within the pixel centres: 4 pixels of 0.001° are 337 m east-west and 444 m north-south here.
  EXPECT_GT(grid.size_x_m(), 330.0);
  EXPECT_LT(grid.size_x_m(), 338.0);
  EXPECT_GT(grid.size_y_m(), 440.0);
  EXPECT_LT(grid.size_y_m(), 445.0);
  // 12 x 16 cells of about 28 m: the centre vertex is the raster's centre.
  ASSERT_EQ(grid.cols, 13);
  ASSERT_EQ(grid.rows, 17);
  EXPECT_NEAR(grid.at(6, 8), wgs84_bilinear(40.8505, 14.2705), 1e-9);
}

TEST_F(DemSource, TheScenesGeoReferencePlacesTheDem) {
  geotiff("wgs84", wgs84_5x5(), "EPSG:4326");
  const std::string world =
      R"({"geo_reference": {"latitude_deg": 40.8505, "longitude_deg": 14.2695, "altitude_m": 5, "position_m": [10, 20]}})";
  const Scene scene = load(R"({"alias": "t", "type": "heightfield", "dem": "wgs84.tif", "spacing_m": 20})", world);
  // The DEM's centre is 0.001° east of the reference: N cos(lat) 0.001° = 84.3 m.
  const double lat = 40.8505 * kDeg;
  const double east = kA / std::sqrt(1 - kE2 * std::sin(lat) * std::sin(lat)) * std::cos(lat) * 0.001 * kDeg;
  const Eigen::Vector3d t = scene.shapes.at(0).pose.translation();
  EXPECT_NEAR(t.x(), 10.0 + east, 1e-3);
  EXPECT_NEAR(t.y(), 20.0, 1e-3);
  EXPECT_NEAR(t.z(), -5.0, 1e-3);
  EXPECT_EQ(scene.world.geo_reference.latitude_deg, 40.8505);  // the scene's, untouched
  // It is placed by the reference, so it takes no pose; nor a seed-001 projection.
  EXPECT_THAT(load_error(R"({"alias": "t", "type": "heightfield", "dem": "wgs84.tif", "pose": {"position_m": [1, 0, 0]}})",
                         world),
              HasSubstr("/objects/0/pose (t): expected no pose: the world's geo_reference places a DEM"));
  EXPECT_THAT(load_error(R"({"alias": "t", "type": "heightfield", "dem": "wgs84.tif"})",
                         R"({"geo_reference": {"latitude_deg": 40.85, "longitude_deg": 14.27, "projection": "sphere_no_coslat"}})"),
              HasSubstr("/objects/0/dem (t): expected a geo_reference with projection \"wgs84_enu\""));
  // A second DEM is placed by the reference the first one filled.
  const Scene two = load(R"({"alias": "a", "type": "heightfield", "dem": "wgs84.tif", "spacing_m": 20},
                             {"alias": "b", "type": "heightfield", "dem": "wgs84.tif", "spacing_m": 20})");
  EXPECT_NEAR((two.shapes.at(1).pose.translation() - two.shapes.at(0).pose.translation()).norm(), 0.0, 1e-6);
  EXPECT_THAT(load_error(R"({"alias": "a", "type": "heightfield", "dem": "wgs84.tif", "spacing_m": 20},
                             {"alias": "b", "type": "heightfield", "dem": "wgs84.tif", "pose": {"position_m": [1, 0, 0]}})"),
              HasSubstr("the geo_reference filled from the DEM at /objects/0 places"));
}

// --- nodata --------------------------------------------------------------------------------

// 4 x 4 with nodata -9999 at `holes` (file column, row pairs).
std::string grid_with_holes(const std::vector<std::pair<int, int>>& holes) {
  std::string text = "ncols 4\nnrows 4\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -9999\n";
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < 4; ++col) {
      const bool hole = std::find(holes.begin(), holes.end(), std::pair{col, row}) != holes.end();
      text += (hole ? std::string("-9999") : std::to_string(10 * row + col)) + (col < 3 ? " " : "\n");
    }
  }
  return text;
}

TEST_F(DemSource, NodataIsRefusedByDefaultNamingTheCountAndTheFirstCell) {
  const fs::path tif = geotiff("holes", grid_with_holes({{2, 1}, {1, 3}}), "EPSG:32633", "Float32");
  const std::string error = dem_error_of(tif);
  EXPECT_THAT(error, HasSubstr("holes.tif"));
  EXPECT_THAT(error, HasSubstr("2 nodata cells (value -9999) among the 16 read, the first at pixel (column 2, row 1)"));
  EXPECT_THAT(error, HasSubstr("\"nodata\": \"fill\""));
}

TEST_F(DemSource, NodataFillTakesTheMeanOfTheValidNeighboursRingByRing) {
  // Two holes side by side at (1, 1) and (2, 1): each is next to valid cells, so both
  // are in the first ring and take the mean of their valid neighbours only.
  const fs::path tif = geotiff("holes", grid_with_holes({{1, 1}, {2, 1}}), "", "Float32");
  DemOptions options;
  options.nodata = DemNodata::fill;
  const DemTerrain dem = heightgrid_from_dem(tif, options);
  EXPECT_EQ(dem.filled_cells, 2);
  EXPECT_EQ(dem.nodata_value, -9999.0);
  // Grid row 2 is file row 1. (1, 1): neighbours 0, 1, 2, 10, 20, 21, 22 -> 76 / 7;
  // (2, 1): 1, 2, 3, 13, 21, 22, 23 -> 85 / 7.
  EXPECT_NEAR(dem.grid.at(1, 2), 76.0 / 7.0, 1e-12);
  EXPECT_NEAR(dem.grid.at(2, 2), 85.0 / 7.0, 1e-12);
  EXPECT_EQ(dem.grid.at(3, 2), 13.0);

  // A 2 x 2 hole in the corner fills from its rim inwards: (0, 0) is the second ring.
  const fs::path corner = geotiff("corner", grid_with_holes({{0, 0}, {1, 0}, {0, 1}, {1, 1}}), "", "Float32");
  const DemTerrain filled = heightgrid_from_dem(corner, options);
  // First ring: (1, 0) from 2, 12 -> 7; (0, 1) from 20, 21 -> 20.5; (1, 1) from 2, 12, 20, 21, 22 -> 15.4.
  const double a = 7.0, b = 20.5, c = 15.4;
  EXPECT_NEAR(filled.grid.at(1, 3), a, 1e-12);
  EXPECT_NEAR(filled.grid.at(0, 2), b, 1e-12);
  EXPECT_NEAR(filled.grid.at(1, 2), c, 1e-12);
  EXPECT_NEAR(filled.grid.at(0, 3), (a + b + c) / 3.0, 1e-12);

  // Nothing valid to fill from.
  const fs::path empty =
      geotiff("empty", grid_with_holes({{0, 0}, {1, 0}, {2, 0}, {3, 0}, {0, 1}, {1, 1}, {2, 1}, {3, 1}, {0, 2},
                                        {1, 2}, {2, 2}, {3, 2}, {0, 3}, {1, 3}, {2, 3}, {3, 3}}),
              "", "Float32");
  EXPECT_THAT(dem_error_of(empty, options), HasSubstr("every one of the 16 cells read is nodata"));
}

TEST_F(DemSource, ACropReadsOnlyTheCellsItNeedsSoNodataElsewhereDoesNotMatter) {
  // A hole at file (3, 0), the north-east corner; a crop of the south-west 2 x 2 pixels never reads it.
  const fs::path tif = geotiff("holes", grid_with_holes({{3, 0}}), "EPSG:32633", "Float32");
  DemOptions options;
  options.crop.form = DemCropForm::projected_box;
  options.crop.min_x = 0.5;
  options.crop.min_y = 0.5;
  options.crop.max_x = 1.5;
  options.crop.max_y = 1.5;
  const DemTerrain dem = heightgrid_from_dem(tif, options);
  ASSERT_EQ(dem.grid.cols, 2);
  EXPECT_EQ(dem.grid.at(0, 0), 30.0);  // file row 3, column 0
  EXPECT_EQ(dem.grid.at(1, 1), 21.0);
}

// --- errors ----------------------------------------------------------------------------------

TEST_F(DemSource, HostileAndWrongFilesAreRefusedClearly) {
  EXPECT_THAT(dem_error_of(write("text.tif", "elevation 100 m\n")), HasSubstr("not a raster GDAL can read"));

  const fs::path good = grid_5x4("EPSG:32633");
  std::ifstream in(good, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string truncated_error = dem_error_of(write("truncated.tif", bytes.substr(0, bytes.size() - 100)));
  EXPECT_THAT(truncated_error, HasSubstr("truncated.tif"));
  EXPECT_FALSE(truncated_error.empty());

  // A raster declared 100000 x 100000: refused before anything is read.
  const std::string vrt_huge =
      R"(<VRTDataset rasterXSize="100000" rasterYSize="100000"><GeoTransform>0, 1, 0, 0, 0, -1</GeoTransform>
         <VRTRasterBand dataType="Float32" band="1"><SimpleSource><SourceFilename relativeToVRT="1">grid.tif</SourceFilename>
         <SourceBand>1</SourceBand></SimpleSource></VRTRasterBand></VRTDataset>)";
  EXPECT_THAT(dem_error_of(write("huge.vrt", vrt_huge)), HasSubstr("the raster is 100000 x 100000 pixels, more than the limit"));
  DemOptions coarse;
  coarse.spacing_m = 1000.0;
  EXPECT_THAT(dem_error_of(write("huge.vrt", vrt_huge), coarse), HasSubstr("more than the limit of 16777216"));

  const std::string vrt_rotated =
      R"(<VRTDataset rasterXSize="5" rasterYSize="4"><GeoTransform>0, 1, 0.5, 0, 0.25, -1</GeoTransform>
         <VRTRasterBand dataType="Float32" band="1"><SimpleSource><SourceFilename relativeToVRT="1">grid.tif</SourceFilename>
         <SourceBand>1</SourceBand></SimpleSource></VRTRasterBand></VRTDataset>)";
  EXPECT_THAT(dem_error_of(write("rotated.vrt", vrt_rotated)), HasSubstr("a rotated geotransform"));

  DemOptions band2;
  band2.band = 2;
  EXPECT_THAT(dem_error_of(good, band2), HasSubstr("no band 2: the file has 1"));

  DemOptions outside;
  outside.crop = {DemCropForm::lat_long_centre, 0, 0, 0, 0, 40.0, 14.0, {100.0, 100.0}};
  EXPECT_THAT(dem_error_of(good, outside), HasSubstr("the crop reaches outside the raster"));
  EXPECT_THAT(dem_error_of(grid_5x4(""), outside), HasSubstr("no coordinate reference system, so no latitude/longitude crop"));

  const fs::path geographic = geotiff("wgs84", wgs84_5x5(), "EPSG:4326");
  DemOptions projected;
  projected.crop.form = DemCropForm::projected_box;
  projected.crop.max_x = projected.crop.max_y = 1.0;
  EXPECT_THAT(dem_error_of(geographic, projected), HasSubstr("the file's CRS is geographic"));
}

TEST_F(DemSource, NonFiniteHeightsAreRefusedAndABandIsChosen) {
  const fs::path nan = geotiff("nan", "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 nan\n3 4\n", "");
  EXPECT_THAT(dem_error_of(nan), HasSubstr("a height that is not finite (nan) at pixel (column 1, row 0)"));

  // Two bands: the first the 5 x 4 heights, the second a 5 x 4 grid of 7s.
  grid_5x4("EPSG:32633");
  geotiff("sevens",
          "ncols 5\nnrows 4\nxllcorner 438000\nyllcorner 4522000\ncellsize 2.5\n"
          "7 7 7 7 7\n7 7 7 7 7\n7 7 7 7 7\n7 7 7 7 7\n",
          "EPSG:32633");
  const std::string band = R"(<VRTRasterBand dataType="Float64" band="%d"><SimpleSource><SourceFilename relativeToVRT="1">%s</SourceFilename><SourceBand>1</SourceBand></SimpleSource></VRTRasterBand>)";
  char first[400], second[400];
  std::snprintf(first, sizeof first, band.c_str(), 1, "grid.tif");
  std::snprintf(second, sizeof second, band.c_str(), 2, "sevens.tif");
  const fs::path two = write("two.vrt", std::string(R"(<VRTDataset rasterXSize="5" rasterYSize="4">)") +
                                            "<GeoTransform>438000, 2.5, 0, 4522010, 0, -2.5</GeoTransform>" + first +
                                            second + "</VRTDataset>");
  DemOptions options;
  EXPECT_EQ(heightgrid_from_dem(two, options).grid.at(0, 0), 98.7);
  options.band = 2;
  const DemTerrain sevens = heightgrid_from_dem(two, options);
  EXPECT_EQ(sevens.grid.heights_m, std::vector<double>(20, 7.0));
}

TEST_F(DemSource, SceneErrorsNameTheFileAndPointer) {
  grid_5x4("EPSG:32633");
  write("text.tif", "not a raster");
  const std::string scene = (dir_ / "scene.json").string();
  std::string error = load_error(R"({"alias": "t", "type": "heightfield", "dem": "text.tif"})");
  EXPECT_THAT(error, HasSubstr(scene + ":1:70: /objects/0/dem (t): "));
  EXPECT_THAT(error, HasSubstr("text.tif': not a raster GDAL can read"));
  EXPECT_THAT(load_error(R"({"alias": "t", "type": "heightfield", "dem": "missing.tif"})"),
              HasSubstr("/objects/0/dem (t): expected a readable file"));
  EXPECT_THAT(load_error(R"({"alias": "t", "type": "heightfield", "dem": "grid.tif",
                             "crop": {"south_deg": 40, "min_x": 3}})"),
              HasSubstr("/objects/0/crop (t): expected exactly one form of crop"));
  EXPECT_THAT(load_error(R"({"alias": "t", "type": "heightfield", "dem": "grid.tif",
                             "crop": {"south_deg": 40.9, "west_deg": 14, "north_deg": 40.8, "east_deg": 15}})"),
              HasSubstr("/objects/0/crop/north_deg (t): expected a latitude north of \"south_deg\""));
  EXPECT_THAT(load_error(R"({"alias": "t", "type": "heightfield", "dem": "grid.tif", "nodata": "zero"})"),
              HasSubstr("/objects/0/nodata (t): expected one of \"refuse\", \"fill\""));
  EXPECT_THAT(load_error(R"({"alias": "t", "type": "heightfield", "dem": "grid.tif", "csv": "grid.csv"})"),
              HasSubstr("expected exactly one height source: \"expression\", \"csv\", \"png\" or \"dem\""));
  EXPECT_THAT(load_error(R"({"alias": "t", "type": "heightfield", "dem": "grid.tif", "pose": {"rpy_deg": [0, 0, 10]}})"),
              HasSubstr("/objects/0/pose (t): expected a pose without yaw: this DEM fills the world's geo_reference"));
}

// --- the bundled example ------------------------------------------------------------------

const std::string kExampleDem = std::string(CAMPO_SOURCE_DIR) + "/scenes/dem/naples_synthetic_utm33n.tif";

TEST(DemExample, TheBundledFileIsSmallSyntheticUtmWithAVoid) {
  EXPECT_LE(fs::file_size(kExampleDem), 200u * 1024u);
  EXPECT_THAT(dem_error_of(kExampleDem), HasSubstr("nodata cells (value -32768)"));
  DemOptions fill;
  fill.nodata = DemNodata::fill;
  const DemTerrain dem = heightgrid_from_dem(kExampleDem, fill);
  EXPECT_EQ(dem.raster_cols, 256);
  EXPECT_EQ(dem.raster_rows, 256);
  EXPECT_EQ(dem.epsg, 32633);
  EXPECT_EQ(dem.grid.spacing_x_m, 10.0);
  // The void of tools/make_example_dem.py: pixel centres in an ellipse of 30 x 20 m semi-axes at (-420, 260) m.
  // Grid row r is file row 255 - r, so y = (r + 0.5) 10 - 1280.
  long void_cells = 0, odd_heights = 0;
  for (int row = 0; row < 256; ++row) {
    for (int col = 0; col < 256; ++col) {
      const double x = (col + 0.5) * 10 - 1280, y = (row + 0.5) * 10 - 1280;
      const bool in_void = std::pow((x + 420) / 30, 2) + std::pow((y - 260) / 20, 2) <= 1.0;
      void_cells += in_void;
      // Decimetres with band scale 0.1: every height read is a whole number of decimetres.
      const double h = dem.grid.at(col, row);
      odd_heights += !in_void && std::abs(h * 10 - std::round(h * 10)) > 1e-9;
    }
  }
  EXPECT_GT(void_cells, 10);
  EXPECT_EQ(dem.filled_cells, void_cells);
  EXPECT_EQ(odd_heights, 0);
}

TEST(DemExample, TheBundledSceneFillsItsReferenceAndItsWaypointsStandAboveTheTerrain) {
  const Scene scene = load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/dem_terrain.json");
  EXPECT_NEAR(scene.world.geo_reference.latitude_deg, 40.8467, 1e-12);
  EXPECT_NEAR(scene.world.geo_reference.longitude_deg, 14.2645, 1e-12);
  const HeightGrid& grid = *scene.shapes.at(0).terrain;
  EXPECT_EQ(grid.cols, 201);
  EXPECT_EQ(grid.rows, 201);
  EXPECT_EQ(grid.spacing_x_m, 8.0);
  EXPECT_GE(grid.min_height_m(), -0.5);
  EXPECT_LE(grid.max_height_m(), 189.4);
  const auto& mission = scene.vehicles.at(0).mission;
  ASSERT_EQ(mission.size(), 5u);
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector3d& p = mission[i].position_m;
    EXPECT_NEAR(p.z() - scene.ground_height(p.x(), p.y()).value(), 25.0, 1e-9) << i;
  }
  // The third waypoint is the summit of the main hill, about 500 m east and 400 m north of the centre.
  EXPECT_NEAR(mission[2].position_m.x(), 500.0, 1.0);
  EXPECT_NEAR(mission[2].position_m.y(), 400.0, 1.0);
  EXPECT_GT(mission[2].position_m.z() - 25.0, 180.0);
}

TEST(DemExample, CampoRunCompletesTheBundledMission) {
  const fs::path out = fs::temp_directory_path() / "campo_dem_example_run";
  fs::remove_all(out);
  const std::string command = std::string(CAMPO_BINARY) + " run " + CAMPO_SOURCE_DIR + "/scenes/dem_terrain.json --out " +
                              out.string() + " > /dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  std::ifstream in(out / "run.json");
  const nlohmann::json run = nlohmann::json::parse(in);
  EXPECT_EQ(run["metrics"]["outcome"], "reached");
  EXPECT_EQ(run["metrics"]["collisions"], 0);
  fs::remove_all(out);
}

TEST(DemFields, CropRoundTripsThroughWrite) {
  DemOptions options;
  options.crop = {DemCropForm::lat_long_centre, 0, 0, 0, 0, 40.85, 14.27, {800.0, 600.0}};
  options.nodata = DemNodata::fill;
  const nlohmann::json j = dem_fields().write(options);
  DemOptions back;
  dem_fields().read(JsonNode(j, "x.json", ""), back);
  EXPECT_EQ(dem_fields().write(back), j);
  EXPECT_EQ(back.crop.size_m, Eigen::Vector2d(800, 600));
  EXPECT_FALSE(dem_fields().write(DemOptions{}).contains("crop"));
}

}  // namespace
}  // namespace campo
