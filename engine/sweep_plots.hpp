// What a sweep draws and how its table names things: the units of the scene keys a sweep varies, and the maps
// (docs/SCENES.md, "Sweeps"): a regime map and a colour map over the first two varied keys, each run one cell of the
// actual grid of values, and the life against the first varied key.
#pragma once

#include <string>

#include "engine/folder.hpp"
#include "engine/sweep.hpp"

namespace fretwear {

// The unit of a scene key: `label` for an axis ("N/m"), `suffix` for a column name ("N_m"); both empty when the key
// is dimensionless or not one fretwear knows a unit for.
struct KeyUnit {
  std::string label, suffix;
};
KeyUnit key_unit(const std::string& dotted);

// "load.P (N/m)", "friction": a varied key as an axis names it.
std::string axis_label(const std::string& dotted);

// "load.P_N_m": a varied key as sweep.csv names its column.
std::string column_name(const std::string& dotted);

// Writes the maps' data into `out`, whatever `plots`: sweep_map.dat (a row per cell of the first two varied keys)
// and, with a life effect, sweep_life.dat, as the runs' CSV files are written without plots; with `plots` also
// sweep.gp, and runs gnuplot on it (sweep_regime, sweep_map, sweep_life .svg/.png).
void write_sweep_maps(const SweepResult& result, const std::string& scene_name, bool wears, bool life, bool plots,
                      const OutputFolder& out);

}  // namespace fretwear
