#include "engine/body_frames.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "common/error.hpp"
#include "engine/checkpoint.hpp"

namespace fretwear {

using boost::numeric::odeint::controlled_step_result;

FramePositions frame_positions(double U, double h) {
  const int M = std::min(kFrameIntervals, std::max(1, int(std::lround(U / h))));
  FramePositions f;
  const double step = U / (double(M) * h);  // cells between positions
  for (int k = -M; k <= M; ++k) {
    f.shift.push_back(double(k) * step);
    f.weight.push_back((k == -M || k == M) ? 0.25 / M : 0.5 / M);
    f.share.emplace_back(k == -M ? -U / h : (double(k) - 0.5) * step, k == M ? U / h : (double(k) + 0.5) * step);
  }
  return f;
}

std::vector<double> mid_stroke(std::span<const double> z) {
  const std::size_t n = z.size() / 2;
  std::vector<double> w(n);
  for (std::size_t i = 0; i < n; ++i) w[i] = z[i] + z[n + i];
  return w;
}

BodyFrames::BodyFrames(const Model& model, double P, double f, double c_pad, double c_specimen, Respond respond,
                       Amplitude amplitude)
    : model_(model),
      n_(model.grid.n),
      P_(P),
      c_pad_(c_pad),
      c_spec_(c_specimen),
      coupling_(model.pair.A() * model.pair.beta() * f),
      directions_(coupling_ != 0.0 ? 2 : 1),
      coupling_kernel_(model.grid),
      respond_(std::move(respond)),
      amplitude_(std::move(amplitude)),
      solver_(*model.kernel, [&model] {
        NormalSolverOptions o;
        o.proportioning = kWearProportioning;
        o.max_iterations = std::max(2000, model.grid.n);
        return o;
      }()) {}


double BodyFrames::respond(std::span<const double> z, wear::CycleResponse& out) {
  respond_(mid_stroke(z), out);
  const double U = amplitude_();
  lag(out, U);
  return U;
}

void BodyFrames::lag(const wear::CycleResponse& r, double U) {
  s_ = r.slip_if_touching();
  positions_ = frame_positions(U, model_.grid.h());
}

// Pad cell i in position k stands for the pad's passage over the specimen's points [i + a_k, i + b_k] (in cells; cell
// j covers [j − ½, j + ½]), position k's share of the stroke: the specimen is read there as its mean, and the cell's
// wear deposited there evenly, the transpose of that reading. The pressure is so taken constant over each share, and
// the specimen's scar is the stroke's integral, not a sum of 2M + 1 shifted copies of the footprint (deposited at the
// points u_k those rippled the pressure at the positions' spacing). Reading and deposit must be transposes: a
// deposit spread over the share read at its centre point made the every-cycle run unstable at 1024 cells (the
// composite's spectrum, a sinc, goes negative), the specimen alternating by ±30 %. A specimen point beyond the
// window holds no wear; a loaded cell that would deposit there is an error of the window (deposit() throws).
template <class Visit>
void BodyFrames::share_cells(std::size_t k, int i, Visit visit) const {
  const auto [a, b] = positions_.share[k];
  const double lo = double(i) + a, hi = double(i) + b;
  const int first = int(std::floor(lo + 0.5)), last = int(std::floor(hi + 0.5));
  for (int j = first; j <= last; ++j) {
    const double overlap = std::min(hi, double(j) + 0.5) - std::max(lo, double(j) - 0.5);
    if (overlap > 0.0) visit(j, overlap / (hi - lo));
  }
}

void BodyFrames::read(std::span<const double> v, std::size_t k, std::vector<double>& out) const {
  for (int i = 0; i < n_; ++i) {
    double value = 0.0;
    share_cells(k, i, [&](int j, double weight) {
      if (j >= 0 && j < n_) value += weight * v[std::size_t(j)];
    });
    out[std::size_t(i)] += value;
  }
}

void BodyFrames::deposit(std::span<const double> v, std::size_t k, std::span<double> out) const {
  for (int i = 0; i < n_; ++i) {
    const double value = v[std::size_t(i)];
    if (value == 0.0) continue;
    share_cells(k, i, [&](int j, double weight) {
      if (j < 0 || j >= n_)
        throw InputError(fmt::format(
            "wear: the specimen's scar reaches the end of grid.window (the pad slides {:.3g} m each way over the "
            "specimen): {}",
            std::max(std::abs(positions_.share[k].first), std::abs(positions_.share[k].second)) * model_.grid.h(),
            model_.window.method == "given"
                ? std::string("widen grid.window")
                : fmt::format("this window, [{:.6g}, {:.6g}] m, is fretwear's choice, sized for the flat the first "
                              "cycle's rate wears: give grid.window wider than it",
                              model_.grid.x_min, model_.grid.x_max)));
      out[std::size_t(j)] += weight * value;
    });
  }
}

void BodyFrames::gap_at(std::span<const double> z, std::size_t k, std::span<const double> extra,
                        std::vector<double>& g) const {
  g.assign(std::size_t(n_), 0.0);
  read(z.subspan(std::size_t(n_)), k, g);
  for (int i = 0; i < n_; ++i) {
    const std::size_t a = std::size_t(i);
    g[a] += model_.g0[a] + z[a] + (extra.empty() ? 0.0 : extra[a]);
  }
}

void BodyFrames::add_coupling(std::size_t m, std::span<const double> p, std::vector<double>& out) const {
  coupled_.resize(std::size_t(n_));
  coupling_kernel_.apply(p, coupled_, -sign(m) * coupling_);
  for (int i = 0; i < n_; ++i) out[std::size_t(i)] += coupled_[std::size_t(i)];
}

void BodyFrames::pressures(std::span<const double> z, std::vector<std::vector<double>>& p) {
  const std::size_t states = this->states();
  p.resize(states);
  std::vector<double> g, extra(static_cast<std::size_t>(n_));
  ContactState state;
  for (std::size_t m = 0; m < states; ++m) {
    // β ≠ 0: sweeps, the sliding shear's gap from the last pressure (none where D = 1: one solve).
    for (int sweep = 0;; ++sweep) {
      std::fill(extra.begin(), extra.end(), 0.0);
      if (directions_ > 1) add_coupling(m, p[m], extra);
      gap_at(z, position(m), directions_ > 1 ? std::span<const double>(extra) : std::span<const double>(), g);
      state.p = p[m];
      const SolveSummary s = solver_.solve(g, P_, state);
      ++solves_;
      cg_iterations_ += s.iterations;
      if (!s.converged())
        throw ConvergenceError(fmt::format("wear: the normal solve at a position of the stroke stopped ({}) with "
                                           "residual {:.3g}",
                                           to_string(s.termination), s.residual));
      double change = 0.0, largest = 0.0;
      for (int i = 0; i < n_; ++i) {
        const std::size_t a = std::size_t(i);
        change = std::max(change, std::abs(state.p[a] - (a < p[m].size() ? p[m][a] : 0.0)));
        largest = std::max(largest, state.p[a]);
      }
      p[m] = state.p;
      if (directions_ == 1 || change <= kFrameSweepTolerance * largest) break;
      if (sweep + 1 == kFrameSweeps)
        throw ConvergenceError(fmt::format("wear: the sliding pressure at a position of the stroke did not settle "
                                           "under the shear's coupling in {} sweeps (change {:.3g} of its largest)",
                                           kFrameSweeps, change / largest));
    }
  }
}

void BodyFrames::rates(const std::vector<std::vector<double>>& p, std::vector<double>& dz) const {
  dz.assign(std::size_t(2 * n_), 0.0);
  const std::span<double> spec = std::span<double>(dz).subspan(std::size_t(n_));
  deposit_.resize(std::size_t(n_));
  for (std::size_t m = 0; m < p.size(); ++m) {
    const double nu = positions_.weight[position(m)] / double(directions_);
    for (int i = 0; i < n_; ++i) {
      const std::size_t a = std::size_t(i);
      const double pi = std::max(0.0, p[m][a]);
      dz[a] += c_pad_ * nu * pi * s_[a];
      deposit_[a] = c_spec_ * nu * pi * s_[a];
    }
    deposit(deposit_, position(m), spec);
  }
}

bool BodyFrames::euler(std::span<const double> z, double dN, std::vector<std::vector<double>>& p,
                       std::vector<double>& out) {
  const std::size_t K = states();
  const std::size_t n = std::size_t(n_);
  const Eigen::Index size = Eigen::Index(K * n);
  std::vector<double> d(n), dz, extra(n), g;
  for (std::size_t i = 0; i < n; ++i) d[i] = dN * (c_pad_ + c_spec_) * s_[i];
  ContactState state;
  // Anderson's mixing of the passes (docs/METHODS.md): x the iterate, G(x) the pass's result, f = G(x) − x; the next
  // iterate is G(x) − ΔG γ with γ the least-squares fit of f by the last kFrameMemory differences ΔF.
  Eigen::VectorXd x(size), gx(size), f(size), f_last, g_last;
  for (std::size_t k = 0; k < K; ++k)
    for (std::size_t i = 0; i < n; ++i) x[Eigen::Index(k * n + i)] = std::max(0.0, p[k][i]);
  std::vector<Eigen::VectorXd> dF, dG;
  for (int pass = 0; pass < kFramePasses; ++pass) {
    ++iterations_;
    for (std::size_t k = 0; k < K; ++k)
      for (std::size_t i = 0; i < n; ++i) p[k][i] = x[Eigen::Index(k * n + i)];
    rates(p, dz);
    double change = 0.0, largest = 0.0;
    for (std::size_t k = 0; k < K; ++k) {
      // ΔN [R_pad + S_k R_spec] − D p_k at the iterate: what the solve's own shift does not carry; and for β ≠ 0
      // the sliding shear's gap at the iterate.
      std::fill(extra.begin(), extra.end(), 0.0);
      read(std::span<const double>(dz).subspan(n), position(k), extra);
      for (std::size_t i = 0; i < n; ++i) extra[i] = dN * (extra[i] + dz[i]) - d[i] * p[k][i];
      if (directions_ > 1) add_coupling(k, p[k], extra);
      gap_at(z, position(k), extra, g);
      state.p = p[k];
      const SolveSummary s = solver_.solve(g, P_, state, d);
      ++solves_;
      cg_iterations_ += s.iterations;
      if (!s.converged()) {
        last_unconverged = s;
        return false;
      }
      for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Index a = Eigen::Index(k * n + i);
        gx[a] = state.p[i];
        change = std::max(change, std::abs(state.p[i] - p[k][i]));
        largest = std::max(largest, state.p[i]);
      }
    }
    if (change <= kFramePassTolerance * largest) {
      for (std::size_t k = 0; k < K; ++k)
        for (std::size_t i = 0; i < n; ++i) p[k][i] = gx[Eigen::Index(k * n + i)];
      rates(p, dz);
      out.resize(2 * n);
      for (std::size_t i = 0; i < 2 * n; ++i) out[i] = z[i] + dN * dz[i];
      return true;
    }
    f = gx - x;
    if (f_last.size() == size) {
      dF.push_back(f - f_last), dG.push_back(gx - g_last);
      if (int(dF.size()) > kFrameMemory) dF.erase(dF.begin()), dG.erase(dG.begin());
    }
    f_last = f, g_last = gx;
    x = gx;
    if (!dF.empty()) {
      Eigen::MatrixXd F(size, Eigen::Index(dF.size()));
      for (std::size_t c = 0; c < dF.size(); ++c) F.col(Eigen::Index(c)) = dF[c];
      const Eigen::VectorXd gamma = F.colPivHouseholderQr().solve(f);
      for (std::size_t c = 0; c < dG.size(); ++c) x -= gamma[Eigen::Index(c)] * dG[c];
    }
    x = x.cwiseMax(0.0);
  }
  return false;
}

controlled_step_result FramesWearStepper::try_step(std::reference_wrapper<BodyFrames> system, state_type& z,
                                                   time_type& N, time_type& dN) {
  BodyFrames& frames = system.get();
  if (responded_ != z) {
    response_.p = p_start_.empty() ? std::vector<double>{} : p_start_[p_start_.size() / 2];
    amplitude_ = frames.respond(z, response_);
    ++stats_.responses;
    responded_ = z;
  } else {
    frames.lag(response_, amplitude_);
  }
  const std::size_t K = frames.states();
  if (p_start_.size() != K) {
    p_start_.assign(K, response_.p);
    frames.pressures(z, p_start_);
  }

  // The half step first; the full step starts its passes from the half step's pressures extrapolated to ΔN.
  std::vector<std::vector<double>> p_half = p_start_, p_full;
  state_type z_full, z_half, z_two;
  bool solved = frames.euler(z, 0.5 * dN, p_half, z_half);
  if (solved) {
    p_full = p_half;
    for (std::size_t k = 0; k < K; ++k)
      for (std::size_t i = 0; i < p_full[k].size(); ++i)
        p_full[k][i] = std::max(0.0, 2.0 * p_half[k][i] - p_start_[k][i]);
    solved = frames.euler(z, dN, p_full, z_full);
  }
  if (solved) {
    wear::CycleResponse r;
    r.p = response_.p;
    frames.respond(z_half, r);
    ++stats_.responses;
    std::vector<std::vector<double>> p_mid = p_half;
    if (p_mid.size() != frames.states()) p_mid.assign(frames.states(), r.p);
    else
      for (std::size_t k = 0; k < K; ++k)
        for (std::size_t i = 0; i < p_mid[k].size(); ++i)
          p_mid[k][i] = std::max(0.0, 2.0 * p_half[k][i] - p_start_[k][i]);
    solved = frames.euler(z_half, 0.5 * dN, p_mid, z_two);
    if (solved) p_half = std::move(p_mid);
  }
  if (!solved) {
    ++stats_.rejected;
    ++stats_.unconverged;
    if (dN <= 1.0)
      throw ConvergenceError(fmt::format("wear: the implicit step of the two bodies' frames did not converge at "
                                         "cycle {:.0f} even for a jump of {:.3g} cycles (residual {:.3g})",
                                         N, dN, frames.last_unconverged.residual));
    dN *= 0.25;
    return controlled_step_result::fail;
  }
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < z.size(); ++i) {
    scale = std::max(scale, std::abs(z_two[i]));
    diff = std::max(diff, std::abs(z_two[i] - z_full[i]));
  }
  const double err = scale > 0.0 ? diff / (tolerance_ * scale) : 0.0;
  stats_.last_error = err;
  if (!(err <= 1.0)) {
    ++stats_.rejected;
    if (dN < wear::kMinJump)
      throw ConvergenceError(fmt::format("wear: the two bodies' frames' error estimate does not fall with the jump "
                                         "(error {:.3g} times the tolerance {:.3g} at a jump of {:.3g} cycles, at "
                                         "cycle {:.6g})",
                                         err, tolerance_, dN, N));
    dN *= std::clamp(0.9 / std::sqrt(err), 0.2, 0.9);
    return controlled_step_result::fail;
  }
  for (std::size_t i = 0; i < z.size(); ++i) z[i] = std::max(z[i], 2.0 * z_two[i] - z_full[i]);
  N += dN;
  dN *= err > 0.0 ? std::clamp(0.9 / std::sqrt(err), 1.0, 4.0) : 4.0;
  ++stats_.accepted;
  p_start_ = std::move(p_half);
  return controlled_step_result::success;
}

nlohmann::json FramesWearStepper::save() const {
  nlohmann::json p = nlohmann::json::array();
  for (const auto& v : p_start_) p.push_back(blob(v));
  return {{"accepted", stats_.accepted},     {"rejected", stats_.rejected}, {"unconverged", stats_.unconverged},
          {"responses", stats_.responses},   {"last_error", stats_.last_error}, {"p_start", std::move(p)}};
}

void FramesWearStepper::restore(const nlohmann::json& j, std::size_t cells) {
  stats_.accepted = j.at("accepted").get<int>();
  stats_.rejected = j.at("rejected").get<int>();
  stats_.unconverged = j.at("unconverged").get<int>();
  stats_.responses = j.at("responses").get<int>();
  stats_.last_error = j.at("last_error").get<double>();
  p_start_.clear();
  for (const auto& v : j.at("p_start")) p_start_.push_back(cell_vector(v, cells, "a position's warm start", false));
}

void FramesRateSystem::operator()(const std::vector<double>& z, std::vector<double>& dz, double /*N*/) {
  wear::CycleResponse r;
  if (!p_.empty()) r.p = p_[p_.size() / 2];
  frames_->respond(z, r);
  ++evaluations_;
  if (p_.size() != frames_->states()) p_.assign(frames_->states(), r.p);
  frames_->pressures(z, p_);
  frames_->rates(p_, dz);
  rate_ = dz;
}

nlohmann::json FramesRateSystem::save() const {
  nlohmann::json p = nlohmann::json::array();
  for (const auto& v : p_) p.push_back(blob(v));
  return {{"evaluations", evaluations_}, {"rate", blob(rate_)}, {"p", std::move(p)},
          {"solves", frames_->solves()}, {"iterations", frames_->iterations()},
          {"cg_iterations", frames_->cg_iterations()}};
}

void FramesRateSystem::restore(const nlohmann::json& j, std::size_t cells, std::size_t state_size) {
  evaluations_ = j.at("evaluations").get<long>();
  rate_ = cell_vector(j.at("rate"), state_size, "the last rate");
  p_.clear();
  for (const auto& v : j.at("p")) p_.push_back(cell_vector(v, cells, "a position's pressure", false));
  frames_->count(j.at("solves").get<long>(), j.at("iterations").get<long>(), j.at("cg_iterations").get<long>());
}

controlled_step_result FramesCycleByCycle::try_step(std::reference_wrapper<BodyFrames> system, state_type& z,
                                                    double& N, double& dN) {
  BodyFrames& frames = system.get();
  wear::CycleResponse r;
  frames.respond(z, r);
  ++responses;
  if (p_.size() != frames.states()) p_.assign(frames.states(), r.p);
  frames.pressures(z, p_);
  std::vector<double> dz;
  frames.rates(p_, dz);
  for (std::size_t i = 0; i < z.size(); ++i) z[i] += dN * dz[i];
  N += dN;
  return controlled_step_result::success;
}

}  // namespace fretwear
