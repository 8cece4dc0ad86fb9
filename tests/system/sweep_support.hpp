// What the sweep tests of this tier share: a small sweep scene and sweep.csv read as a table.
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "system/program.hpp"

namespace fretwear::system_test {

// A Hertz cylinder under a cycling Q: a 4 × 3 sweep of it spans partial and gross slip. `cells` sets how long a
// run takes (256: milliseconds; 4096: a good part of a second).
inline json sweep_scene(const fs::path& output_dir, int cells = 256) {
  return {{"name", "sw"},
          {"materials", {{"both", {{"E", 2e11}, {"nu", 0.3}}}}},
          {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
          {"friction", 0.5},
          {"load", {{"P", 1e5}, {"Q", {{"ratio", 0.5}}}}},
          {"grid", {{"cells", cells}}},
          {"effects", {{"tangential", json::object()}}},
          {"output", {{"dir", output_dir.string()}, {"plots", false}}}};
}

inline const std::vector<std::string> kSweepVary{"--vary", "load.Q.ratio=0.2,0.5,0.8,1.2", "--vary",
                                                 "load.P=1e5,2e5,4e5"};

// sweep.csv's rows, split at commas outside quotes, without the columns named `leave_out` (the timings, which
// differ from one run of the same scene to the next).
inline std::vector<std::vector<std::string>> csv_rows(const fs::path& file, const std::string& leave_out) {
  std::ifstream in(file);
  std::vector<std::vector<std::string>> rows;
  std::size_t skip = std::string::npos;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells{""};
    bool quoted = false;
    for (const char c : line) {
      if (c == '"') quoted = !quoted;
      if (c == ',' && !quoted)
        cells.emplace_back();
      else
        cells.back() += c;
    }
    if (rows.empty())
      for (std::size_t i = 0; i < cells.size(); ++i)
        if (cells[i] == leave_out) skip = i;
    if (skip < cells.size()) cells.erase(cells.begin() + long(skip));
    rows.push_back(cells);
  }
  return rows;
}

}  // namespace fretwear::system_test
