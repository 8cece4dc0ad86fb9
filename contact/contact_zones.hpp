// Contact zones and their edges, located to sub-cell accuracy.
//
// An incomplete contact's pressure falls like √(distance) at its edge, so p² is linear there: the edge is where the
// line through p² at the last two cells before the edge cell reaches zero (EdgeMethod::square_root_fit). A complete
// contact ends at a corner of the pad, a cell boundary where the gap becomes infinite (EdgeMethod::corner). A zone
// too short for a fit ends at its outer cell boundary (EdgeMethod::cell_boundary), and so does a zone cut by an end of
// the grid: the window's end is never a corner, so a caller can tell a clipped zone from a punch's edge.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "contact/grid.hpp"

namespace fretwear {

enum class EdgeMethod { square_root_fit, corner, cell_boundary };
std::string to_string(EdgeMethod m);

struct Edge {
  double x = 0.0;  // m
  EdgeMethod method = EdgeMethod::cell_boundary;
};

struct Zone {
  Edge left, right;
  int first_cell = 0, last_cell = 0;  // inclusive
};

// The maximal runs of loaded cells (p > 0), left to right, with their edges. g0 is the initial gap (+∞ outside the
// pad) and distinguishes corners from smooth edges.
std::vector<Zone> locate_zones(const Grid& grid, std::span<const double> p, std::span<const double> g0);

}  // namespace fretwear
