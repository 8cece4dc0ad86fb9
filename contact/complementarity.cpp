#include "contact/complementarity.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace fretwear {

std::optional<LcpSolution> solve_lcp(const Eigen::MatrixXd& A, const Eigen::VectorXd& q, int max_pivots) {
  const Eigen::Index n = q.size();
  LcpSolution out;
  if (n == 0 || q.minCoeff() >= 0.0) {
    out.z = Eigen::VectorXd::Zero(n);
    out.w = q;
    return out;
  }
  // Variables 0..n−1 are w, n..2n−1 are z, 2n is z₀; their columns in I w − A z − e z₀ = q.
  const Eigen::Index z0 = 2 * n;
  const auto column = [&](Eigen::Index v) -> Eigen::VectorXd {
    if (v < n) return Eigen::VectorXd::Unit(n, v);
    if (v < z0) return -A.col(v - n);
    return -Eigen::VectorXd::Ones(n);
  };
  std::vector<Eigen::Index> basis(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) basis[std::size_t(i)] = i;
  Eigen::MatrixXd Binv = Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd x = q;  // the basic variables' values

  const auto pivot = [&](Eigen::Index r, Eigen::Index entering, const Eigen::VectorXd& d) {
    const double theta = x(r) / d(r);
    x -= theta * d;
    x(r) = theta;
    Binv.row(r) /= d(r);
    for (Eigen::Index i = 0; i < n; ++i)
      if (i != r) Binv.row(i) -= d(i) * Binv.row(r);
    const Eigen::Index leaving = basis[std::size_t(r)];
    basis[std::size_t(r)] = entering;
    return leaving;
  };

  // z₀ enters at the row of the most negative q: every w is then ≥ 0.
  Eigen::Index r0 = 0;
  q.minCoeff(&r0);
  Eigen::Index leaving = pivot(r0, z0, Binv * column(z0));
  for (int it = 1; it <= max_pivots; ++it) {
    const Eigen::Index entering = leaving < n ? leaving + n : leaving - n;
    const Eigen::VectorXd d = Binv * column(entering);
    const double eps = 1e-12 * d.cwiseAbs().maxCoeff();
    // The lexicographic ratio test: the least (x_i, (B⁻¹)_i·)/d_i in lexicographic order, z₀'s row first among
    // exact ties, keeps a degenerate problem from cycling (Cottle, Pang and Stone 1992, §4.9).
    Eigen::Index r = -1;
    const auto before = [&](Eigen::Index i, Eigen::Index k) {  // row i before row k
      const double a = std::max(x(i), 0.0) / d(i), b = std::max(x(k), 0.0) / d(k);
      const double tol = 1e-9 * std::max(a, b);
      if (a < b - tol) return true;
      if (a > b + tol) return false;
      if (basis[std::size_t(i)] == z0) return true;
      if (basis[std::size_t(k)] == z0) return false;
      for (Eigen::Index j = 0; j < n; ++j) {
        const double u = Binv(i, j) / d(i), v = Binv(k, j) / d(k);
        const double t = 1e-9 * std::max(std::abs(u), std::abs(v));
        if (u < v - t) return true;
        if (u > v + t) return false;
      }
      return i < k;
    };
    for (Eigen::Index i = 0; i < n; ++i)
      if (d(i) > eps && (r < 0 || before(i, r))) r = i;
    if (r < 0) return std::nullopt;  // a secondary ray
    leaving = pivot(r, entering, d);
    // The basis inverse drifts by rounding with each update: it is formed again from the basis every 32 pivots and
    // at the end.
    if (it % 32 == 0 || leaving == z0) {
      Eigen::MatrixXd B(n, n);
      for (Eigen::Index i = 0; i < n; ++i) B.col(i) = column(basis[std::size_t(i)]);
      const Eigen::PartialPivLU<Eigen::MatrixXd> lu(B);
      Binv = lu.inverse();
      x = lu.solve(q);
    }
    if (leaving == z0) {
      out.z = Eigen::VectorXd::Zero(n);
      for (Eigen::Index i = 0; i < n; ++i) {
        const Eigen::Index v = basis[std::size_t(i)];
        if (v >= n && v < z0) out.z(v - n) = std::max(x(i), 0.0);
      }
      out.w = A * out.z + q;
      out.pivots = it + 1;
      return out;
    }
  }
  return std::nullopt;
}

}  // namespace fretwear
