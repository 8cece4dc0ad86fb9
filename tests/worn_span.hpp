// Where a worn depth profile is worn: the outer ends of the cells with w > 0 on its grid, for tests that check a worn
// contact against its window.
#pragma once

#include <optional>
#include <utility>
#include <vector>

#include "contact/grid.hpp"

namespace fretwear::test {

// {left end of the first worn cell, right end of the last} (m); empty when nothing is worn.
inline std::optional<std::pair<double, double>> worn_span(const Grid& grid, const std::vector<double>& w) {
  int first = -1, last = -1;
  for (int i = 0; i < grid.n; ++i)
    if (w[std::size_t(i)] > 0.0) last = i, first = first < 0 ? i : first;
  if (first < 0) return std::nullopt;
  return std::pair{grid.left(first), grid.left(last + 1)};
}

}  // namespace fretwear::test
