#include "contact/crack_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "contact/error.hpp"

namespace fretwear {

namespace {

constexpr double kPi = std::numbers::pi;

// k̂(t, s) of the header: the Cauchy term and the free surface's image terms.
double kernel(double t, double s) {
  const double u = 2.0 + t + s, v = 1.0 + s;
  return 1.0 / (t - s) - 1.0 / u - 2.0 * v / (u * u) + 4.0 * v * v / (u * u * u);
}

}  // namespace

std::string CrackSolverOptions::validate() const {
  if (n_quadrature < 2 || n_quadrature > 1000)
    return fmt::format("n_quadrature = {}: must be in [2, 1000]", n_quadrature);
  if (table_points < 8) return fmt::format("table_points = {}: must be at least 8", table_points);
  return {};
}

CrackSolver::CrackSolver(CrackSolverOptions options) : options_(options) {
  if (const std::string m = options_.validate(); !m.empty()) throw InputError("crack solver options: " + m);
  const int N = options_.n_quadrature;
  const double d = 2.0 * N + 1.0;
  s_.resize(N);
  t_.resize(N);
  L1_.resize(N);
  for (int i = 1; i <= N; ++i) {
    const double theta = kPi * (2.0 * i - 1.0) / d;
    s_[i - 1] = std::cos(theta);
    t_[i - 1] = std::cos(2.0 * kPi * i / d);
    // L_i(1) = (2/(2N + 1)) (−1)^{i+1} cot(θ_i/2) cos(θ_i/2)
    const double sign = (i % 2 == 1) ? 1.0 : -1.0;
    L1_[i - 1] = 2.0 / d * sign * std::cos(0.5 * theta) / std::tan(0.5 * theta);
  }
  Eigen::MatrixXd M(N, N);
  for (int k = 0; k < N; ++k)
    for (int i = 0; i < N; ++i) M(k, i) = 2.0 * (1.0 + s_[i]) / d * kernel(t_[k], s_[i]);
  lu_.compute(M);
  // z = −M⁻ᵀ L(1): φ(1) = L(1) · φ = L(1) · M⁻¹(−σ) = z · σ.
  const Eigen::VectorXd L = Eigen::Map<const Eigen::VectorXd>(L1_.data(), N);
  const Eigen::VectorXd z = -Eigen::PartialPivLU<Eigen::MatrixXd>(M.transpose()).solve(L);
  z_.assign(z.data(), z.data() + N);
}

CrackSif CrackSolver::from_loads(double l, std::span<const double> normal, std::span<const double> shear) const {
  double phi_I = 0.0, phi_II = 0.0;
  for (std::size_t k = 0; k < z_.size(); ++k) {
    phi_I += z_[k] * normal[k];
    phi_II += z_[k] * shear[k];
  }
  const double scale = std::sqrt(2.0 * kPi * l);  // K = √(2πl) φ(1)
  CrackSif r;
  r.l = l;
  r.K_I_open = scale * phi_I;
  r.K_II = scale * phi_II;
  r.closed = r.K_I_open < 0.0;
  r.K_I = r.closed ? 0.0 : r.K_I_open;
  return r;
}

CrackSif CrackSolver::sif(double l, const Load& normal, const Load& shear) const {
  if (!(l > 0.0)) throw InputError(fmt::format("crack length {} m: must be > 0", l));
  std::vector<double> n(t_.size()), s(t_.size());
  for (std::size_t k = 0; k < t_.size(); ++k) {
    const double eta = 0.5 * l * (1.0 + t_[k]);
    n[k] = normal ? normal(eta) : 0.0;
    s[k] = shear ? shear(eta) : 0.0;
  }
  return from_loads(l, n, s);
}

std::vector<double> CrackSolver::density(double l, const Load& load) const {
  Eigen::VectorXd rhs(Eigen::Index(t_.size()));
  for (std::size_t k = 0; k < t_.size(); ++k) rhs(Eigen::Index(k)) = -load(0.5 * l * (1.0 + t_[k]));
  const Eigen::VectorXd phi = lu_.solve(rhs);
  return {phi.data(), phi.data() + phi.size()};
}

CrackResult CrackSolver::solve(const SurfaceTractions& t, double x_c, std::span<const double> lengths) const {
  const auto start = std::chrono::steady_clock::now();
  CrackResult result;
  result.x_c = x_c;
  if (lengths.empty()) return result;
  for (double l : lengths)
    if (!(l > 0.0)) throw InputError(fmt::format("crack length {} m: must be > 0", l));
  const double l_max = *std::max_element(lengths.begin(), lengths.end());
  const StressLine line(t, x_c, l_max, options_.table_points);
  std::vector<double> n(t_.size()), s(t_.size());
  result.sifs.reserve(lengths.size());
  for (double l : lengths) {
    for (std::size_t k = 0; k < t_.size(); ++k) {
      const Stress sigma = line.at(0.5 * l * (1.0 + t_[k]));
      n[k] = sigma.xx;
      s[k] = sigma.xy;
    }
    result.sifs.push_back(from_loads(l, n, s));
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace fretwear
