// depth_reactive at coarse resolutions: runs of two_barriers at 32 x 32 that
// collided or grazed a barrier before the margin was kept toward the sensor,
// along TrovaWP's corridor and the blind start of the next leg
// (docs/planners.md, "Safety at coarse resolutions"). The seeds and starts are
// those of `campo sweep` (1 cm range noise, the start jittered within 0.25 m):
// seed 1061 hit barrier_right (a waypoint set 0.42 m in front of it, the drone
// turning there), 1024 passed 3 mm from it, 1026 23 mm, 1031 43 mm.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "campo/scene_loader.hpp"
#include "planners/depth_reactive.hpp"
#include "tests/planners/closed_loop_support.hpp"

namespace campo {
namespace {

struct Start {
  int seed;
  double x, y;
};

// Distance from `p` to the nearest cuboid of the scene (the barriers), metres.
double distance_to_cuboids(const Scene& scene, const Eigen::Vector3d& p) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const Shape& s : scene.shapes) {
    if (s.type != ShapeType::cuboid) continue;
    const Eigen::Vector3d q = (s.pose.inverse() * p).cwiseAbs() - 0.5 * s.size_m;
    nearest = std::min(nearest, q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0));
  }
  return nearest;
}

TEST(DepthReactiveSafety, FormerlyCollidingSeedsAt32KeepTheMargin) {
  const std::vector<Start> starts = {{1061, -0.005381120351097111, -0.10653999589786835},
                                     {1024, -0.19616439930964477, -0.07065527192986519},
                                     {1026, 0.15462096666872277, 0.1835557404804331},
                                     {1031, 0.00014976281761499614, 0.02758172280349022}};
  const Scene scene = load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/two_barriers.json");
  const double margin = DepthReactiveConfig{}.dilation_margin_m;
  // The bounding radius of the drone's 0.6 x 0.6 x 0.12 m box: its centre
  // kept `margin` away keeps the box margin - 0.43 m away, whatever its heading.
  const double bounding_radius = 0.5 * std::sqrt(0.6 * 0.6 + 0.6 * 0.6 + 0.12 * 0.12);
  for (const Start& s : starts) {
    SCOPED_TRACE("seed " + std::to_string(s.seed));
    const EpisodeResult r = testing::run_bundled(
        "two_barriers", "depth_reactive",
        {"/objects/drone/sensors/scanner/noise_stddev_m=0.01", "/objects/drone/sensors/scanner/resolution=[32,32]",
         "/world/seed=" + std::to_string(s.seed),
         "/objects/drone/pose/position_m=[" + std::to_string(s.x) + "," + std::to_string(s.y) + ",1.5]"});
    EXPECT_EQ(r.only().metrics.outcome, Outcome::reached) << r.only().metrics.reason;
    EXPECT_EQ(r.only().metrics.collisions, 0);
    EXPECT_GE(r.only().metrics.min_clearance_m, margin - bounding_radius);
    // Every waypoint the drone flew to keeps the margin from the barriers (up
    // to 5 cm: the range noise is 1 cm), pixel errors included by DilataMappa.
    int reached = 0;
    for (const PlannerEvent& e : r.only().events) {
      if (!e.decisions.reached_intermediate) continue;
      ++reached;
      EXPECT_GE(distance_to_cuboids(scene, *e.decisions.reached_intermediate), margin - 0.05)
          << e.decisions.reached_intermediate->transpose();
    }
    EXPECT_GE(reached, 1);
  }
}

}  // namespace
}  // namespace campo
