// loadChainSettings and parseChainSteps: the chain's config section and its list of steps.

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "mrslam/fusion/merge/chain_merger.hpp"

namespace mrslam::fusion {

ChainSettings loadChainSettings(const Config& chain) {
  ChainSettings s;
  s.refine_psi = chain.getBool("refine_psi", s.refine_psi);
  s.slid_rivals = chain.getBool("slid_rivals", s.slid_rivals);
  s.sweep_rivals = chain.getBool("sweep_rivals", s.sweep_rivals);
  s.turned_rival_degrees =
      chain.getDoubles("turned_rival_degrees", s.turned_rival_degrees, 0, {1.0, 359.0});
  s.turned_rival_similarity =
      chain.getDouble("turned_rival_similarity", s.turned_rival_similarity, {1.0, 100.0});
  s.turned_rival_rate = chain.getDouble("turned_rival_rate", s.turned_rival_rate, {0.0, 100.0});
  s.turned_rival_weak_structure =
      chain.getDouble("turned_rival_weak_structure", s.turned_rival_weak_structure, {0.0, 1.0});
  s.turned_rival_weak_rate =
      chain.getDouble("turned_rival_weak_rate", s.turned_rival_weak_rate, {0.0, 100.0});
  s.sweep_step_deg = chain.getDouble("sweep_step_deg", s.sweep_step_deg, {0.1, 10.0});
  s.sweep_peaks = static_cast<int>(chain.getInt("sweep_peaks", s.sweep_peaks, {1, 100}));
  s.sweep_coarse_cells =
      static_cast<int>(chain.getInt("sweep_coarse_cells", s.sweep_coarse_cells, {1, 16}));
  s.sweep_prefilter_rate =
      chain.getDouble("sweep_prefilter_rate", s.sweep_prefilter_rate, {0.0, 100.0});
  s.cleaner_alternative_rate =
      chain.getDouble("cleaner_alternative_rate", s.cleaner_alternative_rate, {0.0, 10.0});
  s.cleaner_alternative_min_z =
      chain.getDouble("cleaner_alternative_min_z", s.cleaner_alternative_min_z, {0.0, 100.0});
  s.slid_alternative_rate =
      chain.getDouble("slid_alternative_rate", s.slid_alternative_rate, {0.0, 10.0});
  s.walls_alternative_rate =
      chain.getDouble("walls_alternative_rate", s.walls_alternative_rate, {0.0, 10.0});
  s.walls_alternative_overlap =
      chain.getDouble("walls_alternative_overlap", s.walls_alternative_overlap, {0.0, 100.0});
  s.walls_alternative_min_turn_deg = chain.getDouble(
      "walls_alternative_min_turn_deg", s.walls_alternative_min_turn_deg, {0.0, 180.0});
  s.alternative_cells = chain.getDouble("alternative_cells", s.alternative_cells, {0.0, 1000.0});
  s.alternative_prefilter_rate =
      chain.getDouble("alternative_prefilter_rate", s.alternative_prefilter_rate, {0.0, 100.0});
  s.alternative_sweep_degrees =
      chain.getDoubles("alternative_sweep_degrees", s.alternative_sweep_degrees, 0, {1.0, 359.0});
  s.alternative_sweep_peaks = static_cast<int>(
      chain.getInt("alternative_sweep_peaks", s.alternative_sweep_peaks, {1, 100}));
  s.undecided_deg = chain.getDouble("undecided_deg", s.undecided_deg, {0.0, 180.0});
  s.second_opinion_step = chain.getString("second_opinion_step", s.second_opinion_step);
  s.second_opinion_cells =
      chain.getDouble("second_opinion_cells", s.second_opinion_cells, {0.0, 1000.0});
  s.second_opinion_deg = chain.getDouble("second_opinion_deg", s.second_opinion_deg, {0.0, 180.0});
  s.second_opinion_turn_share =
      chain.getDouble("second_opinion_turn_share", s.second_opinion_turn_share, {0.0, 1.0});
  s.min_slide_margin_cells =
      chain.getInt("min_slide_margin_cells", s.min_slide_margin_cells, {0, 100000000});
  s.floor_crossing_min_cells = static_cast<int>(
      chain.getInt("floor_crossing_min_cells", s.floor_crossing_min_cells, {0, 100000000}));
  s.floor_crossing_min_share =
      chain.getDouble("floor_crossing_min_share", s.floor_crossing_min_share, {0.0, 1.0});
  FloorCrossingSettings& floor = s.floor_crossing;
  floor.clearance_cells =
      chain.getDouble("floor_crossing_clearance_cells", floor.clearance_cells, {0.0, 100.0});
  floor.floor_max_occupancy = static_cast<int>(
      chain.getInt("floor_crossing_floor_max_occupancy", floor.floor_max_occupancy, {0, 100}));
  floor.known_around = chain.getBool("floor_crossing_known_around", floor.known_around);
  s.neighbour_basin_min_v_gain =
      chain.getDouble("neighbour_basin_min_v_gain", s.neighbour_basin_min_v_gain, {0.0, 1.0});
  NeighbourBasinSettings& basins = s.neighbour_basins;
  basins.turn_steps =
      static_cast<int>(chain.getInt("neighbour_basin_turn_steps", basins.turn_steps, {0, 20}));
  basins.shift_steps =
      static_cast<int>(chain.getInt("neighbour_basin_shift_steps", basins.shift_steps, {0, 20}));
  basins.climbs =
      static_cast<int>(chain.getInt("neighbour_basin_climbs", basins.climbs, {0, 1000}));
  return s;
}

std::vector<std::string> parseChainSteps(const std::string& steps) {
  std::vector<std::string> names;
  std::stringstream text(steps);
  std::string name;
  while (std::getline(text, name, ',')) {
    name.erase(0, name.find_first_not_of(" \t"));
    name.erase(name.find_last_not_of(" \t") + 1);
    if (name.empty()) {
      continue;
    }
    if (name == "chain" || name.rfind("chain:", 0) == 0) {
      throw std::invalid_argument("a merge chain cannot hold a chain");
    }
    if (std::find(names.begin(), names.end(), name) != names.end()) {
      throw std::invalid_argument("merge chain step '" + name + "' is given twice");
    }
    names.push_back(name);
  }
  if (names.empty()) {
    throw std::invalid_argument("a merge chain needs at least one step");
  }
  return names;
}

}  // namespace mrslam::fusion
