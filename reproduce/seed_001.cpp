// Seed 001 (LIDAR-mapped D* Lite quadrotor): 001 §5.1-5.3, Tabelle 5.1-5.6, Figure 5.4-5.13, §6.
#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "render/run_files.hpp"
#include "reproduce/claims.hpp"
#include "sim/json_reader.hpp"

namespace campo {

namespace fs = std::filesystem;

namespace {

// An obstacle block of Tabelle 5.1/5.3/5.5: rows ("Latitudine [celle]"),
// columns ("Longitudine [celle]"), height above the ground ("ΔAltitudine [m]").
struct ThesisBlock {
  int row_first, row_last, col_first, col_last;
  double height_m;
  bool operator<(const ThesisBlock& o) const {
    return std::tie(row_first, row_last, col_first, col_last, height_m) <
           std::tie(o.row_first, o.row_last, o.col_first, o.col_last, o.height_m);
  }
  bool operator==(const ThesisBlock& o) const { return !(*this < o) && !(o < *this); }
};

struct ThesisScene {
  const char* scene;       // bundled scene
  const char* table;       // the thesis's table of its obstacle cells
  const char* section;     // where the thesis describes it
  std::vector<ThesisBlock> blocks;
};

// The row "49 ÷ 50 | 46 ÷ 49 52 ÷ 55 | 35" of Tabella 5.1 is two blocks with the slot between them.
const std::vector<ThesisScene>& thesis_scenes() {
  static const std::vector<ThesisScene> scenes{
      {"obstacle_field", "Tabella 5.1", "§5.1",
       {{35, 35, 16, 18, 30}, {40, 45, 25, 30, 15}, {55, 56, 15, 18, 35}, {77, 80, 40, 41, 35},
        {49, 50, 46, 49, 35}, {49, 50, 52, 55, 35}, {30, 31, 50, 51, 35}, {65, 100, 5, 30, 10}}},
      {"zigzag", "Tabella 5.3", "§5.2", {{24, 27, 16, 28, 35}, {39, 42, 6, 18, 35}, {54, 57, 16, 28, 35}, {69, 72, 6, 18, 35}}},
      {"wall", "Tabella 5.5", "§5.3", {{20, 22, 1, 100, 30}}},
  };
  return scenes;
}

std::string block_text(const ThesisBlock& b) {
  const auto range = [](int a, int z) { return a == z ? std::to_string(a) : std::to_string(a) + "-" + std::to_string(z); };
  return "rows " + range(b.row_first, b.row_last) + ", cols " + range(b.col_first, b.col_last) + ", " +
         fixed(b.height_m, 0) + " m";
}

// The scene file's grid_obstacles blocks, as written.
std::vector<ThesisBlock> scene_blocks(const fs::path& file) {
  const nlohmann::json document = read_json_file(file);
  std::vector<ThesisBlock> blocks;
  for (const auto& object : document.at("objects")) {
    if (object.value("type", "") != "grid_obstacles") continue;
    for (const auto& box : object.at("boxes")) {
      blocks.push_back({box.at("rows").at(0).get<int>(), box.at("rows").at(1).get<int>(), box.at("cols").at(0).get<int>(),
                        box.at("cols").at(1).get<int>(), box.at("height_m").get<double>()});
    }
  }
  std::sort(blocks.begin(), blocks.end());
  return blocks;
}

void obstacle_geometry(Claim& claim) {
  claim.thesis = "001 §5.1-5.3, Tabelle 5.1, 5.3 and 5.5: the obstacle cells of the three simulations (rows counted "
                 "northward, columns eastward, 100 x 100 cells, height above the ground in metres); the wall of "
                 "Tabella 5.5 is 30 m high.";
  TargetCheck check;
  std::vector<std::vector<std::string>> rows;
  for (const ThesisScene& t : thesis_scenes()) {
    const fs::path file = fs::path("scenes") / (std::string(t.scene) + ".json");
    std::vector<ThesisBlock> expected = t.blocks;
    std::sort(expected.begin(), expected.end());
    const std::vector<ThesisBlock> actual = scene_blocks(file);
    for (const ThesisBlock& b : expected) {
      const bool present = std::find(actual.begin(), actual.end(), b) != actual.end();
      rows.push_back({t.scene, t.table, block_text(b), present ? "the same" : "missing"});
    }
    for (const ThesisBlock& b : actual) {
      if (std::find(expected.begin(), expected.end(), b) == expected.end()) {
        rows.push_back({t.scene, t.table, "(not in the thesis)", block_text(b)});
      }
    }
    check.expect(actual == expected, std::string(t.scene) + " has exactly the blocks of " + t.table);
  }
  claim.measured = "The blocks of the grid_obstacles of scenes/obstacle_field.json, scenes/zigzag.json and "
                   "scenes/wall.json against the thesis's tables:\n\n" +
                   markdown_table({"Scene", "Thesis", "Block in the thesis", "In campo's scene"}, rows);
  claim.verdict = check.verdict();
  claim.verdict_reason = check.summary();
}

// The three simulations' runs and their figures (Figure 5.4/5.8/5.12: the flown route against the nominal one with
// the LIDAR's hits; Figure 5.5/5.9/5.13: the terrain the drone reconstructed).
void route_figures(const Workbench& bench, Claim& claim) {
  claim.thesis = "001 §5.1-5.3, Figure 5.4, 5.8 and 5.12: \"the actual route\" of each simulation, the LIDAR's "
                 "measurements as red points; Figure 5.5, 5.9 and 5.13: \"the reconstruction of the terrain after "
                 "the simulation\" from the sensor's measurements, \"not exactly identical to the DEM, but it "
                 "represents the obstacles well enough for the drone to avoid them\".";
  TargetCheck check;
  std::vector<std::vector<std::string>> rows;
  const std::map<std::string, std::pair<const char*, const char*>> figure_numbers{
      {"obstacle_field", {"5.4", "5.5"}}, {"zigzag", {"5.8", "5.9"}}, {"wall", {"5.12", "5.13"}}};
  for (const ThesisScene& t : thesis_scenes()) {
    const fs::path run = bench.work(std::string("001_") + t.scene);
    claim.commands.push_back(bench.campo({"run", "scenes/" + std::string(t.scene) + ".json", "--out", run.string()}));
    const RecordedRun recorded = load_run_dir(run);
    const nlohmann::json& m = recorded.record.at("metrics");
    const std::string outcome = m.at("outcome").get<std::string>();
    rows.push_back({t.scene, outcome, fixed(m.at("path_length_m").get<double>(), 1),
                    fixed(m.at("sim_time_s").get<double>(), 1), std::to_string(m.at("collisions").get<int>()),
                    fixed(m.at("min_clearance_m").get<double>(), 2)});
    check.expect(outcome == "reached" && m.at("collisions").get<int>() == 0,
                 std::string(t.scene) + " completes its route without collision");
    const auto [route, terrain] = figure_numbers.at(t.scene);
    claim.figures.push_back({bench.publish(run / "map.png", std::string("001_") + t.scene + "_map.png"),
                             std::string("Figure ") + route + " (" + t.scene + "): the flown route by time, the "
                             "waypoints and the LIDAR hits the planner mapped."});
    claim.figures.push_back({bench.publish(run / "heightmap.png", std::string("001_") + t.scene + "_heightmap.png"),
                             std::string("Figure ") + terrain + " (" + t.scene + "): the terrain and obstacles "
                             "as the drone reconstructed them."});
  }
  claim.measured = "Each scene's route flown with the bundled defaults:\n\n" +
                   markdown_table({"Scene", "Outcome", "Path (m)", "Time (s)", "Collisions", "Min clearance (m)"}, rows);
  claim.verdict = check.verdict();
  claim.verdict_reason = check.summary();
}

}  // namespace

std::vector<Claim> seed_001_claims(const Workbench& bench) {
  std::vector<Claim> claims;
  claims.push_back(measure_claim("001", "Obstacles as Tabelle 5.1, 5.3 and 5.5", obstacle_geometry));
  claims.push_back(measure_claim("001", "Figures 5.4/5.8/5.12 and 5.5/5.9/5.13, flown routes and reconstructed terrain",
                                 [&](Claim& c) { route_figures(bench, c); }));
  return claims;
}

}  // namespace campo
