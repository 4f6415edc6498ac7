#pragma once
/// Terrain from a digital elevation model: a GeoTIFF, or any raster GDAL
/// reads. Its geotransform and coordinate reference system (CRS) are read, an
/// area is cropped and resampled (bilinear) to a spacing in metres, nodata
/// cells are refused or filled. GDAL is loaded with dlopen on first use, so a
/// process that reads no DEM never maps it. Failures throw std::runtime_error
/// naming the DEM file (the loader adds the scene file and JSON pointer).
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "campo/config_fields.hpp"
#include "campo/scene.hpp"

namespace campo {

/// Which part of the raster becomes the grid, and in which frame (docs/scene-format.md, "heightfield").
enum class DemCropForm : std::uint8_t {
  whole,            ///< no crop: the whole raster
  lat_long_box,     ///< {south_deg, west_deg, north_deg, east_deg}: WGS84; grid on east-north axes
  lat_long_centre,  ///< {center_deg: [lat, lon], size_m: [x, y]}: WGS84; grid on east-north axes
  projected_box,    ///< {min_x, min_y, max_x, max_y}: the file's CRS units; grid on the file's axes
};

/// The "crop" of a DEM heightfield; only the members of `form` are meaningful.
struct DemCrop {
  DemCropForm form = DemCropForm::whole;
  double south_deg = 0.0;   ///< lat_long_box, [-90, 90], < north_deg
  double west_deg = 0.0;    ///< lat_long_box, [-180, 180], < east_deg (no antimeridian crossing)
  double north_deg = 0.0;
  double east_deg = 0.0;
  double centre_latitude_deg = 0.0;    ///< lat_long_centre, [-90, 90]
  double centre_longitude_deg = 0.0;   ///< lat_long_centre, [-180, 180]
  Eigen::Vector2d size_m{0.0, 0.0};    ///< lat_long_centre: east-west and north-south extent, > 0
  double min_x = 0.0;  ///< projected_box, the file's CRS units (metres for UTM), min < max
  double min_y = 0.0;
  double max_x = 0.0;
  double max_y = 0.0;
};

/// What a nodata cell among those the grid reads does.
enum class DemNodata : std::uint8_t {
  refuse,  ///< the file is refused, naming how many and the first (default)
  fill,    ///< filled from the valid cells around it (heightgrid_from_dem)
};

/// The keys of a "dem" heightfield besides "dem" itself.
struct DemOptions {
  int band = 1;                          ///< raster band of the heights, 1-based
  DemNodata nodata = DemNodata::refuse;
  double spacing_m = 0.0;                ///< vertex spacing, [0, 1e6); 0: the file's pixel size
  DemCrop crop;
};

/// The declared keys of DemOptions ("band", "nodata", "spacing_m", "crop").
const ConfigFields<DemOptions>& dem_fields();

/// What kind of coordinate reference system the file declares.
enum class DemCrs : std::uint8_t {
  none,        ///< no CRS (or a local one): coordinates taken as metres, no geodetic position
  projected,   ///< e.g. UTM: linear units
  geographic,  ///< e.g. EPSG:4326: degrees of latitude and longitude
};

/// A DEM as a heightfield grid, and what was read to make it.
struct DemTerrain {
  HeightGrid grid;                       ///< row 0 south, column 0 west; centred on the crop's centre
  std::array<double, 6> geotransform{};  ///< GDAL's: x0, dx, 0, y0, 0, dy (pixel corners)
  int raster_cols = 0;                   ///< the file's size in pixels
  int raster_rows = 0;
  DemCrs crs = DemCrs::none;
  std::string crs_wkt;                   ///< the file's CRS as WKT; empty when none
  int epsg = 0;                          ///< the CRS's EPSG code when one is identified, else 0
  double metres_per_unit = 1.0;          ///< linear unit of a projected (or absent) CRS
  /// true: the grid's x, y are east and north in metres on the tangent plane
  /// at the centre (lat/long crops, geographic files); false: the file's own
  /// axes (x = easting, y = northing, in metres), no reprojection.
  bool east_north_axes = false;
  std::optional<double> nodata_value;    ///< the band's nodata value, if it declares one
  long filled_cells = 0;                 ///< nodata cells filled ("nodata": "fill")
  /// WGS84 latitude and longitude of the grid's centre (when crs != none).
  std::optional<Eigen::Vector2d> centre_lat_lon_deg;
};

/// The heightfield of `path` under `options` (docs/scene-format.md, "heightfield", "dem"):
///  - whole raster at the file's spacing (spacing_m 0) of a projected or
///    CRS-less file: the raster's pixels are the grid's vertices, unchanged
///    (first raster row = northern edge for a north-up file), spacing = pixel
///    size in metres;
///  - otherwise a grid of about `spacing_m` (default: the pixel size in
///    metres) over the crop, each vertex a bilinear interpolation of the four
///    pixel centres around it; on east-north axes (tangent plane at the
///    crop's centre) for lat/long crops and geographic files, on the file's
///    axes otherwise.
/// Heights: the band's values times its scale plus offset, in metres (a band
/// unit of feet is converted). Nodata cells among those read are refused or
/// filled (DemNodata); a non-finite height is always refused. The raster read
/// (and the grid) hold at most kMaxHeightfieldVertices cells, checked before reading.
DemTerrain heightgrid_from_dem(const std::filesystem::path& path, const DemOptions& options);

}  // namespace campo
