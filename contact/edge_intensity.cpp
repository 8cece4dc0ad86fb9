#include "contact/edge_intensity.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Dense>

namespace fretwear {

double edge_power_average(int k, double r0, double r1) {
  assert(0.0 <= r0 && r0 < r1);
  const double e = k + 0.5;
  return (std::pow(r1, e) - std::pow(r0, e)) / (e * (r1 - r0));
}

std::optional<double> edge_intensity(const Grid& grid, std::span<const double> p, double x_edge, int side,
                                     double length, const EdgeIntensityOptions& options) {
  assert(side == 1 || side == -1);
  assert(p.size() == std::size_t(grid.n));
  assert(options.skip >= 0.0 && options.skip < 1.0 && options.terms >= 1);
  const double h = grid.h(), L = length;
  if (!(L > 0.0)) return std::nullopt;
  // The first whole cell on the contact's side; its near boundary lies r_first ∈ [0, h) from the edge.
  const double t = (x_edge - grid.x_min) / h;
  constexpr double kOnBoundary = 1e-9;  // cells: a boundary this close to the edge is the edge
  const int first = side > 0 ? int(std::ceil(t - kOnBoundary)) : int(std::floor(t + kOnBoundary)) - 1;
  const double near = side > 0 ? grid.left(first) : grid.left(first + 1);
  const double r_first = std::abs(near - x_edge) <= kOnBoundary * h ? 0.0 : side * (near - x_edge);
  struct Row {
    int cell;
    double r0, r1;  // in units of L
  };
  std::vector<Row> rows;
  for (int j = 0;; ++j) {
    const int i = first + side * j;
    const double r0 = r_first + j * h, r1 = r0 + h;
    if (i < 0 || i >= grid.n || r1 > L * (1.0 + 1e-12)) break;
    if (r0 >= options.skip * L * (1.0 - 1e-12)) rows.push_back({i, r0 / L, r1 / L});
  }
  const int m = options.terms;
  if (int(rows.size()) < std::max(options.min_cells, m)) return std::nullopt;
  // p = Σ c_k (r/L)^{k − 1/2}, each row scaled by 1 / avg (r/L)^{-1/2}.
  Eigen::MatrixXd M(rows.size(), m);
  Eigen::VectorXd y(rows.size());
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const double scale = 1.0 / edge_power_average(0, rows[j].r0, rows[j].r1);
    for (int k = 0; k < m; ++k) M(j, k) = edge_power_average(k, rows[j].r0, rows[j].r1) * scale;
    y(j) = p[rows[j].cell] * scale;
  }
  const Eigen::VectorXd c = M.colPivHouseholderQr().solve(y);
  // a_0 = c_0 √L, K_N = √(2π) a_0.
  const double K = c(0) * std::sqrt(2.0 * std::numbers::pi * L);
  if (!(K > 0.0)) return std::nullopt;
  return K;
}

}  // namespace fretwear
