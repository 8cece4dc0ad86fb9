// The linear complementarity problem LCP(A, q): find z ≥ 0 with w = A z + q ≥ 0 and wᵀz = 0, by Lemke's
// complementary pivoting (Lemke 1965; Cottle, Pang and Stone 1992, "The Linear Complementarity Problem", §4.4).
//
// An artificial variable z₀ with the covering vector e = (1, …, 1) makes w = A z + q + e z₀ feasible at once
// (z₀ = −min q); each pivot then brings in the complement of the variable that last left the basis, the leaving one
// chosen by the ratio test, until z₀ leaves (a solution) or the entering column has no positive entry (a secondary
// ray: the method stops without a solution). For a P-matrix A (every principal minor positive) the solution exists,
// is unique, and the path reaches it without a ray; for other matrices it may or may not. Ties in the ratio test
// go to z₀, then to the lowest row, which is enough for the problems fretwear poses (a degenerate cycle ends at
// max_pivots).
//
// The basis inverse is kept explicitly (n² per pivot), the columns of A read as they enter.
#pragma once

#include <optional>

#include <Eigen/Dense>

namespace fretwear {

struct LcpSolution {
  Eigen::VectorXd z;  // the solution, z ≥ 0
  Eigen::VectorXd w;  // A z + q ≥ 0, zero where z > 0
  int pivots = 0;
};

// The solution of LCP(A, q), or nothing if the pivoting ends on a ray or takes more than max_pivots steps.
// A is square with as many rows as q.
std::optional<LcpSolution> solve_lcp(const Eigen::MatrixXd& A, const Eigen::VectorXd& q, int max_pivots);

}  // namespace fretwear
