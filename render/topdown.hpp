#pragma once
/// Top-down map of a run: terrain, obstacle footprints, mission waypoints and
/// the travelled path, with a scale bar and a legend.
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "sim/scene.hpp"

namespace campo {

struct TopdownStyle {
  int max_size_px = 1200;     ///< the map's longer side; the other follows its aspect
  int min_width_px = 720;     ///< room for the legend under narrow maps
  double margin_m = 3.0;      ///< around the path and waypoints
  std::string title;
};

/// Draws the map (x east to the right, y north up) around the path and the
/// mission. `path_m` is the travelled path, `mission` the waypoints.
cv::Mat draw_topdown(const Scene& scene, const std::vector<Eigen::Vector3d>& path_m,
                     const std::vector<Waypoint>& mission, const TopdownStyle& style = {});

}  // namespace campo
