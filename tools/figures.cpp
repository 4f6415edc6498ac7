#include "tools/figures.hpp"

#include <algorithm>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

#include "render/snapshot.hpp"
#include "sim/json_reader.hpp"
#include "sim/scene_mesh.hpp"

namespace campo::cli {

namespace {

std::filesystem::path write_png(const cv::Mat& image, const std::filesystem::path& path) {
  // Fixed compression settings: the same figure gives the same bytes.
  if (!cv::imwrite(path.string(), image, {cv::IMWRITE_PNG_COMPRESSION, 6})) {
    throw std::runtime_error("cannot write " + path.string());
  }
  return path;
}

std::string title_of(const RecordedRun& run, const std::string& what) {
  const auto& p = run.record.at("parameters");
  return run.scene.name + " - " + p.at("vehicle").at("type").get<std::string>() + " - " +
         p.at("planner").at("name").get<std::string>() + " - " + run.view.outcome + " - " + what;
}

}  // namespace

std::vector<std::filesystem::path> write_figure(const RecordedRun& run, const std::string& kind,
                                                const std::filesystem::path& out_dir) {
  FigureStyle style;
  if (kind == "map") {
    style.title = title_of(run, "map");
    return {write_png(draw_map(run.scene, run.view, style), out_dir / "map.png")};
  }
  if (kind == "side") {
    style.title = title_of(run, "side view");
    return {write_png(draw_side_view(run.scene, run.view, style), out_dir / "side.png")};
  }
  if (kind == "snapshot") {
    std::vector<Eigen::Vector3d> path;
    for (const TrackPoint& p : run.view.track) path.push_back(p.position_m);
    const SceneMesh mesh = build_scene_mesh(run.scene);
    const SnapshotCamera camera = default_snapshot_camera(run.scene, path);
    std::optional<Eigen::Isometry3d> pose;
    if (!path.empty()) pose = Eigen::Isometry3d(Eigen::Translation3d(path.back()));
    const auto type = vehicle_type_from_string(run.record.at("parameters").at("vehicle").at("type").get<std::string>());
    return {write_png(render_snapshot(run.scene, mesh, camera, path, pose, type.value_or(VehicleType::quadrotor)),
                      out_dir / "snapshot.png")};
  }
  if (kind == "depth") {
    // Every recorded depth map (campo run --record-depth), grey and colour-mapped.
    std::vector<std::filesystem::path> frames, written;
    const auto depth_dir = run.dir / "depth";
    if (std::filesystem::is_directory(depth_dir)) {
      for (const auto& e : std::filesystem::directory_iterator(depth_dir)) {
        if (e.path().extension() == ".png") frames.push_back(e.path());
      }
    }
    std::sort(frames.begin(), frames.end());
    if (frames.empty()) {
      throw InputError(depth_dir.string(), "", "no recorded depth maps; run with --record-depth N");
    }
    std::filesystem::create_directories(out_dir / "depth_figures");
    for (const auto& frame : frames) {
      const cv::Mat gray16 = cv::imread(frame.string(), cv::IMREAD_UNCHANGED);
      if (gray16.type() != CV_16U) throw InputError(frame.string(), "", "expected a 16-bit grey depth map");
      cv::Mat depth;
      gray16.convertTo(depth, CV_32F, 1.0 / 65535.0);
      const std::string stem = frame.stem().string();
      written.push_back(write_png(draw_depth(depth, {}, false, stem + " (grey)"), out_dir / "depth_figures" / (stem + "_grey.png")));
      written.push_back(write_png(draw_depth(depth, {}, true, stem + " (colour)"), out_dir / "depth_figures" / (stem + "_colour.png")));
    }
    return written;
  }
  throw std::invalid_argument("unknown figure kind " + kind);
}

std::filesystem::path write_overlay(const std::vector<RecordedRun>& runs, const std::filesystem::path& out_dir) {
  std::vector<RunView> views;
  for (const auto& r : runs) views.push_back(r.view);
  FigureStyle style;
  style.title = runs.front().scene.name + " - " + std::to_string(runs.size()) + " runs";
  return write_png(draw_overlay(runs.front().scene, views, style), out_dir / "overlay.png");
}

}  // namespace campo::cli
