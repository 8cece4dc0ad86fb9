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

// The contact located from the gap: the maximal runs of cells that touch, loaded (p > 0) or at a gap of at most
// `touch` (m). On a fresh contact they are the loaded zones, whose pressure falls to zero only at the edge. A worn
// contact near its limit also touches where it carries nothing: the worn flats outside the stick zones sit at zero
// gap and zero pressure (contact/wear_limit.hpp), and reach past the loaded contact to the worn extent. An end of a
// run that is a loaded cell takes that zone's edge (locate_zones); an end at an unloaded cell is its outer cell
// boundary (EdgeMethod::cell_boundary: the gap opens there smoothly, like (x − x_e)^{3/2}, with no square root to
// fit). gap and g0 per cell; +∞ where the pad has no material.
std::vector<Zone> locate_touching(const Grid& grid, std::span<const double> p, std::span<const double> gap,
                                  std::span<const double> g0, double touch);

// The gap below which an unloaded cell counts as touching, as a share of A P (the approach scale of a 2D contact,
// the normal solver's gap scale): 1e-6 A P is 100 times the normal solver's default tolerance on it (the worn flats
// of a run at its limit sit within a few 1e-8 A P of zero: 3–7e-14 m, 2–4e-8 A P, for hertz_wear), and a Hertz contact's gap reaches it
// within 1e-4 a of its edge, inside the first cell of any grid up to 10^4 cells across the contact.
inline constexpr double kTouchingGap = 1e-6;

}  // namespace fretwear
