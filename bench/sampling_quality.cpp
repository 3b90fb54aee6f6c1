// Measures where edge samples land on a simulated sequence (not a Google Benchmark: it prints
// quality figures). At evenly spaced ticks it compares AA sampling with ESVO's newest events at
// the same point count against the simulator's true edges (sim/edge_truth.hpp):
//   sampling_quality --preset rpg --trajectory box2.txt --duration 20 --ticks 20 --points 2000
// Options: --preset NAME, --trajectory FILE, --calib DIR, --start S, --duration S, --ticks N,
// --points M, --tolerance PX (edge dilation), --config-grid C R (sampling/AA grid),
// --window-ms MS (AA window), --min-spacing PX (edge_sampling.min_spacing_px).
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "aavio/sim/edge_truth.hpp"

int main(int argc, char** argv) {
  using namespace aavio;
  sim::SimulationRequest request;
  request.preset = "rpg";
  int ticks = 10;
  events::RepresentationConfig config;
  sim::EdgeTruthConfig truth;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", arg.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "--preset") {
      request.preset = next();
    } else if (arg == "--trajectory") {
      request.trajectory = next();
    } else if (arg == "--calib") {
      request.calibration = next();
    } else if (arg == "--start") {
      request.start_s = std::stod(next());
    } else if (arg == "--duration") {
      request.duration_s = std::stod(next());
    } else if (arg == "--ticks") {
      ticks = std::stoi(next());
    } else if (arg == "--points") {
      config.edge_sampling.num_points = std::stoi(next());
    } else if (arg == "--window-ms") {
      config.adaptive_accumulation.window_ms = std::stod(next());
    } else if (arg == "--min-spacing") {
      config.edge_sampling.min_spacing_px = std::stoi(next());
    } else if (arg == "--tolerance") {
      truth.tolerance_px = std::stoi(next());
    } else if (arg == "--config-grid") {
      config.edge_sampling.grid_cols = config.adaptive_accumulation.grid_cols = std::stoi(next());
      config.edge_sampling.grid_rows = config.adaptive_accumulation.grid_rows = std::stoi(next());
    } else {
      std::fprintf(stderr, "unknown option %s (see the comment at the top of the source)\n",
                   arg.c_str());
      return 2;
    }
  }
  Expected<sim::SimulationWorld> world = sim::BuildSimulationWorld(request);
  if (!world) {
    std::fprintf(stderr, "%s\n", world.status().ToString().c_str());
    return 1;
  }
  const TimeNs begin = world->spline.t_begin_ns(), end = world->spline.t_end_ns();
  std::vector<TimeNs> at;
  for (int k = 1; k <= ticks; ++k)
    at.push_back(begin + (end - begin) * k / (ticks + 1));
  Expected<sim::SamplingComparison> c = sim::CompareEdgeSampling(*world, at, config, truth);
  if (!c) {
    std::fprintf(stderr, "%s\n", c.status().ToString().c_str());
    return 1;
  }
  std::printf(
      "%d ticks, %zu samples per tick, edges ±%d px cover %.1f %% of usable pixels "
      "(blocks with edges %.1f of %d)\n",
      c->ticks, c->aa.samples, truth.tolerance_px, 100.0 * c->aa.edge_density,
      c->aa.blocks_with_edges, config.edge_sampling.grid_cols * config.edge_sampling.grid_rows);
  for (const auto& [name, q] : {std::pair{"AA", c->aa}, std::pair{"ESVO newest", c->esvo}}) {
    std::printf(
        "%-12s on edge %.1f %%  ratio to random %.2f  blocks with ≥1 %% of samples %.1f  "
        "largest block share %.1f %%\n",
        name, 100.0 * q.on_edge, q.ratio, q.blocks_covered, 100.0 * q.largest_block_share);
  }
  return 0;
}
