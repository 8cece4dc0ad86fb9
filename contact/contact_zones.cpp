#include "contact/contact_zones.hpp"

#include <algorithm>
#include <cmath>

namespace fretwear {

std::string to_string(EdgeMethod m) {
  switch (m) {
    case EdgeMethod::square_root_fit: return "square_root_fit";
    case EdgeMethod::corner: return "corner";
    case EdgeMethod::cell_boundary: return "cell_boundary";
  }
  return "?";
}

namespace {

// Edge of a zone on the side `dir` (+1 right, −1 left) whose outermost loaded cell is `last`.
Edge locate_edge(const Grid& grid, std::span<const double> p, std::span<const double> g0, int first, int last,
                 int dir) {
  const int n = grid.n;
  const int beyond = last + dir;
  const double boundary = dir > 0 ? grid.left(last + 1) : grid.left(last);
  // The window's end is not a corner: a zone cut by it is reported at the cell boundary, and callers treat a zone
  // reaching an end of the grid without a corner as clipped.
  if (beyond < 0 || beyond >= n) return {boundary, EdgeMethod::cell_boundary};
  if (!std::isfinite(g0[beyond])) return {boundary, EdgeMethod::corner};
  const int size = std::abs(last - first) + 1;
  if (size < 4) return {boundary, EdgeMethod::cell_boundary};
  // p² is linear near a square-root edge: extrapolate it from the two cells inside the outermost one.
  const int i1 = last - dir, i2 = last - 2 * dir;
  const double q1 = p[i1] * p[i1], q2 = p[i2] * p[i2];
  if (!(q2 > q1)) return {boundary, EdgeMethod::cell_boundary};
  const double x = grid.x(i1) + (grid.x(i1) - grid.x(i2)) * q1 / (q2 - q1);
  // The fit must land in the outermost cell or its outer neighbour; otherwise the pressure is not square-root there.
  const double lo = dir > 0 ? grid.left(last) : grid.left(last - 1);
  const double hi = dir > 0 ? grid.left(last + 2) : grid.left(last + 1);
  if (x < lo || x > hi) return {boundary, EdgeMethod::cell_boundary};
  return {x, EdgeMethod::square_root_fit};
}

}  // namespace

std::vector<Zone> locate_zones(const Grid& grid, std::span<const double> p, std::span<const double> g0) {
  std::vector<Zone> zones;
  const int n = grid.n;
  for (int i = 0; i < n;) {
    if (!(p[i] > 0.0)) {
      ++i;
      continue;
    }
    int j = i;
    while (j + 1 < n && p[j + 1] > 0.0) ++j;
    Zone z;
    z.first_cell = i;
    z.last_cell = j;
    z.left = locate_edge(grid, p, g0, j, i, -1);
    z.right = locate_edge(grid, p, g0, i, j, +1);
    zones.push_back(z);
    i = j + 1;
  }
  return zones;
}

std::vector<Zone> locate_touching(const Grid& grid, std::span<const double> p, std::span<const double> gap,
                                  std::span<const double> g0, double touch) {
  const std::vector<Zone> loaded = locate_zones(grid, p, g0);
  auto edge_of = [&loaded](int cell, bool right) -> const Edge* {
    for (const Zone& z : loaded)
      if ((right ? z.last_cell : z.first_cell) == cell) return right ? &z.right : &z.left;
    return nullptr;
  };
  std::vector<Zone> zones;
  const int n = grid.n;
  auto touches = [&](int i) { return p[i] > 0.0 || gap[i] <= touch; };
  for (int i = 0; i < n;) {
    if (!touches(i)) {
      ++i;
      continue;
    }
    int j = i;
    while (j + 1 < n && touches(j + 1)) ++j;
    Zone z;
    z.first_cell = i;
    z.last_cell = j;
    const Edge* l = edge_of(i, false);
    const Edge* r = edge_of(j, true);
    z.left = l ? *l : Edge{grid.left(i), EdgeMethod::cell_boundary};
    z.right = r ? *r : Edge{grid.left(j + 1), EdgeMethod::cell_boundary};
    zones.push_back(z);
    i = j + 1;
  }
  return zones;
}

}  // namespace fretwear
