#include "scene/world_config.hpp"

#include <cmath>
#include <numbers>

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

const ConfigFields<WindConfig>& wind_config_fields() {
  using W = WindConfig;
  const auto gust_is = [](GustModel model) { return [model](const W& w) { return w.gust == model; }; };
  static const ConfigFields<W> fields =
      ConfigFields<W>()
          .number("speed_mps", &W::speed_mps, Range::closed(0.0, 100.0), "m/s", "steady horizontal wind speed")
          .number("direction_deg", &W::direction_deg, Range::closed(-360.0, 360.0), "deg",
                  "where the steady wind blows toward, counter-clockwise from +x (east): 90 blows toward +y")
          .number("vertical_mps", &W::vertical_mps, Range::closed(-20.0, 20.0), "m/s",
                  "steady vertical component (an updraft > 0)")
          // The steady wind as one vector, as a user of other simulators writes it: read into the
          // three fields above (which run.json then records), never written itself.
          .custom(
              "velocity_mps", "m/s", "3 numbers, horizontal norm <= 100, z in [-20, 20]",
              "the steady wind as a vector, world frame, instead of the three fields above",
              [](const JsonNode& n, W& w) {
                if (w.speed_mps != 0.0 || w.direction_deg != 0.0 || w.vertical_mps != 0.0) {
                  n.fail("either velocity_mps or speed_mps, direction_deg and vertical_mps, not both");
                }
                const Eigen::Vector3d v = n.as_vector3(Range::closed(-100.0, 100.0));
                const double horizontal = std::hypot(v.x(), v.y());
                if (horizontal > 100.0 || v.z() < -20.0 || v.z() > 20.0) {
                  n.fail("a horizontal speed within 100 m/s and a vertical one in [-20, 20] m/s");
                }
                w.speed_mps = horizontal;
                w.direction_deg = horizontal > 0.0 ? std::atan2(v.y(), v.x()) * (180.0 / std::numbers::pi) : 0.0;
                w.vertical_mps = v.z();
              },
              [](const W&, nlohmann::json&) {})
          .choice("gust", &W::gust,
                  {{"none", GustModel::none},
                   {"one_minus_cos", GustModel::one_minus_cos},
                   {"dryden", GustModel::dryden}},
                  "what is added to the steady wind: nothing, one discrete 1-cos gust, or Dryden turbulence (below)")
          .vector("gust_amplitude_mps", &W::gust_amplitude_mps, Range::closed(-100.0, 100.0), "m/s",
                  "`one_minus_cos`: the gust's peak velocity, world frame")
          .only_when(gust_is(GustModel::one_minus_cos), "a field of \"gust\": \"one_minus_cos\" only")
          .number("gust_start_s", &W::gust_start_s, Range::closed(0.0, 1e6), "s", "`one_minus_cos`: when it begins")
          .only_when(gust_is(GustModel::one_minus_cos), "a field of \"gust\": \"one_minus_cos\" only")
          .number("gust_duration_s", &W::gust_duration_s, Range::closed(0.01, 1e4), "s",
                  "`one_minus_cos`: how long it lasts (peak at half of it)")
          .only_when(gust_is(GustModel::one_minus_cos), "a field of \"gust\": \"one_minus_cos\" only")
          .number("turbulence_intensity_mps", &W::turbulence_intensity_mps, Range::closed(0.0, 20.0), "m/s",
                  "`dryden`: standard deviation of each component")
          .only_when(gust_is(GustModel::dryden), "a field of \"gust\": \"dryden\" only")
          .number("turbulence_length_m", &W::turbulence_length_m, Range::closed(1.0, 1e5), "m",
                  "`dryden`: length scale L of the three components (MIL-F-8785C convention)")
          .only_when(gust_is(GustModel::dryden), "a field of \"gust\": \"dryden\" only")
          .seed("seed", &W::seed, "`dryden`: turbulence stream, combined with the world's seed")
          .only_when(gust_is(GustModel::dryden), "a field of \"gust\": \"dryden\" only");
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
                  "geodetic reference point of the local frame (geodetic waypoints)")
          .nested("wind", &W::wind, wind_config_fields(),
                  "the velocity of the air, world frame, felt by the vehicles through their drag (below)");
  return fields;
}

}  // namespace campo
