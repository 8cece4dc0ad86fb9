#include "contact/fatigue_life.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>

// Boost 1.74's pchip.hpp calls isnan unqualified in a template; the declaration it needs must be visible where the
// header is read.
using std::isnan;
#include <boost/math/interpolators/pchip.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint.hpp>

#include "common/error.hpp"

namespace fretwear {

double swt_of_life(const InitiationConstants& k, double N) {
  const double two_n = 2.0 * N;
  return k.sigma_f * k.sigma_f / k.E * std::pow(two_n, 2.0 * k.b) + k.sigma_f * k.eps_f * std::pow(two_n, k.b + k.c);
}

double initiation_life(const InitiationConstants& k, double swt) {
  if (!(swt > swt_of_life(k, kMaxLife))) return std::numeric_limits<double>::infinity();
  if (swt >= swt_of_life(k, kMinLife)) return kMinLife;
  // ln SWT(N) − ln swt on ln N: decreasing, one root in (ln kMinLife, ln kMaxLife).
  auto f = [&](double ln_n) { return std::log(swt_of_life(k, std::exp(ln_n))) - std::log(swt); };
  std::uintmax_t iterations = 200;
  const auto [lo, hi] = boost::math::tools::toms748_solve(f, std::log(kMinLife), std::log(kMaxLife),
                                                          boost::math::tools::eps_tolerance<double>(42), iterations);
  return std::exp(0.5 * (lo + hi));
}

double line_average(std::span<const double> y, std::span<const double> v, double ell) {
  if (ell <= 0.0 || y.size() == 1) return v[0];
  double integral = 0.0;
  for (std::size_t j = 1; j < y.size(); ++j) {
    if (y[j - 1] >= ell) break;
    const double y1 = std::min(y[j], ell);
    const double v1 = v[j - 1] + (v[j] - v[j - 1]) * (y1 - y[j - 1]) / (y[j] - y[j - 1]);
    integral += 0.5 * (v[j - 1] + v1) * (y1 - y[j - 1]);
  }
  const double depth = std::min(ell, y.back());
  return depth > 0.0 ? integral / depth : v[0];
}

double el_haddad_length(double dK_th, double delta_sigma_e) {
  const double r = dK_th / (1.12 * delta_sigma_e);
  return r * r / std::numbers::pi;
}

double growth_threshold(const GrowthConstants& g, double a) {
  return g.a0 > 0.0 ? g.dK_th * std::sqrt(a / (a + g.a0)) : g.dK_th;
}

// K/√a against ln a: PCHIP through four points or more, linear through two or three.
struct SifTable::Curve {
  std::vector<double> x, y;
  std::optional<boost::math::interpolators::pchip<std::vector<double>>> pchip;
};

namespace {

std::unique_ptr<SifTable::Curve> make_curve(const std::vector<double>& a, const std::vector<double>& K);

}  // namespace

SifTable::SifTable(std::vector<double> a, std::vector<double> KI_top, std::vector<double> KI_bottom,
                   std::vector<double> KII_top, std::vector<double> KII_bottom)
    : a_(std::move(a)) {
  const std::size_t n = a_.size();
  if (n < 2 || KI_top.size() != n || KI_bottom.size() != n || KII_top.size() != n || KII_bottom.size() != n)
    throw InputError("SIF table: give two lengths or more, and one value of each SIF per length");
  for (std::size_t j = 0; j < n; ++j)
    if (!(a_[j] > 0.0) || (j > 0 && !(a_[j] > a_[j - 1])))
      throw InputError("SIF table: the lengths must be positive and increasing");
  KI_top_ = make_curve(a_, KI_top);
  KI_bottom_ = make_curve(a_, KI_bottom);
  KII_top_ = make_curve(a_, KII_top);
  KII_bottom_ = make_curve(a_, KII_bottom);
}

SifTable::SifTable(SifTable&&) noexcept = default;
SifTable& SifTable::operator=(SifTable&&) noexcept = default;
SifTable::~SifTable() = default;

namespace {

std::unique_ptr<SifTable::Curve> make_curve(const std::vector<double>& a, const std::vector<double>& K) {
  auto c = std::make_unique<SifTable::Curve>();
  for (std::size_t j = 0; j < a.size(); ++j) c->x.push_back(std::log(a[j])), c->y.push_back(K[j] / std::sqrt(a[j]));
  if (a.size() >= 4) c->pchip.emplace(std::vector<double>(c->x), std::vector<double>(c->y));
  return c;
}

}  // namespace

double SifTable::at(const Curve& curve, double a) const {
  a = std::clamp(a, a_.front(), a_.back());
  const double x = std::clamp(std::log(a), curve.x.front(), curve.x.back());
  double k;
  if (curve.pchip) {
    k = (*curve.pchip)(x);
  } else {
    const auto hi = std::upper_bound(curve.x.begin(), curve.x.end() - 1, x);
    const std::size_t j = std::size_t(std::max<std::ptrdiff_t>(1, hi - curve.x.begin()));
    const double t = (x - curve.x[j - 1]) / (curve.x[j] - curve.x[j - 1]);
    k = curve.y[j - 1] + t * (curve.y[j] - curve.y[j - 1]);
  }
  return k * std::sqrt(a);
}

double SifTable::dK_I(double a) const { return at(*KI_top_, a) - at(*KI_bottom_, a); }
double SifTable::dK_II(double a) const { return at(*KII_top_, a) - at(*KII_bottom_, a); }
double SifTable::K_max(double a) const { return std::max(at(*KI_top_, a), at(*KI_bottom_, a)); }

double SifTable::dK(double a, const GrowthConstants& g) const {
  const double dI = std::abs(dK_I(a));
  if (!g.equivalent) return dI;
  const double dII = dK_II(a);
  return std::sqrt(dI * dI + dII * dII);
}

std::string to_string(GrowthFate fate) {
  switch (fate) {
    case GrowthFate::failure: return "failure";
    case GrowthFate::arrest: return "arrest";
    case GrowthFate::runout: return "runout";
  }
  return "runout";
}

namespace {

using GrowthVector = std::array<double, 1>;  // a (m)

// da/dN of one state: C ΔK^m above the threshold, 0 at or below it.
double growth_rate(const GrowthConstants& g, const SifTable& t, double a) {
  const double dK = t.dK(a, g);
  return dK > growth_threshold(g, a) ? g.C * std::pow(dK, g.m) : 0.0;
}

GrowthPoint point(const GrowthConstants& g, const SifTable& t, double N, double a) {
  return {N, a, t.dK_I(a), t.dK_II(a), growth_rate(g, t, a)};
}

// The failure condition at a: ≥ 0 once a reaches a_final or K_max reaches K_c.
double failure_margin(const GrowthConstants& g, const SifTable& t, double a, double a_final) {
  double margin = (a - a_final) / a_final;
  if (g.K_c > 0.0) margin = std::max(margin, (t.K_max(a) - g.K_c) / g.K_c);
  return margin;
}

}  // namespace

GrowthResult grow_crack(const GrowthConstants& g, double a_initial, double a_final, double N_start,
                        std::span<const GrowthState> states, double cycles_max) {
  namespace odeint = boost::numeric::odeint;
  if (states.empty() || states.front().N_from > N_start)
    throw InputError("crack growth: the first state must start at or before the growth's first cycle");
  GrowthResult result;
  const double N_stop = N_start + cycles_max;
  std::size_t k = 0;
  while (k + 1 < states.size() && states[k + 1].N_from <= N_start) ++k;
  double N = N_start, a = a_initial;
  result.path.push_back(point(g, *states[k].table, N, a));
  auto finish = [&](GrowthFate fate, double N_end, double a_end) {
    result.fate = fate;
    result.final_length = a_end;
    result.cycles = fate == GrowthFate::arrest ? std::numeric_limits<double>::infinity() : N_end - N_start;
    if (result.path.back().N != N_end || result.path.back().a != a_end)
      result.path.push_back(point(g, *states[k].table, N_end, a_end));
    return result;
  };
  for (;; ++k) {
    const SifTable& table = *states[k].table;
    const bool last = k + 1 == states.size();
    const double N_next = last ? N_stop : std::min(states[k + 1].N_from, N_stop);
    if (failure_margin(g, table, a, a_final) >= 0.0) return finish(GrowthFate::failure, N, a);
    if (growth_rate(g, table, a) == 0.0) {  // below the threshold here: stalls until the state changes
      if (last) return finish(GrowthFate::arrest, N, a);
      if (N_next >= N_stop) return finish(GrowthFate::runout, N_stop, a);
      N = N_next;
      continue;
    }
    auto system = [&](const GrowthVector& x, GrowthVector& dxdt, double) { dxdt[0] = growth_rate(g, table, x[0]); };
    auto stepper = odeint::make_dense_output(kGrowthTolerance * a_initial, kGrowthTolerance,
                                             odeint::runge_kutta_dopri5<GrowthVector>());
    const double dN0 = std::min(1e-3 * a / growth_rate(g, table, a), N_next - N);
    stepper.initialize(GrowthVector{a}, N, dN0);
    for (;;) {
      stepper.do_step(system);
      const double t0 = stepper.previous_time(), t1 = stepper.current_time();
      const double a1 = stepper.current_state()[0];
      auto a_at = [&](double t) {
        GrowthVector x;
        stepper.calc_state(t, x);
        return x[0];
      };
      const double t_end = std::min(t1, N_next);
      const double a_end = t1 <= N_next ? a1 : a_at(N_next);
      if (failure_margin(g, table, a_end, a_final) >= 0.0) {  // the end lies within the step: locate it
        auto f = [&](double t) { return failure_margin(g, table, a_at(t), a_final); };
        std::uintmax_t iterations = 100;
        const auto [lo, hi] = boost::math::tools::toms748_solve(
            f, t0, t_end, boost::math::tools::eps_tolerance<double>(40), iterations);
        return finish(GrowthFate::failure, hi, a_at(hi));
      }
      a = a_end;
      N = t_end;
      result.path.push_back(point(g, table, N, a));
      if (N >= N_stop) return finish(GrowthFate::runout, N_stop, a);
      if (N >= N_next) break;  // the next state from here
      if (growth_rate(g, table, a) == 0.0) {  // reached the threshold: stalled
        if (last) return finish(GrowthFate::arrest, N, a);
        N = N_next;
        break;
      }
    }
  }
}

}  // namespace fretwear
