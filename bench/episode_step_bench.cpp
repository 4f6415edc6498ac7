// One control tick of the closed loop stepped from outside (campo::Episode::step),
// without sensors: the C++ side of the Python module's ep.step() overhead
// (bench/python_step_bench.py subtracts it from the Python call's time;
// docs/PERFORMANCE.md). The scene is the Python tests' open field with its
// sensors removed and no time limit in reach; the command is a fixed hover.
#include <benchmark/benchmark.h>

#include <string>

#include "campo/episode.hpp"
#include "campo/json_reader.hpp"
#include "campo/scene_loader.hpp"
#include "campo/vehicle_factory.hpp"

namespace campo {
namespace {

Scene open_field_without_sensors() {
  const std::string file = std::string(CAMPO_SOURCE_DIR) + "/tests/python/fixtures/open_field.json";
  nlohmann::json document = parse_json_text(read_text_file(file), file);
  document["world"]["time_limit_s"] = 1e6;
  for (nlohmann::json& object : document["objects"]) {
    if (object.value("alias", "") == "drone") object["sensors"] = nlohmann::json::array();
  }
  return parse_scene(document, file, std::string(CAMPO_SOURCE_DIR) + "/tests/python/fixtures");
}

void BM_EpisodeStepNoSensors(benchmark::State& state) {
  const Scene scene = open_field_without_sensors();
  Episode episode(scene, &make_vehicle);
  PlanResult hover;
  hover.command = command::Hold{{0.0, 0.0, 1.5}, std::nullopt};
  for (auto _ : state) {
    episode.step(hover);
    benchmark::DoNotOptimize(episode.observation().state.position_m);
  }
  state.counters["ticks_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_EpisodeStepNoSensors)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace campo
