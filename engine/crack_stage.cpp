#include "engine/crack_stage.hpp"

#include <algorithm>
#include <cmath>

namespace fretwear {

std::vector<SifSet> crack_sifs(const Grid& grid, const std::vector<Phase>& phases, double x_c,
                               const CrackEffect& effect, double cycles) {
  CrackSolverOptions options;
  options.n_quadrature = effect.quadrature;
  const CrackSolver solver(options, CrackSpec{effect.angle_deg, effect.face_friction});
  std::vector<SifSet> out;
  for (const Phase& ph : phases) {
    const SurfaceTractions t{grid, ph.p, ph.q, ph.sigma_bulk};
    out.push_back({ph.name, cycles, solver.solve(t, x_c, effect.lengths)});
  }
  return out;
}

std::vector<StressMap> stress_maps(const Grid& grid, const std::vector<Phase>& phases, double x_lo, double x_hi,
                                   double depth, const StressEffect& effect) {
  std::vector<StressMap> out;
  for (const Phase& ph : phases) {
    const SurfaceTractions t{grid, ph.p, ph.q, ph.sigma_bulk};
    StressMap m;
    m.phase = ph.name;
    for (int i = 0; i < effect.nx; ++i) m.x.push_back(x_lo + (x_hi - x_lo) * i / (effect.nx - 1));
    // Depths from just below the surface (the surface itself is the traction) to `depth`.
    for (int j = 0; j < effect.ny; ++j) m.y.push_back(depth * (j + 0.5) / effect.ny);
    m.sigma.resize(m.x.size() * m.y.size());
    for (std::size_t i = 0; i < m.x.size(); ++i) {
      const auto column = stress_along_depth(t, m.x[i], m.y);
      for (std::size_t j = 0; j < m.y.size(); ++j) m.sigma[j * m.x.size() + i] = column[j];
      m.surface_sxx.push_back(stress_at(t, m.x[i], 0.0).xx);
    }
    const double mid = 0.5 * (x_lo + x_hi);
    for (std::size_t i = 0; i < m.x.size(); ++i)
      if (m.x[i] <= mid && (i == 0 || m.surface_sxx[i] > m.trailing_peak))
        m.trailing_peak = m.surface_sxx[i], m.trailing_peak_x = m.x[i];
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace fretwear
