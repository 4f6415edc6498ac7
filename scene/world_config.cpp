#include "scene/world_config.hpp"

namespace campo {

const ConfigFields<GeoReference>& geo_reference_fields() {
  using G = GeoReference;
  static const ConfigFields<G> fields =
      ConfigFields<G>()
          .number("latitude_deg", &G::latitude_deg, Range::closed(-90.0, 90.0), "deg", "WGS84 latitude of the reference point")
          .number("longitude_deg", &G::longitude_deg, Range::closed(-180.0, 180.0), "deg",
                  "WGS84 longitude of the reference point")
          .number("altitude_m", &G::altitude_m, Range::closed(-1e4, 1e5), "m", "ellipsoidal height of the reference point")
          .choice("projection", &G::projection,
                  {{"wgs84_enu", GeoProjection::wgs84_enu}, {"sphere_no_coslat", GeoProjection::sphere_no_coslat}},
                  "how latitude/longitude become x, y (below)")
          .vector("position_m", &G::position_m, Range::closed(-1e6, 1e6), "m",
                  "local x, y of the reference point");
  return fields;
}

const ConfigFields<WorldConfig>& world_config_fields() {
  using W = WorldConfig;
  static const ConfigFields<W> fields =
      ConfigFields<W>()
          .vector("gravity_mps2", &W::gravity_mps2, Range::closed(-100.0, 100.0), "m/s²", "gravity, world frame")
          .number("physics_step_s", &W::physics_step_s, Range::closed(1e-5, 0.1), "s", "fixed Bullet step")
          .number("control_rate_hz", &W::control_rate_hz, Range::closed(0.1, 10000.0), "Hz",
                  "controller and planner rate; must divide the physics rate (below)")
          .number("sensor_rate_hz", &W::sensor_rate_hz, Range::closed(0.01, 10000.0), "Hz",
                  "rate of sensors that set none; must divide the physics rate (below)")
          .number("time_limit_s", &W::time_limit_s, Range{0.0, 1e6, true, false}, "s",
                  "an episode ends here with \"timeout\"")
          .seed("seed", &W::seed, "master seed of a run (sensor noise, generators, planners)")
          .nested("geo_reference", &W::geo_reference, geo_reference_fields(),
                  "geodetic reference point of the local frame (geodetic waypoints)");
  return fields;
}

}  // namespace campo
