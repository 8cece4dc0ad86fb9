#include "contact/coupling_kernel.hpp"

#include <algorithm>
#include <cassert>

namespace fretwear {

double CouplingKernel::coefficient(double x, int j) const {
  const double lo = grid_.left(j), hi = lo + grid_.h();
  // ∫_lo^hi sgn(x − ξ) dξ = (min(x, hi) − lo)⁺ − (hi − max(x, lo))⁺
  const double below = std::max(std::min(x, hi) - lo, 0.0), above = std::max(hi - std::max(x, lo), 0.0);
  return 0.5 * (below - above);
}

void CouplingKernel::apply(std::span<const double> t, std::span<double> u, double scale) const {
  const int n = grid_.n;
  assert(int(t.size()) == n && int(u.size()) == n && t.data() != u.data());
  double total = 0.0;
  for (int j = 0; j < n; ++j) total += t[j];
  // u_i = (h/2)(Σ_{j<i} t_j − Σ_{j>i} t_j) = (h/2)(2 Σ_{j<i} t_j + t_i − total)
  const double c = 0.5 * grid_.h() * scale;
  double before = 0.0;
  for (int i = 0; i < n; ++i) {
    u[i] = c * (2.0 * before + t[i] - total);
    before += t[i];
  }
}

}  // namespace fretwear
