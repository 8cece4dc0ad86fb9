#include "engine/wear_contacts.hpp"

#include <cmath>
#include <limits>

#include <boost/math/tools/toms748_solve.hpp>
#include <fmt/format.h>

#include "common/error.hpp"
#include "contact/displacement_limit.hpp"
#include "engine/checkpoint.hpp"
#include "engine/simulation.hpp"

namespace fretwear {

using nlohmann::json;

WearContact::WearContact(const Scene& scene, const Model& model)
    : scene_(scene),
      model_(model),
      P_ref_(scene.P),
      solver_(*model.kernel, worn_options()),
      implicit_solver_(*model.kernel, implicit_options(model.grid.n)) {}

void WearContact::set_gap(std::span<const double> w) {
  const int n = model_.grid.n;
  gap_.resize(n);
  for (int i = 0; i < n; ++i) gap_[i] = model_.g0[i] + w[i];
}

void WearContact::solve_worn(double P, ContactState& state, const char* what) {
  const SolveSummary s = solver_.solve(gap_, P, state);
  ++cycle_solves;
  cycle_iterations += s.iterations;
  if (!s.converged())
    throw ConvergenceError(fmt::format("wear: the {} solve on the worn profile stopped ({}) with residual {:.3g}",
                                       what, to_string(s.termination), s.residual));
}

void WearContact::check_window(const std::vector<double>& p) const {
  if (!(p.front() > 0.0) && !(p.back() > 0.0)) return;
  const Grid& grid = model_.grid;
  throw InputError(fmt::format(
      "grid.window: the worn contact reaches the window's {} end (x = {:.6g} m); the contact widens as it wears "
      "(towards its limit in partial slip, without limit in gross slip): {}, or wear fewer cycles",
      p.front() > 0.0 ? "left" : "right", p.front() > 0.0 ? grid.x_min : grid.x_max,
      model_.window.method == "given"
          ? std::string("widen grid.window")
          : fmt::format("this window, [{:.6g}, {:.6g}] m, is fretwear's choice, sized by the worn contact's limit "
                        "where the cycle has one, and in gross slip by the flat it wears at the first cycle's rate "
                        "(not where a bulk stress dwarfs the friction, nor where the wear speeds up as it goes): give "
                        "grid.window wider than it",
                        grid.x_min, grid.x_max)));
}

bool WearContact::implicit_pressure(std::span<const double> w, std::span<const double> d, std::vector<double>& p) {
  set_gap(w);
  implicit_.p = p;
  const SolveSummary s = implicit_solver_.solve(gap_, P_ref_, implicit_, d);
  ++implicit_solves;
  implicit_iterations += s.iterations;
  if (!s.converged()) {
    last_unconverged = s;
    return false;
  }
  p = implicit_.p;
  return true;
}

json WearContact::counts() const {
  return {{"cycle_solves", cycle_solves},
          {"cycle_iterations", cycle_iterations},
          {"implicit_solves", implicit_solves},
          {"implicit_iterations", implicit_iterations}};
}

void WearContact::restore_counts(const json& j) {
  cycle_solves = j.at("cycle_solves").get<long>();
  cycle_iterations = j.at("cycle_iterations").get<long>();
  implicit_solves = j.at("implicit_solves").get<long>();
  implicit_iterations = j.at("implicit_iterations").get<long>();
}

namespace {

// The search for a displacement-controlled cycle's Q stops at a relative bracket of 2⁻⁴⁰ (1e-12), far below the
// grid's error in Q, or after this many evaluations (toms748 takes about a dozen).
constexpr int kTopBits = 40;
constexpr std::uintmax_t kTopEvaluations = 100;

}  // namespace

AnalogyContactResponse::AnalogyContactResponse(const Scene& scene, const Model& model, const CyclicLoad& load)
    : WearContact(scene, model) {
  tilt_ = load.bulk_strain / load.f;
  Q_ = load.Q_max;
  corrective_load_ = load.P - load.Q_max / load.f;
  if (!(corrective_load_ > 0.0)) throw UnsupportedError(sliding_under_force_control(load.Q_max, load.f * load.P));
}

AnalogyContactResponse::AnalogyContactResponse(const Scene& scene, const Model& model, const CyclicLoad& load,
                                               const ReferenceDatum& datum)
    : WearContact(scene, model), datum_(&datum), delta_(load.delta) {
  if (!(load.delta > 0.0) || load.bulk_strain != 0.0 || !load.history.empty())
    throw std::logic_error("AnalogyContactResponse: a displacement amplitude without bulk strain or history");
}

void AnalogyContactResponse::solve_top_displacement() {
  const double f = *scene_.friction, P = scene_.P;
  std::vector<double> q;
  // δ_top(Q) − δ (contact/displacement_limit.hpp), the corrective solve warm-started from the last one.
  const auto miss = [&](double Q) {
    solve_worn(P - Q / f, corrective_, "corrective");
    return analogy_delta_top(*datum_, f, normal_, corrective_, q) - delta_;
  };
  const double at_limit = analogy_stick_limit(*datum_, f, normal_, gap_, q) - delta_;
  if (!(at_limit > 0.0))
    throw UnsupportedError(fmt::format("effects.wear: the worn contact slides under delta = {:.6g} m (its stick "
                                       "limit is {:.6g} m), which the analogy route cannot follow",
                                       delta_, at_limit + delta_));
  std::uintmax_t evaluations = kTopEvaluations;
  const auto [a, b] = boost::math::tools::toms748_solve(
      [&](double Q) { return Q <= 0.0 ? -delta_ : miss(Q); }, 0.0, f * P, -delta_, at_limit,
      boost::math::tools::eps_tolerance<double>(kTopBits), evaluations);
  if (evaluations >= kTopEvaluations)
    throw ConvergenceError(fmt::format("wear: the search for the Q whose cycle reaches delta = {:.6g} m took {} "
                                       "evaluations without closing its bracket [{:.6g}, {:.6g}] N/m",
                                       delta_, evaluations, a, b));
  Q_ = 0.5 * (a + b);
  corrective_load_ = P - Q_ / f;
}

void AnalogyContactResponse::respond(std::span<const double> w, wear::CycleResponse& out) {
  const Grid& grid = model_.grid;
  const int n = grid.n;
  set_gap(w);
  if (int(out.p.size()) == n) normal_.p = out.p;
  solve_worn(scene_.P, normal_, "normal");
  check_window(normal_.p);
  if (datum_) solve_top_displacement();
  for (int i = 0; i < n; ++i) gap_[i] -= tilt_ * grid.x(i);
  solve_worn(corrective_load_, corrective_, "corrective");
  const double f = *scene_.friction;
  out.p = normal_.p;
  out.s.assign(n, 0.0);
  out.s_touching.clear();  // filled below only where a worn cell carries no pressure
  q_top_.resize(n);  // q = f (p − p*) at the top of the cycle
  for (int i = 0; i < n; ++i) {
    if (corrective_.p[i] > 0.0 && !(normal_.p[i] > 0.0))
      throw UnsupportedError(fmt::format("effects.wear: the worn contact slips backwards at its leading edge (reverse "
                                         "slip at x = {:.6g} m), which the analogy route cannot follow{}",
                                         grid.x(i),
                                         advise_route_ ? "; set effects.tangential.route to \"incremental\"" : ""));
    if (normal_.p[i] > 0.0 && !(corrective_.p[i] > 0.0)) out.s[i] = 4.0 * f * std::max(corrective_.gap[i], 0.0);
    q_top_[i] = f * (normal_.p[i] - corrective_.p[i]);
  }
  // A cell without pressure, worn or not, would slip 4 f (g* − g) on touching: the header says why the step needs it.
  for (int i = 0; i < n; ++i) {
    if (normal_.p[i] > 0.0 || corrective_.p[i] > 0.0 || !std::isfinite(normal_.gap[i])) continue;
    if (out.s_touching.empty()) out.s_touching = out.s;
    out.s_touching[i] = 4.0 * f * std::max(corrective_.gap[i] - normal_.gap[i], 0.0);
  }
  stick_zones_ = locate_zones(grid, corrective_.p, model_.g0);
  out.has_stick = !stick_zones_.empty();
  if (out.has_stick) out.stick_left = stick_zones_.front().left.x, out.stick_right = stick_zones_.back().right.x;
  out.stick_zones.clear();
  if (stick_zones_.size() > 1)
    for (const Zone& z : stick_zones_) out.stick_zones.emplace_back(z.left.x, z.right.x);
}

json AnalogyContactResponse::save() const {
  json j = counts();
  j["normal"] = contact_state_json(normal_);
  j["corrective"] = contact_state_json(corrective_);
  j["implicit"] = contact_state_json(implicit_);
  return j;
}

void AnalogyContactResponse::restore(const json& j) {
  const std::size_t n = std::size_t(cells());
  contact_state_from(j.at("normal"), normal_, n, "the normal solve");
  contact_state_from(j.at("corrective"), corrective_, n, "the corrective solve");
  contact_state_from(j.at("implicit"), implicit_, n, "the contact-implicit solve");
  restore_counts(j);
}

namespace {

// The slip per cycle continued from the contact's cells (p > 0) over the cells out of contact: linear between the
// nearest contact cells on either side, constant beyond the outermost ones. In gross slip every point of the
// specimen's surface slides past the pad by the same rigid 4 × sliding amplitude per cycle, and the elastic part
// varies smoothly along the contact, so a cell that touches during a step travels what its touching neighbours do.
std::vector<double> continued_over_gaps(std::span<const double> p, std::span<const double> s) {
  const int n = int(p.size());
  std::vector<double> out(s.begin(), s.end());
  int prev = -1;
  for (int i = 0; i < n; ++i) {
    if (!(p[i] > 0.0)) continue;
    if (prev < 0)
      std::fill(out.begin(), out.begin() + i, s[i]);
    else
      for (int j = prev + 1; j < i; ++j) out[j] = s[prev] + (s[i] - s[prev]) * double(j - prev) / double(i - prev);
    prev = i;
  }
  if (prev >= 0) std::fill(out.begin() + prev + 1, out.end(), s[prev]);
  return out;
}

// The energy's equivalent slip e / (f p_ref) is capped at this many times the slip travelled (header).
constexpr double kEnergySlipCap = 2.0;

// The lagged coupling may add this share of what one accepted step may err by (header).
constexpr double kLagSafety = 0.5;

// The increments per cycle of the settling march (the first loading takes one, the first cycle four) of a coupled
// response (header).
constexpr int kSettlingIncrements = 4;

IncrementalSlipOptions incremental_options(const Scene& scene, double beta, const CyclicLoad& load) {
  IncrementalSlipOptions o;
  o.increments_per_cycle = scene.tangential->increments;
  if (beta != 0.0) o.cycles = 2;  // as the cycle stage: the first cycle after the first loading is not yet steady
  if (beta != 0.0) o.settling_increments = kSettlingIncrements;
  if (beta != 0.0 && load.history.empty()) o.mirror_half_cycle = true;  // on an even worn gap (header)
  o.normal.proportioning = kWearProportioning;  // the coupled normal solves are on the worn profile
  return o;
}

}  // namespace

IncrementalContactResponse::IncrementalContactResponse(const Scene& scene, const Model& model,
                                                       const CycleStage& cycle, Coupling coupling)
    : IncrementalContactResponse(scene, model, cycle, cycle.plan.load, coupling) {}

IncrementalContactResponse::IncrementalContactResponse(const Scene& scene, const Model& model,
                                                       const CycleStage& cycle, const CyclicLoad& load,
                                                       Coupling coupling)
    : WearContact(scene, model),
      slip_(*model.kernel, incremental_options(scene, cycle.plan.beta, load)),
      datum_(model.grid, model.pair, cycle.reference_x, cycle.reference_depth),
      load_(load),
      beta_(cycle.plan.beta) {
  if (load_.history.empty() && !(load_.delta > 0.0) && !(load_.Q_max < load_.f * load_.P))
    throw UnsupportedError(sliding_under_force_control(load_.Q_max, load_.f * load_.P));
  P_ref_ = load_.P;
  for (const HistoryPoint& pt : load_.history) P_ref_ = std::max(P_ref_, pt.P);
  std::unique_ptr<AnalogyContactResponse> analogy;
  if (coupling == Coupling::lagged && beta_ != 0.0 && load_.history.empty() && !(load_.delta > 0.0))
    analogy = std::make_unique<AnalogyContactResponse>(scene, model, load_);
  // Under displacement control the lag's uncoupled cycle is the analogy's at the Q that reaches δ (header).
  if (coupling == Coupling::lagged && beta_ != 0.0 && load_.history.empty() && load_.delta > 0.0 &&
      load_.bulk_strain == 0.0 && cycle.result.regime == Regime::partial_slip)
    analogy = std::make_unique<AnalogyContactResponse>(scene, model, load_, datum_);
  // Similar bodies under displacement control: the analogy's cycle at the Q that reaches δ (header).
  if (beta_ == 0.0 && load_.delta > 0.0 && load_.history.empty() && load_.bulk_strain == 0.0 &&
      scene.tangential->route == TangentialRoute::automatic && cycle.result.regime == Regime::partial_slip)
    analogy = std::make_unique<AnalogyContactResponse>(scene, model, load_, datum_);
  if (analogy) analogy->falls_back();  // where the analogy gives up, every later response is marched (respond)
  analogy_ = std::move(analogy);
  // Under a load history the lag's uncoupled cycle is the marched one of β = 0 through the same history (header).
  if (coupling == Coupling::lagged && beta_ != 0.0 && !load_.history.empty()) {
    CycleStage uncoupled = cycle;
    uncoupled.plan.beta = 0.0;
    analogy_ = std::make_unique<IncrementalContactResponse>(scene, model, uncoupled, load_, Coupling::every_response);
  }
  tolerance_ = scene.wear ? scene.wear->tolerance : WearEffect{}.tolerance;
}

bool IncrementalContactResponse::respond_by_analogy(std::span<const double> w, wear::CycleResponse& r) {
  const long solves = analogy_->cycle_solves, iterations = analogy_->cycle_iterations;
  try {
    analogy_->respond(w, r);
  } catch (const UnsupportedError& e) {  // it slides or slips backwards: every response marched from now
    analogy_.reset();
    analogy_gave_up_ = e.what();
    return false;
  }
  cycle_solves += analogy_->cycle_solves - solves;
  cycle_iterations += analogy_->cycle_iterations - iterations;
  return true;
}

void IncrementalContactResponse::respond(std::span<const double> w, wear::CycleResponse& out) {
  if (analogy_ && beta_ == 0.0) {  // displacement control, similar bodies: the analogy's response is the cycle's
    if (respond_by_analogy(w, out)) {
      q_top_ = analogy_->shear_top();
      Q_top_ = analogy_->Q_top();
      ++analogy_responses_;
      return;
    }
  } else if (analogy_ && respond_by_analogy(w, uncoupled_) && lag_allowed(w)) {
    respond_lagged(out);
    return;
  }
  respond_coupled(w, out);
  if (analogy_) refresh(w, out);
}

double IncrementalContactResponse::worn_area(std::span<const double> w) const {
  double a = 0.0;
  for (double x : w) a += x;
  return a * model_.grid.h();
}

bool IncrementalContactResponse::lag_allowed(std::span<const double> w) const {
  if (!(gain_ >= 0.0) || !same_stick_zones()) return false;
  const double area = worn_area(w);
  return gain_ * drift() * std::abs(area - area_ref_) <= kLagSafety * tolerance_ * area;
}

double IncrementalContactResponse::drift() const {
  const std::vector<double>& p = uncoupled_.p;
  const std::vector<double>& p_r = uncoupled_ref_.p;
  double moved = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r_r = p_r[i] * uncoupled_ref_.s[i];
    moved += std::abs(p[i] * uncoupled_.s[i] - r_r);
    scale += r_r;
  }
  return scale > 0.0 ? moved / scale : (moved > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
}

bool IncrementalContactResponse::same_stick_zones() const {
  const wear::CycleResponse& a = uncoupled_;
  const wear::CycleResponse& b = uncoupled_ref_;
  if (!(load_.delta > 0.0) && load_.history.empty())
    return a.has_stick == b.has_stick && a.stick_left == b.stick_left && a.stick_right == b.stick_right &&
           a.stick_zones == b.stick_zones;
  // Under displacement control Q moves at every response, and the edges with it within their cells; under a history
  // the marched cycle's edges move with the pressure the worn slip zones leave the stick zone: the same zones are
  // the same cells.
  const Grid& grid = model_.grid;
  const auto cell = [&grid](double x) { return std::floor((x - grid.x_min) / grid.h()); };
  const auto same = [&cell](const Interval& u, const Interval& v) {
    return cell(u.first) == cell(v.first) && cell(u.second) == cell(v.second);
  };
  if (a.has_stick != b.has_stick || a.stick_zones.size() != b.stick_zones.size()) return false;
  if (a.has_stick && !same({a.stick_left, a.stick_right}, {b.stick_left, b.stick_right})) return false;
  for (std::size_t k = 0; k < a.stick_zones.size(); ++k)
    if (!same(a.stick_zones[k], b.stick_zones[k])) return false;
  return true;
}

void IncrementalContactResponse::respond_lagged(wear::CycleResponse& out) {
  const int n = model_.grid.n;
  out.p = uncoupled_.p;
  out.s.assign(n, 0.0);
  for (int i = 0; i < n; ++i)
    if (out.p[i] > 0.0) out.s[i] = std::max(0.0, uncoupled_.s[i] + slip_correction_[i]);
  // Off the contact the slip on touching, corrected alike by the last refresh's share there (none under a history,
  // as the coupled response).
  const std::vector<double>& t_u = uncoupled_.slip_if_touching();
  out.s_touching.clear();
  if (!uncoupled_.s_touching.empty() || !touching_correction_.empty()) {
    out.s_touching = out.s;
    for (int i = 0; i < n; ++i)
      if (!(out.p[i] > 0.0))
        out.s_touching[i] = std::max(0.0, t_u[i] + (touching_correction_.empty() ? 0.0 : touching_correction_[i]));
  }
  out.has_stick = coupled_ref_.has_stick;
  out.stick_left = coupled_ref_.stick_left;
  out.stick_right = coupled_ref_.stick_right;
  out.stick_zones = coupled_ref_.stick_zones;
  const std::vector<double>& q_u = analogy_->shear_top();
  q_top_.resize(n);
  for (int i = 0; i < n; ++i) q_top_[i] = q_u[i] + shear_correction_[i];
  Q_top_ = analogy_->Q_top() + Q_correction_;
  ++lagged_responses_;
}

void IncrementalContactResponse::refresh(std::span<const double> w, const wear::CycleResponse& out) {
  const int n = model_.grid.n;
  // ε: the lagged rate the last correction would have given here, against the coupled one; ρ: the correction's
  // share of the rate.
  double rate = 0.0, correction = 0.0, miss = 0.0;
  for (int i = 0; i < n; ++i) {
    if (!(out.p[i] > 0.0)) continue;
    rate += out.p[i] * out.s[i];
    correction += out.p[i] * std::abs(out.s[i] - uncoupled_.s[i]);
    if (gain_ >= 0.0)
      miss += out.p[i] * std::abs(std::max(0.0, uncoupled_.s[i] + slip_correction_[i]) - out.s[i]);
  }
  if (!(rate > 0.0)) {
    gain_ = -1.0;  // nothing wears here: no correction to measure, couple the next response too
  } else if (gain_ < 0.0) {
    gain_ = correction / rate;  // γ = ρ before any ε is measured
  } else if (same_stick_zones()) {
    const double d = drift();
    if (d > 0.0) gain_ = std::max(miss / rate / d, 0.25 * gain_);  // a lucky ε lengthens the lag by 4 at most
  }
  slip_correction_.resize(n);
  shear_correction_.resize(n);
  const std::vector<double>& q_u = analogy_->shear_top();
  for (int i = 0; i < n; ++i) {
    slip_correction_[i] = out.p[i] > 0.0 ? out.s[i] - uncoupled_.s[i] : 0.0;
    shear_correction_[i] = q_top_[i] - q_u[i];
  }
  // Off the contact, the distance travelled on touching: the coupled cycle's (where it slipped, the slip travelled,
  // not the energy's equivalent) against the analogy's, on every cell with material.
  const std::vector<double>& t_u = uncoupled_.slip_if_touching();
  touching_correction_.clear();  // none where the coupled response gives no slip on touching (a history)
  if (!out.s_touching.empty()) {
    touching_correction_.assign(n, 0.0);
    for (int i = 0; i < n; ++i)
      if (std::isfinite(gap_[i])) touching_correction_[i] = cycle_.slip_if_touching[i] - t_u[i];
  }
  Q_correction_ = Q_top_ - analogy_->Q_top();  // 0 under force control; the coupling's share of Q under δ
  uncoupled_ref_ = uncoupled_;
  coupled_ref_ = out;
  area_ref_ = worn_area(w);
}

void IncrementalContactResponse::respond_coupled(std::span<const double> w, wear::CycleResponse& out) {
  const Grid& grid = model_.grid;
  const int n = grid.n;
  set_gap(w);
  const bool own_reference = P_ref_ != load_.P;  // a history whose largest P is above load.P
  ContactState& ref = own_reference ? reference_ : normal_;
  if (int(out.p.size()) == n) ref.p = out.p;
  if (own_reference) solve_worn(load_.P, normal_, "normal");
  solve_worn(P_ref_, ref, own_reference ? "normal (the history's largest P)" : "normal");
  check_window(ref.p);
  // The worn gap g0 + w for the history's normal solves and the coupled ones (gap_ outlives the call).
  const NormalCoupling coupling{beta_, gap_};
  const IncrementalResult r = load_.history.empty() ? slip_.solve(normal_, load_, &datum_, &coupling)
                                                    : slip_.solve_history(normal_, load_, gap_, &datum_, &coupling);
  cycle_solves += r.n_increments;
  cycle_iterations += r.n_iterations;
  ++coupled_responses_;
  if (r.mirrored) ++mirrored_responses_;
  if (!r.repeated) ++unsteady_responses_;
  cycle_ = r.cycles.back();
  Q_top_ = cycle_.Q_peak;
  if (cycle_.slip_travelled.empty())  // Q ≥ f P at some point of the cycle under force control: the bodies slide
    throw UnsupportedError("effects.wear: " + cycle_.message);
  q_top_ = cycle_.q_top;
  out.p = ref.p;
  const double f = *scene_.friction;
  // The slip the stepper's rate c p s needs: the slip travelled where the pressure is that of P (β = 0, constant P),
  // otherwise the energy's equivalent s = e / (f p_ref) of the header (zero where p_ref = 0); the slip travelled
  // when the caller weighs it by its own pressures (give_slip_travelled()).
  const bool energy = (!load_.history.empty() || beta_ != 0.0) && !slip_travelled_;
  out.s.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    if (!(ref.p[i] > 0.0)) continue;
    out.s[i] = energy ? std::min(cycle_.energy_density[i] / (f * ref.p[i]),
                                 kEnergySlipCap * cycle_.slip_travelled[i])
                      : cycle_.slip_travelled[i];
  }
  out.has_stick = cycle_.stick_zone.has_value();
  out.stick_left = out.stick_right = 0.0;
  if (out.has_stick) out.stick_left = cycle_.stick_zone->first, out.stick_right = cycle_.stick_zone->second;
  out.stick_zones.clear();
  if (out.has_stick && cycle_.stick_zones.size() > 1) out.stick_zones = cycle_.stick_zones;
  // In gross slip a cell out of contact would slide as its neighbours do on touching (wear/implicit_stepper.hpp:
  // lagging it at 0 is what makes the contact-implicit step unstable there). In partial slip it would slip what
  // the cycle moved its surfaces relative to each other (CycleResult::slip_if_touching), as the analogy's 4 f (g* − g)
  // says for similar bodies (AnalogyContactResponse, which says why the step needs it).
  if (cycle_.regime == Regime::gross_slip) {
    // With β ≠ 0 the pressure leans one way at the top and the other at the bottom, so a cell at the contact's end
    // may touch for part of the stroke and travel that part (half the slip, at the end cells). A caller that weighs
    // the slip by pressures of its own (give_slip_travelled) needs what it travels on touching: the slip continued
    // from the cells loaded at both ends of the cycle.
    if (slip_travelled_ && beta_ != 0.0 && r.p_top.size() == std::size_t(n) && r.p_bottom.size() == std::size_t(n)) {
      std::vector<double> throughout(std::size_t(n), 0.0);
      for (int i = 0; i < n; ++i)
        if (ref.p[i] > 0.0 && r.p_top[i] > 0.0 && r.p_bottom[i] > 0.0) throughout[i] = 1.0;
      out.s_touching = continued_over_gaps(throughout, out.s);
      return;
    }
    out.s_touching = continued_over_gaps(ref.p, out.s);
    return;
  }
  // Under a history s is the energy's equivalent e / (f p_ref), and p_ref's contact, that of the largest P, covers
  // every cell that touches in the cycle: a cell beyond it would touch only near that P and slip a share of what
  // its surfaces travel, which the travel would overstate (it made the steps of a history's run rejected the more,
  // 23 → 37 of 113 at 256 cells, 32 → 76 of 139 at 512). Such cells enter by the stepper's own rule for cells that
  // start to wear within a step (wear/implicit_stepper.hpp).
  if (!load_.history.empty()) {
    out.s_touching.clear();
    return;
  }
  out.s_touching = out.s;
  for (int i = 0; i < n; ++i)
    if (!(ref.p[i] > 0.0) && std::isfinite(ref.gap[i])) out.s_touching[i] = cycle_.slip_if_touching[i];
}

namespace {

json response_json(const wear::CycleResponse& r) {
  return {{"p", r.p},
          {"s", r.s},
          {"has_stick", r.has_stick},
          {"stick_left", r.stick_left},
          {"stick_right", r.stick_right},
          {"stick_zones", r.stick_zones}};
}

void response_from(const json& j, wear::CycleResponse& r, std::size_t cells, const std::string& what,
                   bool empty = true) {
  r.p = cell_vector(j.at("p"), cells, what + "'s pressure", empty);
  r.s = cell_vector(j.at("s"), cells, what + "'s slip", empty);
  r.has_stick = j.at("has_stick").get<bool>();
  r.stick_left = j.at("stick_left").get<double>();
  r.stick_right = j.at("stick_right").get<double>();
  j.at("stick_zones").get_to(r.stick_zones);
}

}  // namespace

json IncrementalContactResponse::save() const {
  json j = counts();
  j["route"] = "incremental";
  j["normal"] = contact_state_json(normal_);
  j["implicit"] = contact_state_json(implicit_);
  if (P_ref_ != load_.P) j["reference"] = contact_state_json(reference_);
  j["q_top"] = q_top_;
  j["coupled_responses"] = coupled_responses_;
  j["mirrored_responses"] = mirrored_responses_;
  j["unsteady_responses"] = unsteady_responses_;
  j["lagged_responses"] = lagged_responses_;
  j["analogy_responses"] = analogy_responses_;
  j["analogy_gave_up"] = analogy_gave_up_;
  j["Q_top"] = Q_top_;
  if (analogy_)
    j["lagged"] = {{"analogy", analogy_->save()},
                   {"uncoupled", response_json(uncoupled_)},
                   {"uncoupled_ref", response_json(uncoupled_ref_)},
                   {"coupled_ref", response_json(coupled_ref_)},
                   {"slip_correction", slip_correction_},
                   {"shear_correction", shear_correction_},
                   {"touching_correction", touching_correction_},
                   {"gain", gain_},
                   {"area_ref", area_ref_},
                   {"Q_correction", Q_correction_}};
  return j;
}

void IncrementalContactResponse::restore(const json& j) {
  if (j.value("route", "") != "incremental") throw InputError("checkpoint: written by the analogy route's wear run");
  const std::size_t n = std::size_t(cells());
  contact_state_from(j.at("normal"), normal_, n, "the normal solve");
  contact_state_from(j.at("implicit"), implicit_, n, "the contact-implicit solve");
  if (j.contains("reference")) contact_state_from(j.at("reference"), reference_, n, "the reference solve");
  restore_counts(j);
  if (j.contains("q_top")) q_top_ = cell_vector(j.at("q_top"), n, "the cycle's top shear");
  coupled_responses_ = j.value("coupled_responses", 0L);
  mirrored_responses_ = j.value("mirrored_responses", 0L);
  unsteady_responses_ = j.value("unsteady_responses", 0L);
  lagged_responses_ = j.value("lagged_responses", 0L);
  analogy_responses_ = j.value("analogy_responses", 0L);
  analogy_gave_up_ = j.value("analogy_gave_up", std::string());
  Q_top_ = j.value("Q_top", Q_top_);
  if (!j.contains("lagged")) {
    analogy_.reset();  // written by a run whose every response was coupled
    return;
  }
  if (!analogy_) throw InputError("checkpoint: written by a wear run with the lagged coupling, which this one has not");
  const json& l = j.at("lagged");
  analogy_->restore(l.at("analogy"));
  gain_ = l.at("gain").get<double>();
  // A lag that may go on (γ ≥ 0) reads its references and corrections on every cell; before the first refresh
  // they may be empty. The uncoupled response is the next one's before it is read.
  const bool lagging = gain_ >= 0.0;
  response_from(l.at("uncoupled"), uncoupled_, n, "the lag's uncoupled response");
  response_from(l.at("uncoupled_ref"), uncoupled_ref_, n, "the lag's uncoupled reference", !lagging);
  response_from(l.at("coupled_ref"), coupled_ref_, n, "the lag's coupled reference", !lagging);
  slip_correction_ = cell_vector(l.at("slip_correction"), n, "the lag's slip correction", !lagging);
  shear_correction_ = cell_vector(l.at("shear_correction"), n, "the lag's shear correction", !lagging);
  touching_correction_.clear();  // absent from checkpoints written before the slip on touching was lagged
  if (l.contains("touching_correction"))
    touching_correction_ = cell_vector(l.at("touching_correction"), n, "the lag's correction on touching cells");
  area_ref_ = l.at("area_ref").get<double>();
  Q_correction_ = l.value("Q_correction", 0.0);
}

std::unique_ptr<WearContact> make_wear_contact(const Scene& scene, const Model& model, const CycleStage& cycle) {
  if (cycle.ran != TangentialRoute::incremental)
    return std::make_unique<AnalogyContactResponse>(scene, model, cycle.plan.load);
  return std::make_unique<IncrementalContactResponse>(scene, model, cycle);
}

}  // namespace fretwear
