// depth_reactive's record: its replanning details written through its declarations, and the
// overlays of a recorded step (what `campo render --kind depth --step K` draws) recomputed by the
// planner's own steps from the recorded depth map and parameters.
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "campo/json_reader.hpp"
#include "campo/planner_record.hpp"
#include "planners/depth_reactive.hpp"
#include "planners/depth_reactive_steps.hpp"

namespace campo {
namespace {

// A 32 x 24 depth map: free (1) but for a near wall (0.2) on the left half.
RecordedImage wall_image() {
  RecordedImage image{.cols = 32, .rows = 24, .fov_h_deg = 90.0, .fov_v_deg = 60.0, .max_range_m = 10.0};
  image.values.assign(32 * 24, 1.0f);
  for (int r = 0; r < 24; ++r) {
    for (int c = 0; c < 14; ++c) image.values[static_cast<std::size_t>(r) * 32 + c] = 0.2f;
  }
  return image;
}

// A recorded step that found a new waypoint, written as evaluate() writes it.
ReplanDecision found_step() {
  const DepthReactiveRecord& r = depth_reactive_record();
  ReplanDecision step{.index = 3, .sensor = "cam"};
  r.role.set(step.details, "target");
  r.visibility.set(step.details, "invisible");
  r.pixel.set(step.details, {10.5, 12.0});
  r.radius_px.set(step.details, {3.0, 2.0});
  r.threshold.set(step.details, 0.5);
  r.chosen_pixel.set(step.details, {20, 12});
  r.edge_pixel.set(step.details, {15, 12});
  r.waypoint_pixel.set(step.details, {22, 12});
  r.action.set(step.details, "new_waypoint");
  return step;
}

TEST(DepthReactiveRecord, CaptionsNameWhatTheStepSawAndDid) {
  const PlannerRecord& d = depth_reactive_record().description;
  EXPECT_EQ(d.replan_action(found_step()), "new waypoint");
  EXPECT_EQ(d.replan_caption(found_step()), "target invisible -> new waypoint");
  EXPECT_NO_THROW(d.replan.check(found_step().details, "events.jsonl", "/decisions/replan"));
}

TEST(DepthReactiveRecord, ReplanOverlaysAreThePlannersStepsOnTheRecordedMap) {
  const RecordedImage image = wall_image();
  const nlohmann::json parameters = depth_reactive_config_fields().write(DepthReactiveConfig{});
  const ImageOverlays o =
      depth_reactive_record().description.replan_overlays(found_step(), image, parameters, "run.json", "/p");
  // The dilated map and its threshold, as the planner computes them.
  const cv::Mat depth(image.rows, image.cols, CV_32F, const_cast<float*>(image.values.data()));
  const DepthGrid grid{image.cols, image.rows, image.fov_h_deg, image.fov_v_deg, image.max_range_m};
  const cv::Mat dilated = dilate_depth_map(depth, dilation_params(DepthReactiveConfig{}, grid));
  ASSERT_EQ(o.processed.size(), dilated.total());
  EXPECT_EQ(o.processed, std::vector<float>(dilated.ptr<float>(), dilated.ptr<float>() + dilated.total()));
  const cv::Mat free = threshold_free(dilated, 0.5);
  EXPECT_EQ(o.mask, std::vector<std::uint8_t>(free.ptr<std::uint8_t>(), free.ptr<std::uint8_t>() + free.total()));
  EXPECT_EQ(o.mask_threshold, 0.5);
  // W' and its ellipse as recorded; the scan runs from the chosen pixel toward W' up to the edge.
  EXPECT_EQ(o.target_px, Eigen::Vector2d(10.5, 12.0));
  EXPECT_EQ(o.ellipse_px, Eigen::Vector2d(3.0, 2.0));
  EXPECT_EQ(o.chosen_px, Eigen::Vector2i(20, 12));
  ASSERT_FALSE(o.polyline_px.empty());
  EXPECT_EQ(o.polyline_px.front(), Eigen::Vector2i(20, 12));
  EXPECT_EQ(o.polyline_px.back(), Eigen::Vector2i(15, 12));
  EXPECT_EQ(o.polyline_px.size(), 6u);  // columns 20 down to 15 along row 12
  EXPECT_EQ(o.placed_px, Eigen::Vector2i(22, 12));
  // A step without W' is refused, naming the run's record.
  ReplanDecision bare{.index = 4};
  depth_reactive_record().action.set(bare.details, "fly");
  EXPECT_THROW(depth_reactive_record().description.replan_overlays(bare, image, parameters, "run.json", "/p"),
               InputError);
}

}  // namespace
}  // namespace campo
