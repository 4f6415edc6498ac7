#include "scene/dem_source.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <memory>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <dlfcn.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include "scene/generators_grid.hpp"
#include "scene/geodesy.hpp"

namespace campo {

// ---------------------------------------------------------------------------
// The crop's keys: three forms, told apart by their keys.

namespace {

constexpr const char* kCropForms =
    "{\"south_deg\", \"west_deg\", \"north_deg\", \"east_deg\"}, {\"center_deg\": [lat, lon], \"size_m\": [x, y]} "
    "or {\"min_x\", \"min_y\", \"max_x\", \"max_y\"}";

DemCrop read_crop(const JsonNode& node) {
  ObjectReader r(node);
  DemCrop crop;
  const bool box = r.has("south_deg") || r.has("west_deg") || r.has("north_deg") || r.has("east_deg");
  const bool centre = r.has("center_deg") || r.has("size_m");
  const bool projected = r.has("min_x") || r.has("min_y") || r.has("max_x") || r.has("max_y");
  if (static_cast<int>(box) + centre + projected != 1) node.fail("exactly one form of crop: " + std::string(kCropForms));
  const Range latitude = Range::closed(-90.0, 90.0), longitude = Range::closed(-180.0, 180.0);
  if (box) {
    crop.form = DemCropForm::lat_long_box;
    crop.south_deg = r.required("south_deg").as_number(latitude);
    crop.west_deg = r.required("west_deg").as_number(longitude);
    const JsonNode north = r.required("north_deg"), east = r.required("east_deg");
    crop.north_deg = north.as_number(latitude);
    crop.east_deg = east.as_number(longitude);
    if (crop.north_deg <= crop.south_deg) north.fail("a latitude north of \"south_deg\"");
    if (crop.east_deg <= crop.west_deg) east.fail("a longitude east of \"west_deg\" (a crop may not cross 180°)");
  } else if (centre) {
    crop.form = DemCropForm::lat_long_centre;
    const JsonNode at = r.required("center_deg");
    const auto items = at.as_array(2, 2);
    crop.centre_latitude_deg = items[0].as_number(latitude);
    crop.centre_longitude_deg = items[1].as_number(longitude);
    crop.size_m = r.required("size_m").as_vector2(Range{0.0, 1e6, true, false});
  } else {
    crop.form = DemCropForm::projected_box;
    const Range coordinate = Range::closed(-1e12, 1e12);
    crop.min_x = r.required("min_x").as_number(coordinate);
    crop.min_y = r.required("min_y").as_number(coordinate);
    const JsonNode max_x = r.required("max_x"), max_y = r.required("max_y");
    crop.max_x = max_x.as_number(coordinate);
    crop.max_y = max_y.as_number(coordinate);
    if (crop.max_x <= crop.min_x) max_x.fail("a number greater than \"min_x\"");
    if (crop.max_y <= crop.min_y) max_y.fail("a number greater than \"min_y\"");
  }
  r.finish();
  return crop;
}

void write_crop(const DemCrop& crop, nlohmann::json& j) {
  switch (crop.form) {
    case DemCropForm::whole:
      return;
    case DemCropForm::lat_long_box:
      j["crop"] = {{"south_deg", crop.south_deg}, {"west_deg", crop.west_deg},
                   {"north_deg", crop.north_deg}, {"east_deg", crop.east_deg}};
      return;
    case DemCropForm::lat_long_centre:
      j["crop"] = {{"center_deg", {crop.centre_latitude_deg, crop.centre_longitude_deg}},
                   {"size_m", {crop.size_m.x(), crop.size_m.y()}}};
      return;
    case DemCropForm::projected_box:
      j["crop"] = {{"min_x", crop.min_x}, {"min_y", crop.min_y}, {"max_x", crop.max_x}, {"max_y", crop.max_y}};
      return;
  }
}

}  // namespace

const ConfigFields<DemOptions>& dem_fields() {
  using D = DemOptions;
  static const ConfigFields<D> fields =
      ConfigFields<D>()
          .integer("band", &D::band, IntRange{1, 65535}, "", "raster band of the heights (1 = the first)")
          .choice("nodata", &D::nodata, {{"refuse", DemNodata::refuse}, {"fill", DemNodata::fill}},
                  "a nodata cell among those read: refuse the file, or fill the cell from its valid neighbours (below)")
          .number("spacing_m", &D::spacing_m, Range{0.0, 1e6, false, true}, "m",
                  "vertex spacing; 0: the file's pixel size in metres (the smaller side of a pixel)")
          .custom("crop", "", "an object of one of the three forms below",
                  "the area that becomes the terrain; none: the whole raster",
                  [](const JsonNode& node, D& d) { d.crop = read_crop(node); },
                  [](const D& d, nlohmann::json& j) { write_crop(d.crop, j); });
  return fields;
}

// ---------------------------------------------------------------------------
// GDAL, loaded on first use.

namespace {

#define CAMPO_GDAL_FUNCTIONS(X)                                                                        \
  X(GDALAllRegister) X(GDALOpenEx) X(GDALClose) X(GDALGetRasterXSize) X(GDALGetRasterYSize)           \
  X(GDALGetRasterCount) X(GDALGetGeoTransform) X(GDALGetProjectionRef) X(GDALGetRasterBand)           \
  X(GDALGetRasterDataType) X(GDALGetBlockSize) X(GDALGetRasterNoDataValue) X(GDALGetRasterScale)      \
  X(GDALGetRasterOffset) X(GDALGetRasterUnitType) X(GDALRasterIO) X(GDALGetDataTypeName)              \
  X(GDALGetDatasetDriver) X(GDALGetDriverShortName)                                                   \
  X(CPLPushErrorHandler) X(CPLPopErrorHandler) X(CPLQuietErrorHandler) X(CPLErrorReset)               \
  X(CPLGetLastErrorMsg)                                                                               \
  X(OSRNewSpatialReference) X(OSRDestroySpatialReference) X(OSRImportFromEPSG)                        \
  X(OSRSetAxisMappingStrategy) X(OSRIsGeographic) X(OSRIsProjected) X(OSRIsLocal) X(OSRGetLinearUnits)              \
  X(OSRAutoIdentifyEPSG) X(OSRGetAuthorityName) X(OSRGetAuthorityCode)                                \
  X(OCTNewCoordinateTransformation) X(OCTDestroyCoordinateTransformation) X(OCTTransform)

struct GdalApi {
#define CAMPO_GDAL_MEMBER(name) decltype(&::name) name = nullptr;
  CAMPO_GDAL_FUNCTIONS(CAMPO_GDAL_MEMBER)
#undef CAMPO_GDAL_MEMBER
};

GdalApi load_gdal() {
  // Never closed: GDAL's drivers and caches live until the process ends.
  void* const library = dlopen("libgdal.so.32", RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) {
    throw std::runtime_error(std::string("DEM: cannot load GDAL, libgdal.so.32 (Debian libgdal32): ") + dlerror());
  }
  GdalApi api;
  const auto symbol = [library](const char* name) {
    void* const address = dlsym(library, name);
    if (address == nullptr) throw std::runtime_error(std::string("DEM: libgdal.so.32 has no ") + name);
    return address;
  };
#define CAMPO_GDAL_LOAD(name) api.name = reinterpret_cast<decltype(&::name)>(symbol(#name));
  CAMPO_GDAL_FUNCTIONS(CAMPO_GDAL_LOAD)
#undef CAMPO_GDAL_LOAD
  api.GDALAllRegister();
  return api;
}

const GdalApi& gdal() {
  static const GdalApi api = load_gdal();
  return api;
}

std::string dem_number(double value) {
  std::ostringstream out;
  out.precision(12);
  out << value;
  return out.str();
}

// Text from GDAL (its messages quote file contents) as one printable line.
std::string printable(std::string text) {
  for (char& c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) c = ' ';
  }
  if (text.size() > 300) text = text.substr(0, 300) + "...";
  return text;
}

// GDAL's complaints on this thread go to its last-error slot, not to stderr,
// while this lives; fail() throws with the DEM's path and GDAL's last message.
class GdalSession {
 public:
  explicit GdalSession(const std::filesystem::path& path) : api_(gdal()), path_(path.string()) {
    api_.CPLPushErrorHandler(api_.CPLQuietErrorHandler);
    api_.CPLErrorReset();
  }
  ~GdalSession() { api_.CPLPopErrorHandler(); }
  GdalSession(const GdalSession&) = delete;
  GdalSession& operator=(const GdalSession&) = delete;

  const GdalApi& api() const { return api_; }

  /// Our own finding about the file.
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("DEM '" + printable(path_) + "': " + what);
  }
  /// A GDAL call that failed, with GDAL's own last message.
  [[noreturn]] void gdal_failed(const std::string& what) const {
    const char* message = api_.CPLGetLastErrorMsg();
    std::string text = "DEM '" + printable(path_) + "': " + what;
    if (message != nullptr && *message != '\0') text += " (GDAL: " + printable(message) + ")";
    throw std::runtime_error(text);
  }

 private:
  const GdalApi& api_;
  std::string path_;
};

// Owners of GDAL handles.
struct DatasetCloser {
  const GdalApi* api;
  void operator()(void* dataset) const { api->GDALClose(dataset); }
};
struct SrsDestroyer {
  const GdalApi* api;
  void operator()(void* srs) const { api->OSRDestroySpatialReference(srs); }
};
struct TransformDestroyer {
  const GdalApi* api;
  void operator()(void* transform) const { api->OCTDestroyCoordinateTransformation(transform); }
};
using Dataset = std::unique_ptr<void, DatasetCloser>;
using Srs = std::unique_ptr<void, SrsDestroyer>;
using Transform = std::unique_ptr<void, TransformDestroyer>;

// Metres per unit of a band's "unit type" (empty: metres).
std::optional<double> height_unit_metres(std::string unit) {
  std::transform(unit.begin(), unit.end(), unit.begin(), [](unsigned char c) { return std::tolower(c); });
  if (unit.empty() || unit == "m" || unit == "metre" || unit == "meter" || unit == "metres" || unit == "meters") {
    return 1.0;
  }
  if (unit == "ft" || unit == "foot" || unit == "feet" || unit == "international foot") return 0.3048;
  if (unit == "us-ft" || unit == "us survey foot" || unit == "ftus") return 1200.0 / 3937.0;
  return std::nullopt;
}

// The raster's pixel grid as GDAL's geotransform states it (north-up or
// south-up, no rotation): file coordinate <-> continuous pixel coordinate,
// where pixel (i, j)'s centre is at integer (i, j).
struct PixelGrid {
  std::array<double, 6> gt{};
  int cols = 0;
  int rows = 0;
  double pixel_x(double x) const { return (x - gt[0]) / gt[1] - 0.5; }
  double pixel_y(double y) const { return (y - gt[3]) / gt[5] - 0.5; }
  double file_x(double px) const { return gt[0] + (px + 0.5) * gt[1]; }
  double file_y(double py) const { return gt[3] + (py + 0.5) * gt[5]; }
};

// The part of the raster a grid reads: columns [col0, col0 + cols), rows [row0, row0 + rows).
struct Window {
  int col0 = 0;
  int row0 = 0;
  int cols = 0;
  int rows = 0;
};

// How each grid vertex finds its place in the file.
struct GridPlan {
  GridLayout layout;
  bool copy_pixels = false;     // the raster's pixels are the vertices (no resampling)
  bool east_north = false;      // vertices on the tangent plane at `centre` (else the file's axes)
  Geodetic centre;              // east_north: the grid's centre, WGS84
  Eigen::Vector2d centre_file{0.0, 0.0};  // file's axes: the grid's centre in file coordinates
  double metres_per_unit = 1.0;
};

constexpr double kOutsideTolerancePx = 0.5 + 1e-9;  // the outer half pixel is the edge pixel's

class DemReader {
 public:
  DemReader(const std::filesystem::path& path, const DemOptions& options)
      : session_(path), api_(session_.api()), options_(options), path_(path) {}

  DemTerrain read() {
    open(path_);
    read_crs();
    const GridPlan plan = plan_grid();
    terrain_.east_north_axes = plan.east_north;
    if (plan.copy_pixels) {
      copy_raster(plan);
    } else {
      resample(plan);
    }
    return std::move(terrain_);
  }

 private:
  void open(const std::filesystem::path& path) {
    const std::string name = path.string();
    dataset_ = Dataset(api_.GDALOpenEx(name.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr),
                       DatasetCloser{&api_});
    if (!dataset_) session_.gdal_failed("not a raster GDAL can read");
    pixels_.cols = api_.GDALGetRasterXSize(dataset_.get());
    pixels_.rows = api_.GDALGetRasterYSize(dataset_.get());
    terrain_.raster_cols = pixels_.cols;
    terrain_.raster_rows = pixels_.rows;
    const std::string size = std::to_string(pixels_.cols) + " x " + std::to_string(pixels_.rows) + " pixels";
    if (pixels_.cols < 2 || pixels_.rows < 2) session_.fail("the raster is " + size + "; at least 2 x 2 are needed");
    const int bands = api_.GDALGetRasterCount(dataset_.get());
    if (options_.band > bands) {
      session_.fail("no band " + std::to_string(options_.band) + ": the file has " + std::to_string(bands));
    }
    band_ = api_.GDALGetRasterBand(dataset_.get(), options_.band);
    if (band_ == nullptr) session_.gdal_failed("cannot read band " + std::to_string(options_.band));
    data_type_ = api_.GDALGetRasterDataType(band_);
    if (data_type_ == GDT_Unknown || data_type_ == GDT_CInt16 || data_type_ == GDT_CInt32 ||
        data_type_ == GDT_CFloat32 || data_type_ == GDT_CFloat64) {
      const char* type = api_.GDALGetDataTypeName(data_type_);
      session_.fail(std::string("band of type ") + (type ? type : "unknown") + "; heights must be real numbers");
    }
    // GDAL reads whole blocks: a block beyond the cell limit would be allocated whatever the crop.
    int block_x = 0, block_y = 0;
    api_.GDALGetBlockSize(band_, &block_x, &block_y);
    if (static_cast<double>(block_x) * block_y > static_cast<double>(kMaxHeightfieldVertices)) {
      session_.fail("blocks of " + std::to_string(block_x) + " x " + std::to_string(block_y) +
                    " pixels, more than the limit of " + std::to_string(kMaxHeightfieldVertices) + " cells per read");
    }
    if (api_.GDALGetGeoTransform(dataset_.get(), pixels_.gt.data()) != CE_None) {
      session_.fail("no geotransform: the raster is not georeferenced");
    }
    terrain_.geotransform = pixels_.gt;
    const auto& gt = pixels_.gt;
    if (gt[2] != 0.0 || gt[4] != 0.0) {
      session_.fail("a rotated geotransform (row rotation " + dem_number(gt[2]) + ", column rotation " + dem_number(gt[4]) +
                    "); warp it north-up first, e.g. gdalwarp");
    }
    if (!(std::isfinite(gt[0]) && std::isfinite(gt[3]) && std::isfinite(gt[1]) && std::isfinite(gt[5]) &&
          gt[1] != 0.0 && gt[5] != 0.0)) {
      session_.fail("a geotransform with pixel size " + dem_number(gt[1]) + " x " + dem_number(gt[5]) + "; expected finite, non-zero");
    }
    int has_nodata = 0;
    const double nodata = api_.GDALGetRasterNoDataValue(band_, &has_nodata);
    if (has_nodata != 0) terrain_.nodata_value = nodata;
    int has_scale = 0, has_offset = 0;
    scale_ = api_.GDALGetRasterScale(band_, &has_scale);
    offset_ = api_.GDALGetRasterOffset(band_, &has_offset);
    if (has_scale == 0) scale_ = 1.0;
    if (has_offset == 0) offset_ = 0.0;
    const char* unit = api_.GDALGetRasterUnitType(band_);
    const auto unit_m = height_unit_metres(unit ? unit : "");
    if (!unit_m) session_.fail(std::string("heights in \"") + printable(unit) + "\"; expected metres or feet");
    if (!(std::isfinite(scale_) && std::isfinite(offset_) && scale_ != 0.0)) {
      session_.fail("band scale " + dem_number(scale_) + " and offset " + dem_number(offset_) + "; expected finite, scale non-zero");
    }
    scale_ *= *unit_m;
    offset_ *= *unit_m;
  }

  void read_crs() {
    const char* wkt = api_.GDALGetProjectionRef(dataset_.get());
    if (wkt == nullptr || *wkt == '\0') {
      if (options_.crop.form == DemCropForm::lat_long_box || options_.crop.form == DemCropForm::lat_long_centre) {
        session_.fail("no coordinate reference system, so no latitude/longitude crop; crop with min_x, min_y, max_x, "
                      "max_y in the file's coordinates");
      }
      return;
    }
    terrain_.crs_wkt = wkt;
    file_srs_ = Srs(api_.OSRNewSpatialReference(wkt), SrsDestroyer{&api_});
    if (!file_srs_) session_.gdal_failed("a coordinate reference system GDAL cannot read");
    api_.OSRSetAxisMappingStrategy(file_srs_.get(), OAMS_TRADITIONAL_GIS_ORDER);
    if (api_.OSRIsGeographic(file_srs_.get()) != 0) {
      terrain_.crs = DemCrs::geographic;
    } else if (api_.OSRIsProjected(file_srs_.get()) != 0) {
      terrain_.crs = DemCrs::projected;
      terrain_.metres_per_unit = api_.OSRGetLinearUnits(file_srs_.get(), nullptr);
      if (!(std::isfinite(terrain_.metres_per_unit) && terrain_.metres_per_unit > 0.0)) {
        session_.fail("a projected CRS whose linear unit is " + dem_number(terrain_.metres_per_unit) + " m");
      }
    } else if (api_.OSRIsLocal(file_srs_.get()) != 0) {
      // A local (engineering) CRS: plain coordinates in its linear unit, no geodetic position.
      terrain_.metres_per_unit = api_.OSRGetLinearUnits(file_srs_.get(), nullptr);
      if (!(std::isfinite(terrain_.metres_per_unit) && terrain_.metres_per_unit > 0.0)) terrain_.metres_per_unit = 1.0;
      file_srs_.reset();
      if (options_.crop.form == DemCropForm::lat_long_box || options_.crop.form == DemCropForm::lat_long_centre) {
        session_.fail("a local coordinate system, so no latitude/longitude crop; crop with min_x, min_y, max_x, max_y "
                      "in the file's coordinates");
      }
      return;
    } else {
      session_.fail("a coordinate reference system that is neither projected nor geographic (geocentric?)");
    }
    // A CRS written without its code (WKT alone) is matched to one where PROJ can.
    api_.OSRAutoIdentifyEPSG(file_srs_.get());
    const char* authority = api_.OSRGetAuthorityName(file_srs_.get(), nullptr);
    const char* code = api_.OSRGetAuthorityCode(file_srs_.get(), nullptr);
    if (authority != nullptr && code != nullptr && std::strcmp(authority, "EPSG") == 0) terrain_.epsg = std::atoi(code);
    Srs wgs84(api_.OSRNewSpatialReference(nullptr), SrsDestroyer{&api_});
    if (!wgs84 || api_.OSRImportFromEPSG(wgs84.get(), 4326) != OGRERR_NONE) session_.gdal_failed("no WGS84 (EPSG:4326) in PROJ");
    api_.OSRSetAxisMappingStrategy(wgs84.get(), OAMS_TRADITIONAL_GIS_ORDER);
    to_wgs84_ = Transform(api_.OCTNewCoordinateTransformation(file_srs_.get(), wgs84.get()), TransformDestroyer{&api_});
    from_wgs84_ = Transform(api_.OCTNewCoordinateTransformation(wgs84.get(), file_srs_.get()), TransformDestroyer{&api_});
    if (!to_wgs84_ || !from_wgs84_) session_.gdal_failed("no transformation between the file's CRS and WGS84");
  }

  // File coordinates (x, y) -> WGS84 latitude, longitude (degrees).
  Eigen::Vector2d file_to_lat_lon(double x, double y) const {
    double lon = x, lat = y;
    if (api_.OCTTransform(to_wgs84_.get(), 1, &lon, &lat, nullptr) == 0 || !std::isfinite(lat) || !std::isfinite(lon)) {
      session_.fail("cannot convert (" + dem_number(x) + ", " + dem_number(y) + ") of the file's CRS to latitude/longitude");
    }
    return {lat, lon};
  }

  // WGS84 latitude, longitude -> file coordinates.
  Eigen::Vector2d lat_lon_to_file(double latitude_deg, double longitude_deg) const {
    double x = longitude_deg, y = latitude_deg;
    if (api_.OCTTransform(from_wgs84_.get(), 1, &x, &y, nullptr) == 0 || !std::isfinite(x) || !std::isfinite(y)) {
      session_.fail("cannot convert latitude " + dem_number(latitude_deg) + ", longitude " + dem_number(longitude_deg) +
                    " to the file's CRS");
    }
    return {x, y};
  }

  // Size in metres of one pixel along x and y at file point `at` (east-north distances).
  Eigen::Vector2d pixel_size_m_at(const Eigen::Vector2d& at) const {
    const Eigen::Vector2d c = file_to_lat_lon(at.x(), at.y());
    const Geodetic origin{c.x(), c.y(), 0.0};
    const auto metres_to = [&](double x, double y) {
      const Eigen::Vector2d p = file_to_lat_lon(x, y);
      return geodetic_to_enu({p.x(), p.y(), 0.0}, origin).head<2>().norm();
    };
    return {metres_to(at.x() + pixels_.gt[1], at.y()), metres_to(at.x(), at.y() + pixels_.gt[5])};
  }

  GridPlan plan_grid() {
    const DemCrop& crop = options_.crop;
    GridPlan plan;
    plan.metres_per_unit = terrain_.metres_per_unit;
    const auto& gt = pixels_.gt;
    const Eigen::Vector2d raster_centre(gt[0] + 0.5 * pixels_.cols * gt[1], gt[3] + 0.5 * pixels_.rows * gt[5]);
    const auto layout = [&](const Eigen::Vector2d& size_m, double default_spacing_m) {
      const double spacing = options_.spacing_m > 0.0 ? options_.spacing_m : default_spacing_m;
      try {
        return grid_layout<std::runtime_error>(size_m, spacing);
      } catch (const std::runtime_error& e) {
        session_.fail(e.what());
      }
    };
    const bool geographic = terrain_.crs == DemCrs::geographic;

    if (crop.form == DemCropForm::projected_box && geographic) {
      session_.fail("min_x ... max_y crops are in a projected CRS's units, but the file's CRS is geographic "
                    "(degrees); crop with south_deg, west_deg, north_deg, east_deg or center_deg and size_m");
    }
    if (crop.form == DemCropForm::whole && !geographic) {
      // The file's own axes, centred on the raster.
      plan.centre_file = raster_centre;
      const Eigen::Vector2d pixel_m(std::abs(gt[1]) * plan.metres_per_unit, std::abs(gt[5]) * plan.metres_per_unit);
      if (options_.spacing_m == 0.0) {
        if (static_cast<double>(pixels_.cols) * pixels_.rows > static_cast<double>(kMaxHeightfieldVertices)) {
          session_.fail("the raster is " + std::to_string(pixels_.cols) + " x " + std::to_string(pixels_.rows) +
                        " pixels, more than the limit of " + std::to_string(kMaxHeightfieldVertices) +
                        " vertices; crop it or set a coarser spacing_m");
        }
        plan.copy_pixels = true;
        plan.layout = {pixels_.cols, pixels_.rows, pixel_m.x(), pixel_m.y()};
      } else {
        plan.layout = layout({(pixels_.cols - 1) * pixel_m.x(), (pixels_.rows - 1) * pixel_m.y()}, 0.0);
      }
    } else if (crop.form == DemCropForm::projected_box) {
      plan.centre_file = {0.5 * (crop.min_x + crop.max_x), 0.5 * (crop.min_y + crop.max_y)};
      const double unit = plan.metres_per_unit;
      plan.layout = layout({(crop.max_x - crop.min_x) * unit, (crop.max_y - crop.min_y) * unit},
                           std::min(std::abs(gt[1]), std::abs(gt[5])) * unit);
    } else {
      // East-north axes on the tangent plane at the centre.
      plan.east_north = true;
      Eigen::Vector2d size_m;
      if (crop.form == DemCropForm::lat_long_centre) {
        plan.centre = {crop.centre_latitude_deg, crop.centre_longitude_deg, 0.0};
        size_m = crop.size_m;
      } else if (crop.form == DemCropForm::lat_long_box) {
        plan.centre = {0.5 * (crop.south_deg + crop.north_deg), 0.5 * (crop.west_deg + crop.east_deg), 0.0};
        // The east-north rectangle through the midpoints of the box's edges.
        const auto enu = [&](double lat, double lon) { return geodetic_to_enu({lat, lon, 0.0}, plan.centre); };
        size_m = {enu(plan.centre.latitude_deg, crop.east_deg).x() - enu(plan.centre.latitude_deg, crop.west_deg).x(),
                  enu(crop.north_deg, plan.centre.longitude_deg).y() - enu(crop.south_deg, plan.centre.longitude_deg).y()};
      } else {
        // A whole geographic raster: the largest east-north rectangle about its
        // centre inside its pixel centres (its edges sampled finely).
        const Eigen::Vector2d c = file_to_lat_lon(raster_centre.x(), raster_centre.y());
        plan.centre = {c.x(), c.y(), 0.0};
        size_m = inscribed_size_m(plan.centre);
      }
      plan.centre_file = lat_lon_to_file(plan.centre.latitude_deg, plan.centre.longitude_deg);
      const Eigen::Vector2d pixel_m = pixel_size_m_at(plan.centre_file);
      plan.layout = layout(size_m, pixel_m.minCoeff());
    }
    if (terrain_.crs != DemCrs::none) {
      terrain_.centre_lat_lon_deg = plan.east_north
                                        ? Eigen::Vector2d(plan.centre.latitude_deg, plan.centre.longitude_deg)
                                        : file_to_lat_lon(plan.centre_file.x(), plan.centre_file.y());
    }
    return plan;
  }

  Eigen::Vector2d inscribed_size_m(const Geodetic& centre) const {
    constexpr int kSamples = 64;
    double half_x = std::numeric_limits<double>::infinity(), half_y = half_x;
    const double last_col = pixels_.cols - 1, last_row = pixels_.rows - 1;
    for (int i = 0; i <= kSamples; ++i) {
      const double t = static_cast<double>(i) / kSamples;
      const auto enu = [&](double px, double py) {
        const Eigen::Vector2d p = file_to_lat_lon(pixels_.file_x(px), pixels_.file_y(py));
        return geodetic_to_enu({p.x(), p.y(), 0.0}, centre);
      };
      // Left and right edges bound x, top and bottom edges bound y.
      half_x = std::min({half_x, std::abs(enu(0.0, t * last_row).x()), std::abs(enu(last_col, t * last_row).x())});
      half_y = std::min({half_y, std::abs(enu(t * last_col, 0.0).y()), std::abs(enu(t * last_col, last_row).y())});
    }
    return {2.0 * half_x, 2.0 * half_y};
  }

  // Pixel coordinates of every vertex of grid row `row` into px, py (resized to the row).
  void row_pixels(const GridPlan& plan, int row, std::vector<double>& px, std::vector<double>& py) const {
    const GridLayout& g = plan.layout;
    px.resize(static_cast<std::size_t>(g.cols));
    py.resize(static_cast<std::size_t>(g.cols));
    const double y = grid_vertex_coordinate(row, g.rows, g.spacing_y_m);
    for (int c = 0; c < g.cols; ++c) {
      const double x = grid_vertex_coordinate(c, g.cols, g.spacing_x_m);
      if (plan.east_north) {
        const Geodetic p = enu_to_geodetic({x, y, 0.0}, plan.centre);
        px[c] = p.longitude_deg;
        py[c] = p.latitude_deg;
      } else {
        px[c] = plan.centre_file.x() + x / plan.metres_per_unit;
        py[c] = plan.centre_file.y() + y / plan.metres_per_unit;
      }
    }
    if (plan.east_north && api_.OCTTransform(from_wgs84_.get(), g.cols, px.data(), py.data(), nullptr) == 0) {
      session_.fail("cannot convert the crop's latitudes/longitudes to the file's CRS");
    }
    for (int c = 0; c < g.cols; ++c) {
      px[c] = pixels_.pixel_x(px[c]);
      py[c] = pixels_.pixel_y(py[c]);
    }
  }

  // Lower-left pixel of the 2 x 2 a sample at (px, py) interpolates, and the
  // fractions; samples within the outer half pixel take the edge's value.
  struct Cell {
    int col;
    int row;
    double fx;
    double fy;
  };
  Cell cell_of(double px, double py, const GridPlan& plan, int grid_col, int grid_row) const {
    if (!(px >= -kOutsideTolerancePx && px <= pixels_.cols - 1 + kOutsideTolerancePx &&
          py >= -kOutsideTolerancePx && py <= pixels_.rows - 1 + kOutsideTolerancePx)) {
      const double x = grid_vertex_coordinate(grid_col, plan.layout.cols, plan.layout.spacing_x_m);
      const double y = grid_vertex_coordinate(grid_row, plan.layout.rows, plan.layout.spacing_y_m);
      session_.fail("the crop reaches outside the raster: its vertex at (" + dem_number(x) + ", " + dem_number(y) +
                    ") m from its centre falls at pixel (" + dem_number(px) + ", " + dem_number(py) + ") of a raster of " +
                    std::to_string(pixels_.cols) + " x " + std::to_string(pixels_.rows) + " pixels");
    }
    px = std::clamp(px, 0.0, pixels_.cols - 1.0);
    py = std::clamp(py, 0.0, pixels_.rows - 1.0);
    const int col = std::min(static_cast<int>(std::floor(px)), pixels_.cols - 2);
    const int row = std::min(static_cast<int>(std::floor(py)), pixels_.rows - 2);
    return {col, row, px - col, py - row};
  }

  // The window holding the 2 x 2 pixels of the vertices of `rows` (each row
  // whole, or only its two ends).
  Window window_of(const GridPlan& plan, const std::vector<int>& whole_rows, bool ends_of_others) const {
    const GridLayout& g = plan.layout;
    std::vector<double> px, py;
    int col_min = pixels_.cols, col_max = -1, row_min = pixels_.rows, row_max = -1;
    const auto extend = [&](double x, double y, int c, int r) {
      const Cell cell = cell_of(x, y, plan, c, r);
      col_min = std::min(col_min, cell.col);
      col_max = std::max(col_max, cell.col + 1);
      row_min = std::min(row_min, cell.row);
      row_max = std::max(row_max, cell.row + 1);
    };
    for (const int r : whole_rows) {
      row_pixels(plan, r, px, py);
      for (int c = 0; c < g.cols; ++c) extend(px[c], py[c], c, r);
    }
    if (ends_of_others) {
      for (int r = 1; r + 1 < g.rows; ++r) {
        for (const int c : {0, g.cols - 1}) {
          const Eigen::Vector2d p = vertex_pixel(plan, c, r);
          extend(p.x(), p.y(), c, r);
        }
      }
    }
    return {col_min, row_min, col_max - col_min + 1, row_max - row_min + 1};
  }

  // Pixel coordinates of one vertex (as row_pixels computes them).
  Eigen::Vector2d vertex_pixel(const GridPlan& plan, int col, int row) const {
    const GridLayout& g = plan.layout;
    const double x = grid_vertex_coordinate(col, g.cols, g.spacing_x_m);
    const double y = grid_vertex_coordinate(row, g.rows, g.spacing_y_m);
    double fx = 0.0, fy = 0.0;
    if (plan.east_north) {
      const Geodetic p = enu_to_geodetic({x, y, 0.0}, plan.centre);
      fx = p.longitude_deg;
      fy = p.latitude_deg;
      if (api_.OCTTransform(from_wgs84_.get(), 1, &fx, &fy, nullptr) == 0) {
        session_.fail("cannot convert the crop's latitudes/longitudes to the file's CRS");
      }
    } else {
      fx = plan.centre_file.x() + x / plan.metres_per_unit;
      fy = plan.centre_file.y() + y / plan.metres_per_unit;
    }
    return {pixels_.pixel_x(fx), pixels_.pixel_y(fy)};
  }

  // Bilinear heights of every vertex from `window`; false (grid unfinished)
  // if a vertex needs a pixel outside it.
  bool sample(const GridPlan& plan, const Window& window, const std::vector<double>& heights) {
    const GridLayout& g = plan.layout;
    std::vector<double> px, py;
    for (int r = 0; r < g.rows; ++r) {
      row_pixels(plan, r, px, py);
      for (int c = 0; c < g.cols; ++c) {
        const Cell cell = cell_of(px[c], py[c], plan, c, r);
        if (cell.col < window.col0 || cell.row < window.row0 || cell.col + 1 >= window.col0 + window.cols ||
            cell.row + 1 >= window.row0 + window.rows) {
          return false;
        }
        const std::size_t i = static_cast<std::size_t>(cell.row - window.row0) * window.cols + (cell.col - window.col0);
        const double h00 = heights[i], h10 = heights[i + 1];
        const double h01 = heights[i + window.cols], h11 = heights[i + window.cols + 1];
        const double h = (1.0 - cell.fy) * ((1.0 - cell.fx) * h00 + cell.fx * h10) +
                         cell.fy * ((1.0 - cell.fx) * h01 + cell.fx * h11);
        terrain_.grid.heights_m[static_cast<std::size_t>(r) * g.cols + c] = h;
      }
    }
    return true;
  }

  void resample(const GridPlan& plan) {
    const GridLayout& g = plan.layout;
    terrain_.grid.cols = g.cols;
    terrain_.grid.rows = g.rows;
    terrain_.grid.spacing_x_m = g.spacing_x_m;
    terrain_.grid.spacing_y_m = g.spacing_y_m;
    terrain_.grid.heights_m.resize(static_cast<std::size_t>(g.cols) * g.rows);
    // The pixels the grid's edges need: every vertex's, wherever a vertex's
    // pixel coordinates change monotonically along rows and columns (always
    // on the file's axes; on east-north axes unless the crop spans a large
    // part of the globe). Should an inner vertex reach beyond them, the
    // window of every vertex is read instead.
    Window window = window_of(plan, {0, g.rows - 1}, true);
    std::vector<double> heights = read_window(window);
    if (sample(plan, window, heights)) return;
    std::vector<int> all_rows(static_cast<std::size_t>(g.rows));
    for (int r = 0; r < g.rows; ++r) all_rows[static_cast<std::size_t>(r)] = r;
    window = window_of(plan, all_rows, false);
    heights = read_window(window);
    if (!sample(plan, window, heights)) throw std::logic_error("DEM: a vertex outside the window of every vertex");
  }

  // The raster's pixels as the grid: grid row 0 is the southern raster row
  // (the last of a north-up file), grid column 0 the western.
  void copy_raster(const GridPlan& plan) {
    const std::vector<double> heights = read_window({0, 0, pixels_.cols, pixels_.rows});
    HeightGrid& grid = terrain_.grid;
    grid.cols = pixels_.cols;
    grid.rows = pixels_.rows;
    grid.spacing_x_m = plan.layout.spacing_x_m;
    grid.spacing_y_m = plan.layout.spacing_y_m;
    grid.heights_m.resize(heights.size());
    const bool north_up = pixels_.gt[5] < 0.0, west_left = pixels_.gt[1] > 0.0;
    for (int r = 0; r < grid.rows; ++r) {
      const int source_row = north_up ? grid.rows - 1 - r : r;
      for (int c = 0; c < grid.cols; ++c) {
        const int source_col = west_left ? c : grid.cols - 1 - c;
        grid.heights_m[static_cast<std::size_t>(r) * grid.cols + c] =
            heights[static_cast<std::size_t>(source_row) * grid.cols + source_col];
      }
    }
  }

  bool is_nodata(double raw) const {
    if (!terrain_.nodata_value) return false;
    const double nodata = *terrain_.nodata_value;
    if (std::isnan(nodata)) return std::isnan(raw);
    // Float32 pixels against a nodata value written in decimal: compared as floats.
    if (data_type_ == GDT_Float32) return static_cast<float>(raw) == static_cast<float>(nodata);
    return raw == nodata;
  }

  // The heights of `window` in metres, row-major from its first (file) row;
  // nodata refused or filled, non-finite values refused.
  std::vector<double> read_window(const Window& w) {
    if (static_cast<double>(w.cols) * w.rows > static_cast<double>(kMaxHeightfieldVertices)) {
      session_.fail("the crop reads " + std::to_string(w.cols) + " x " + std::to_string(w.rows) +
                    " pixels, more than the limit of " + std::to_string(kMaxHeightfieldVertices) +
                    "; use a coarser file (gdalwarp -tr) or a smaller crop");
    }
    std::vector<double> values(static_cast<std::size_t>(w.cols) * w.rows);
    if (api_.GDALRasterIO(band_, GF_Read, w.col0, w.row0, w.cols, w.rows, values.data(), w.cols, w.rows, GDT_Float64,
                          0, 0) != CE_None) {
      session_.gdal_failed("cannot read pixels " + std::to_string(w.cols) + " x " + std::to_string(w.rows) + " at (" +
                    std::to_string(w.col0) + ", " + std::to_string(w.row0) + ")");
    }
    std::vector<std::uint8_t> missing(values.size(), 0);
    long nodata_count = 0;
    std::size_t first_nodata = 0;
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (is_nodata(values[i])) {
        if (nodata_count++ == 0) first_nodata = i;
        missing[i] = 1;
        continue;
      }
      const double h = values[i] * scale_ + offset_;
      if (!std::isfinite(h)) {
        session_.fail("a height that is not finite (" + dem_number(values[i]) + ") at pixel (column " +
                      std::to_string(w.col0 + static_cast<long>(i % w.cols)) + ", row " +
                      std::to_string(w.row0 + static_cast<long>(i / w.cols)) + ")");
      }
      values[i] = h;
    }
    if (nodata_count > 0) {
      const std::string first = "(column " + std::to_string(w.col0 + static_cast<long>(first_nodata % w.cols)) +
                                ", row " + std::to_string(w.row0 + static_cast<long>(first_nodata / w.cols)) + ")";
      if (options_.nodata == DemNodata::refuse) {
        session_.fail(std::to_string(nodata_count) + " nodata cell" + (nodata_count == 1 ? "" : "s") + " (value " +
                      dem_number(*terrain_.nodata_value) + ") among the " + std::to_string(values.size()) +
                      " read, the first at pixel " + first + "; set \"nodata\": \"fill\" to fill them");
      }
      if (static_cast<std::size_t>(nodata_count) == values.size()) {
        session_.fail("every one of the " + std::to_string(values.size()) + " cells read is nodata");
      }
      fill_missing(w, values, missing);
      terrain_.filled_cells = nodata_count;
    }
    return values;
  }

  // Fills missing cells in rings from the valid ones (breadth first, 8
  // neighbours): each takes the mean of its neighbours already known when its
  // ring begins, so a hole fills from its rim inwards, the same on every run.
  static void fill_missing(const Window& w, std::vector<double>& values, std::vector<std::uint8_t>& missing) {
    std::vector<std::size_t> ring, next;
    const auto neighbours = [&](std::size_t i, auto&& visit) {
      const long col = static_cast<long>(i % w.cols), row = static_cast<long>(i / w.cols);
      for (long dr = -1; dr <= 1; ++dr) {
        for (long dc = -1; dc <= 1; ++dc) {
          const long c = col + dc, r = row + dr;
          if ((dr == 0 && dc == 0) || c < 0 || r < 0 || c >= w.cols || r >= w.rows) continue;
          visit(static_cast<std::size_t>(r) * w.cols + c);
        }
      }
    };
    // The first ring: missing cells next to a valid one.
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (!missing[i]) continue;
      bool touches = false;
      neighbours(i, [&](std::size_t j) { touches |= missing[j] == 0; });
      if (touches) ring.push_back(i);
    }
    std::vector<std::uint8_t> queued(missing);  // 1: missing and not yet in a ring
    for (const std::size_t i : ring) queued[i] = 0;
    while (!ring.empty()) {
      std::vector<double> filled(ring.size());
      for (std::size_t k = 0; k < ring.size(); ++k) {
        double sum = 0.0;
        int count = 0;
        neighbours(ring[k], [&](std::size_t j) {
          if (missing[j] == 0) {
            sum += values[j];
            ++count;
          }
        });
        filled[k] = sum / count;
      }
      next.clear();
      for (std::size_t k = 0; k < ring.size(); ++k) {
        values[ring[k]] = filled[k];
        missing[ring[k]] = 0;
      }
      for (const std::size_t i : ring) {
        neighbours(i, [&](std::size_t j) {
          if (queued[j]) {
            queued[j] = 0;
            next.push_back(j);
          }
        });
      }
      ring.swap(next);
    }
  }

  GdalSession session_;
  const GdalApi& api_;
  const DemOptions& options_;
  std::filesystem::path path_;
  DemTerrain terrain_;
  Dataset dataset_{nullptr, DatasetCloser{nullptr}};
  Srs file_srs_{nullptr, SrsDestroyer{nullptr}};
  Transform to_wgs84_{nullptr, TransformDestroyer{nullptr}};
  Transform from_wgs84_{nullptr, TransformDestroyer{nullptr}};
  PixelGrid pixels_;
  GDALRasterBandH band_ = nullptr;
  GDALDataType data_type_ = GDT_Unknown;
  double scale_ = 1.0;   // metres per raw unit (band scale times unit)
  double offset_ = 0.0;  // metres
};

}  // namespace

DemTerrain heightgrid_from_dem(const std::filesystem::path& path, const DemOptions& options) {
  DemReader reader(path, options);
  return reader.read();
}

}  // namespace campo
