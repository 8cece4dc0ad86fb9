// A uniform grid of n cells over the window [x_min, x_max]; cell i spans [x_min + i h, x_min + (i + 1) h] and
// carries a constant traction; its collocation point is the centre.
#pragma once

#include <cassert>

namespace fretwear {

struct Grid {
  double x_min = 0.0;  // m
  double x_max = 0.0;  // m
  int n = 0;           // cells

  double h() const { return (x_max - x_min) / n; }          // cell width (m)
  double x(int i) const { return x_min + (i + 0.5) * h(); }  // centre of cell i (m)
  double left(int i) const { return x_min + i * h(); }       // left boundary of cell i (m)
  double width() const { return x_max - x_min; }
};

}  // namespace fretwear
