#include "contact/crack_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <optional>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "common/error.hpp"
#include "contact/complementarity.hpp"

namespace fretwear {

namespace {

constexpr double kPi = std::numbers::pi;
// The largest violation, relative to the load, of a contact set kept when the active set cycles.
constexpr double kCycleTolerance = 1e-3;
using Complex = std::complex<double>;

// PHYSICS.md's kernel of a crack normal to the surface: the Cauchy term and the free surface's image terms.
double normal_kernel(double t, double s) {
  const double u = 2.0 + t + s, v = 1.0 + s;
  return 1.0 / (t - s) - 1.0 / u - 2.0 * v / (u * u) + 4.0 * v * v / (u * u * u);
}

// (cos α, sin α), exact at α = 90°.
std::pair<double, double> direction(double angle_deg) {
  const double d = (90.0 - angle_deg) * kPi / 180.0;
  return {std::sin(d), std::cos(d)};
}

// σ at z of the half-plane dislocation at z0 with γ = (b_y − i b_x)/2, in units of 2μ/(π(κ + 1)) (header).
Stress dislocation_stress(Complex z, Complex z0, Complex g) {
  const Complex zb0 = std::conj(z0), gb = std::conj(g), d = zb0 - z0;
  const Complex a = 1.0 / (z - z0), c = 1.0 / (z - zb0);
  const Complex Phi = g * (a - c) + gb * d * c * c;
  const Complex dPhi = g * (c * c - a * a) - 2.0 * gb * d * c * c * c;
  const Complex Phib = gb * (c - a) - g * d * a * a;  // conj Φ(z̄)
  const double S1 = 4.0 * Phi.real();
  const Complex S2 = 2.0 * ((std::conj(z) - z) * dPhi - Phi - Phib);
  return {0.5 * (S1 - S2.real()), 0.5 * (S1 + S2.real()), 0.5 * S2.imag()};
}

// (σ_n, τ) on a line at (cos α, sin α) = (c, s): header.
std::pair<double, double> resolve(const Stress& x, double c, double s) {
  return {x.xx * s * s + x.yy * c * c - 2.0 * x.xy * s * c, (x.xx - x.yy) * s * c - x.xy * (c * c - s * s)};
}

}  // namespace

CrackKernel crack_kernel(double angle_deg, double t, double s) {
  const auto [c, sn] = direction(angle_deg);
  const Complex e(c, sn), z = (1.0 + t) * e, z0 = (1.0 + s) * e;
  // b = −n̂ (opening): γ = e/2;  b = −t̂ (sliding): γ = i e/2.
  const auto [n1, t1] = resolve(dislocation_stress(z, z0, 0.5 * e), c, sn);
  const auto [n2, t2] = resolve(dislocation_stress(z, z0, Complex(0.0, 0.5) * e), c, sn);
  return {{{n1, n2}, {t1, t2}}};
}

std::string CrackSolverOptions::validate() const {
  if (n_quadrature < 2 || n_quadrature > 1000)
    return fmt::format("n_quadrature = {}: must be in [2, 1000]", n_quadrature);
  if (max_contact_iterations < 1)
    return fmt::format("max_contact_iterations = {}: must be at least 1", max_contact_iterations);
  return {};
}

std::string CrackSpec::validate() const {
  if (!(angle_deg >= kMinAngle && angle_deg <= 180.0 - kMinAngle))
    return fmt::format("angle_deg = {}: must be in [{}, {}] degrees", angle_deg, kMinAngle, 180.0 - kMinAngle);
  if (!(face_friction >= 0.0) || !std::isfinite(face_friction))
    return fmt::format("face_friction = {}: must be a finite number >= 0", face_friction);
  return {};
}

CrackSolver::CrackSolver(CrackSolverOptions options, CrackSpec crack) : options_(options), crack_(crack) {
  if (const std::string m = options_.validate(); !m.empty()) throw InputError("crack solver options: " + m);
  if (const std::string m = crack_.validate(); !m.empty()) throw InputError("crack: " + m);
  const int N = options_.n_quadrature;
  const double d = 2.0 * N + 1.0;
  s_.resize(N);
  t_.resize(N);
  L1_.resize(N);
  std::vector<double> theta(N);
  for (int i = 1; i <= N; ++i) {
    theta[i - 1] = kPi * (2.0 * i - 1.0) / d;
    s_[i - 1] = std::cos(theta[i - 1]);
    t_[i - 1] = std::cos(2.0 * kPi * i / d);
    // L_i(1) = (2/(2N + 1)) (−1)^{i+1} cot(θ_i/2) cos(θ_i/2)
    const double sign = (i % 2 == 1) ? 1.0 : -1.0;
    L1_[i - 1] = 2.0 / d * sign * std::cos(0.5 * theta[i - 1]) / std::tan(0.5 * theta[i - 1]);
  }
  uncoupled_ = crack_.angle_deg == 90.0;
  M_ = Eigen::MatrixXd::Zero(2 * N, 2 * N);
  for (int k = 0; k < N; ++k)
    for (int i = 0; i < N; ++i) {
      const double W = 2.0 * (1.0 + s_[i]) / d;
      if (uncoupled_) {
        M_(k, i) = M_(N + k, N + i) = W * normal_kernel(t_[k], s_[i]);
      } else {
        const CrackKernel K = crack_kernel(crack_.angle_deg, t_[k], s_[i]);
        M_(k, i) = W * K[0][0];
        M_(k, N + i) = W * K[0][1];
        M_(N + k, i) = W * K[1][0];
        M_(N + k, N + i) = W * K[1][1];
      }
    }
  if (uncoupled_)
    lu_.compute(M_.topLeftCorner(N, N));
  else
    lu_.compute(M_);
  // Q_ki = ∫_{t_k}^1 w L_i ds: the interpolant Σ_j a_j V_j with a_j = Σ_i W_i V_j(s_i) φ_i (Gauss–Jacobi is exact
  // for V_j V_m, ∫ w V_j V_m = π δ_jm), and ∫_t^1 w V_j ds = sin((j + 1)θ)/(j + 1) + sin(jθ)/j (θ for j = 0).
  Eigen::MatrixXd I(N, N), V(N, N);
  for (int k = 0; k < N; ++k) {
    const double th = 2.0 * kPi * (k + 1) / d;
    for (int j = 0; j < N; ++j) I(k, j) = std::sin((j + 1) * th) / (j + 1) + (j == 0 ? th : std::sin(j * th) / j);
  }
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i)
      V(j, i) = 2.0 * (1.0 + s_[i]) / d * std::cos((j + 0.5) * theta[i]) / std::cos(0.5 * theta[i]);
  Q_ = I * V;
}

Eigen::VectorXd CrackSolver::open_density(const Eigen::VectorXd& rhs) const {
  if (!uncoupled_) return lu_.solve(rhs);
  const Eigen::Index N = Eigen::Index(s_.size());
  Eigen::VectorXd phi(2 * N);
  phi.head(N) = lu_.solve(rhs.head(N));
  phi.tail(N) = lu_.solve(rhs.tail(N));
  return phi;
}

namespace {

// Every active-set pass changes all the violating points up to this many passes, then only the worst one.
constexpr int kAllAtOnce = 20;
// Lemke's pivots allowed per unknown of the complementarity problem (about one took the shallow cracks whose passes
// cycled).
constexpr int kMaxPivots = 50;

// The contact of the crack faces at the collocation points by an active set (header, "Face contact"): each point
// open (0), stuck (1) or slipping (±2, with the sign of the slip h). On a set the closed points' rows of M φ = −σ
// become g(t_k) = 0 and either h(t_k) = 0 (stick) or T = f p sign(h) (slip).
class FaceContact {
 public:
  FaceContact(const Eigen::MatrixXd& M, const Eigen::MatrixXd& Q, const Eigen::Map<const Eigen::VectorXd>& L,
              const Eigen::VectorXd& sigma, double friction, double scale, double tol, double tol_K)
      : M_(M), Q_(Q), L_(L), sigma_(sigma), N_(Q.rows()), f_(friction), scale_(scale), tol_(tol), tol_K_(tol_K) {
    Tn = Eigen::VectorXd::Zero(N_);
    Tt = Eigen::VectorXd::Zero(N_);
  }

  // The open crack's set, from its density phi: closed where its faces overlap (g < 0) and at the tip if
  // K_I_open < 0. Returns whether any point closed.
  bool close_overlaps(double K_I_open);
  // Pass after pass from the present set until no inequality is violated (true), a set met before closes a cycle,
  // or max_passes run out (false). The passes add to `passes`; a cycle's least violating set is kept aside for
  // keep_cycle_best().
  bool settle(int max_passes);
  // The set the contact's linear complementarity problem gives (header), the starting set of a settle() that has
  // met a cycle; false if the pivoting found no solution.
  bool complementary_set();
  // Passes from the complementarity problem's set again: without friction with its closed points sliding the way
  // the faces do, then also with the points it was not posed on (the mouth's, whose own compliance is not positive)
  // held in the state it gave them and their inequalities left unchecked. False if it was not solved or neither
  // settles.
  bool settle_again(int max_passes);
  // A cycle's least violating set and its solution, if its violation is below kCycleTolerance of the load.
  bool keep_cycle_best(double load);
  // The sliding density of the least violating set of the cycles met so far (empty if none).
  Eigen::VectorXd cycle_best_slide() const { return cycle_best_ ? cycle_best_->phi.tail(N_) : Eigen::VectorXd(); }

  std::vector<int> state;   // 0 open, 1 stick, ±2 slip with sign(h) = ±1
  Eigen::VectorXd phi;      // (φ₁, φ₂) at the nodes (Pa)
  Eigen::VectorXd Tn, Tt;   // the total normal and shear traction across the faces, σ + M φ (Pa)
  Eigen::VectorXd g, h;     // the opening and the slip integrals Q φ₁, Q φ₂ at the collocation points (Pa)
  double K_I = 0.0;         // √(2πl) φ₁(1) (Pa√m)
  int passes = 0;
  // When settle() fails: whether it met a cycle of sets, and the least violation of the sets it tried (Pa).
  bool cycled = false;
  double least_violation = std::numeric_limits<double>::infinity();
  // Whether the complementarity problem was solved (0 not tried, 1 solved, −1 no solution found).
  int complementarity = 0;

 private:
  // A set tried, with its solution and its largest violation.
  struct Pass {
    std::vector<int> state;
    Eigen::VectorXd phi;
    double worst;
  };

  // The state of a point that closes: it keeps sliding the way the faces were sliding there (h); it sticks only with
  // friction and no slip to follow.
  int closing(double slip) const { return slip > 0.0 ? 2 : slip < 0.0 ? -2 : f_ > 0.0 ? 1 : 2; }
  // φ, the tractions, g, h and K_I on the current set.
  void solve_on_set();
  // The density φ, and from it the tractions, g, h and K_I.
  void take(const Eigen::VectorXd& density);
  // Every violated inequality, by how much (Pa), and in next the state that removes it.
  std::vector<std::pair<double, Eigen::Index>> violations(std::vector<int>& next) const;
  std::optional<Pass> cycle_best_;  // the least violating set of the cycles met
  std::vector<int> complementary_state_;  // the complementarity problem's set
  std::vector<int> signed_state_;         // the same, frictionless closed points sliding the way the faces do
  std::vector<Eigen::Index> mouth_;       // the points it was not posed on
  bool mouth_held_ = false;               // settle() leaves mouth_'s inequalities unchecked

  const Eigen::MatrixXd& M_;
  const Eigen::MatrixXd& Q_;
  const Eigen::Map<const Eigen::VectorXd>& L_;
  const Eigen::VectorXd& sigma_;
  const Eigen::Index N_;
  const double f_, scale_, tol_, tol_K_;
};

bool FaceContact::close_overlaps(double K_I_open) {
  state.assign(std::size_t(N_), 0);
  g = Q_ * phi.head(N_);
  h = Q_ * phi.tail(N_);
  bool overlap = K_I_open < -tol_K_;
  for (Eigen::Index k = 0; k < N_; ++k)
    if (g(k) < -tol_) state[k] = closing(h(k)), overlap = true;
  if (K_I_open < -tol_K_) state[0] = closing(h(0));
  K_I = K_I_open;
  return overlap;
}

bool FaceContact::settle(int max_passes) {
  std::vector<Pass> tried;  // every set tried: a set met again closes a cycle
  for (int it = 1; it <= max_passes; ++it) {
    ++passes;
    solve_on_set();
    std::vector<int> next = state;
    const auto violated = violations(next);
    if (violated.empty()) return true;
    const auto worst = std::max_element(violated.begin(), violated.end());
    tried.push_back({state, phi, worst->first});
    least_violation = std::min(least_violation, worst->first);
    // The first passes change every violating point, later ones only the worst, which breaks the cycles a stick–slip
    // or open–closed boundary falling between two collocation points can cause.
    if (it <= kAllAtOnce) {
      state = next;
    } else {
      state[worst->second] = next[worst->second];
    }
    const auto seen = std::find_if(tried.begin(), tried.end(), [&](const Pass& q) { return q.state == state; });
    if (seen != tried.end()) {
      const auto best =
          std::min_element(seen, tried.end(), [](const Pass& u, const Pass& v) { return u.worst < v.worst; });
      if (!cycle_best_ || best->worst < cycle_best_->worst) cycle_best_ = *best;
      cycled = true;
      return false;
    }
  }
  return false;
}

bool FaceContact::complementary_set() {
  const Eigen::MatrixXd Minv = M_.partialPivLu().inverse();
  // With the faces' pressure p and shear T at the collocation points as loads, φ = M⁻¹([−p; T] − σ), so that
  // g = g₀ + G_p p + G_t T and h = h₀ + H_p p + H_t T.
  const Eigen::VectorXd phi0 = -(Minv * sigma_);
  const Eigen::VectorXd g0 = Q_ * phi0.head(N_), h0 = Q_ * phi0.tail(N_);
  const Eigen::MatrixXd Gp = -(Q_ * Minv.topLeftCorner(N_, N_)), Gt = Q_ * Minv.topRightCorner(N_, N_);
  const Eigen::MatrixXd Hp = -(Q_ * Minv.bottomLeftCorner(N_, N_)), Ht = Q_ * Minv.bottomRightCorner(N_, N_);
  // The problem is posed on the points whose own compliance G_p,kk is positive: an inclined crack's last two or three
  // points at the mouth, a corner the polynomial density does not resolve (header), close further under their own
  // pressure, where no pivoting method can be relied on; the passes that follow settle them, or hold them.
  std::vector<Eigen::Index> J;
  for (Eigen::Index k = 0; k < N_; ++k)
    (Gp(k, k) > 0.0 ? J : mouth_).push_back(k);
  const Eigen::Index m = Eigen::Index(J.size());
  Eigen::VectorXd p = Eigen::VectorXd::Zero(N_), T = Eigen::VectorXd::Zero(N_), slip = Eigen::VectorXd::Zero(N_);
  std::optional<LcpSolution> s;
  if (f_ == 0.0) {
    s = solve_lcp(Gp(J, J), g0(J), kMaxPivots * int(m));
    if (s) p(J) = s->z;
  } else {
    // With T = b⁻ − b⁺, the unknowns (p, b⁺, b⁻, s) are complementary to (g, s + h, s − h, f p − b⁺ − b⁻): where
    // the faces slip, s = |h| and T = f p sign(h); where they stick, h = 0 and |T| ≤ f p; where they are open, p = 0
    // and T = 0 (Stewart and Trinkle 1996, in two dimensions).
    const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(m, m), Z = Eigen::MatrixXd::Zero(m, m);
    const Eigen::MatrixXd gp = Gp(J, J), gt = Gt(J, J), hp = Hp(J, J), ht = Ht(J, J);
    Eigen::MatrixXd A(4 * m, 4 * m);
    A << gp, -gt, gt, Z,  //
        hp, -ht, ht, I,   //
        -hp, ht, -ht, I,  //
        f_ * I, -I, -I, Z;
    Eigen::VectorXd q(4 * m);
    q << g0(J), h0(J), -h0(J), Eigen::VectorXd::Zero(m);
    s = solve_lcp(A, q, kMaxPivots * int(4 * m));
    if (s) p(J) = s->z.head(m), T(J) = s->z.segment(2 * m, m) - s->z.segment(m, m), slip(J) = s->z.tail(m);
  }
  // Friction makes the problem's matrix lose the properties that guarantee Lemke's path (it may end on a ray); the
  // frictionless problem's contact set is then the start, its points closing the way the faces slide.
  bool frictionless = f_ == 0.0;
  if (!s && f_ > 0.0) {
    s = solve_lcp(Gp(J, J), g0(J), kMaxPivots * int(m));
    if (s) p(J) = s->z, frictionless = true;
  }
  complementarity = s ? 1 : -1;
  if (!s) return false;
  // The set: without friction, a closed point first as slipping one way (its shear is zero either way), and in
  // signed_state_ the way the faces slide there, as closing() takes it.
  const Eigen::VectorXd gap = g0 + Gp * p + Gt * T, h_all = h0 + Hp * p + Ht * T;
  signed_state_ = state;
  for (Eigen::Index k = 0; k < N_; ++k) {
    if (p(k) > tol_) {
      state[k] = f_ == 0.0 ? 2 : frictionless ? closing(h_all(k)) : slip(k) > tol_ ? (T(k) > 0.0 ? 2 : -2) : 1;
      signed_state_[k] = frictionless ? closing(h_all(k)) : state[k];
    } else {
      state[k] = signed_state_[k] = gap(k) < -tol_ ? closing(h_all(k)) : 0;
    }
  }
  complementary_state_ = state;
  return true;
}

bool FaceContact::settle_again(int max_passes) {
  if (complementarity <= 0) return false;
  if (signed_state_ != complementary_state_) {
    state = signed_state_;
    if (settle(max_passes)) return true;
  }
  if (mouth_.empty()) return false;
  state = signed_state_;
  mouth_held_ = true;
  return settle(max_passes);
}

bool FaceContact::keep_cycle_best(double load) {
  if (!cycle_best_ || cycle_best_->worst > kCycleTolerance * load) return false;
  state = cycle_best_->state;
  take(cycle_best_->phi);
  return true;
}

void FaceContact::solve_on_set() {
  Eigen::MatrixXd A = M_;
  Eigen::VectorXd b = -sigma_;
  for (Eigen::Index k = 0; k < N_; ++k) {
    if (state[k] == 0) continue;
    A.row(k).setZero();  // g(t_k) = 0
    A.row(k).head(N_) = Q_.row(k);
    b(k) = 0.0;
    if (state[k] == 1) {  // h(t_k) = 0
      A.row(N_ + k).setZero();
      A.row(N_ + k).tail(N_) = Q_.row(k);
      b(N_ + k) = 0.0;
    } else {  // T = f p sign(h) = −f sign(h) σ_n,total
      const double fs = f_ * (state[k] > 0 ? 1.0 : -1.0);
      A.row(N_ + k) = M_.row(N_ + k) + fs * M_.row(k);
      b(N_ + k) = -(sigma_(N_ + k) + fs * sigma_(k));
    }
  }
  take(A.partialPivLu().solve(b));
}

void FaceContact::take(const Eigen::VectorXd& density) {
  phi = density;
  const Eigen::VectorXd total = sigma_ + M_ * phi;
  Tn = total.head(N_);
  Tt = total.tail(N_);
  g = Q_ * phi.head(N_);
  h = Q_ * phi.tail(N_);
  K_I = scale_ * L_.dot(phi.head(N_));
}

// Closing where g < 0 or where K_I < 0 at an open tip; opening where p < 0; slipping where |T| > f p; sticking where
// the slip reverses.
std::vector<std::pair<double, Eigen::Index>> FaceContact::violations(std::vector<int>& next) const {
  std::vector<std::pair<double, Eigen::Index>> violated;
  for (Eigen::Index k = 0; k < N_; ++k) {
    if (mouth_held_ && std::find(mouth_.begin(), mouth_.end(), k) != mouth_.end()) continue;
    const double p = -Tn(k);
    double by = 0.0;
    if (state[k] == 0) {
      if (g(k) < -tol_) next[k] = closing(h(k)), by = -g(k);
    } else if (p < -tol_) {
      next[k] = 0, by = -p;
    } else if (state[k] == 1) {
      if (std::abs(Tt(k)) > f_ * p + tol_) next[k] = Tt(k) > 0.0 ? 2 : -2, by = std::abs(Tt(k)) - f_ * p;
    } else if (const double hs = state[k] > 0 ? h(k) : -h(k); hs < -tol_) {
      next[k] = 1, by = -hs;
    }
    if (next[k] != state[k]) violated.emplace_back(by, k);
  }
  if (state[0] == 0 && K_I < -tol_K_ && next[0] == 0) next[0] = closing(h(0)), violated.emplace_back(-K_I / scale_, 0);
  return violated;
}

}  // namespace

CrackFaces CrackSolver::from_loads(double l, std::span<const double> normal, std::span<const double> shear,
                                   bool detail) const {
  const Eigen::Index N = Eigen::Index(s_.size());
  Eigen::VectorXd sigma(2 * N);
  for (Eigen::Index k = 0; k < N; ++k) sigma(k) = normal[k], sigma(N + k) = shear[k];
  const Eigen::Map<const Eigen::VectorXd> L(L1_.data(), N);
  const double scale = std::sqrt(2.0 * kPi * l);  // K = √(2πl) φ(1)
  // Tolerances of the inequalities, relative to the load: the opening integral and φ are in Pa, like σ.
  const double load = std::max(sigma.cwiseAbs().maxCoeff(), 1e-300);
  const double tol = 1e-10 * load, tol_K = 1e-10 * load * scale;

  // The open crack; where its faces would overlap they touch, and the active set settles their contact.
  FaceContact c(M_, Q_, L, sigma, crack_.face_friction, scale, tol, tol_K);
  c.phi = open_density(-sigma);
  CrackSif r;
  r.l = l;
  r.K_I_open = scale * L.dot(c.phi.head(N));
  r.K_II_open = scale * L.dot(c.phi.tail(N));
  if (c.close_overlaps(r.K_I_open)) {
    // The passes from the overlaps' set settle most contacts; where they cycle or run out, they start again from the
    // set of the complementarity problem (exact where the problem has a solution on these points); then a cycle's
    // nearly satisfied set is kept, and only where there is none do the passes start from the complementarity set
    // again (settle_again).
    bool settled = c.settle(options_.max_contact_iterations);
    // Where the passes cycle, their least violating set is kept aside: the solution they came near, which a settled
    // restart is compared with (CrackSif::K_II_nearly).
    const Eigen::VectorXd nearly = c.cycle_best_slide();
    const bool restarted = !settled && crack_.face_friction > 0.0 && nearly.size() == N;
    if (!settled && c.complementary_set())
      settled = c.settle(std::max(1, options_.max_contact_iterations - c.passes));
    if (!settled) settled = c.keep_cycle_best(load);
    if (!settled) settled = c.settle_again(std::max(1, options_.max_contact_iterations - c.passes));
    r.contact_iterations = c.passes;
    if (settled && restarted) r.K_II_nearly = scale * L.dot(nearly);
    if (!settled)
      throw ConvergenceError(fmt::format(
          "crack face contact: the open/stick/slip set {}{}, its least violation {:.3g} Pa, {:.2g} of the largest "
          "load on the faces (accepted up to {:.2g} at a cycle), at l = {} m, angle {}°, face friction {}, {} "
          "points: a boundary between open, sticking and slipping points that falls between two of them; change "
          "effects.crack.quadrature",
          c.cycled ? fmt::format("cycles after {} passes", c.passes)
                   : fmt::format("did not settle in {} passes", c.passes),
          c.complementarity < 0   ? ", and Lemke's pivoting found no solution of its complementarity problem"
          : c.complementarity > 0 ? ", also when started from its complementarity problem's solution"
                                  : "",
          c.least_violation, c.least_violation / load, kCycleTolerance, l, crack_.angle_deg, crack_.face_friction,
          s_.size()));
  }
  r.closed = c.state[0] != 0;
  r.K_I = r.closed ? 0.0 : std::max(c.K_I, 0.0);
  r.K_II = scale * L.dot(c.phi.tail(N));
  r.closed_fraction = double(std::count_if(c.state.begin(), c.state.end(), [](int s) { return s != 0; })) / double(N);

  CrackFaces out;
  out.sif = r;
  if (detail) {
    const Eigen::VectorXd h = Q_ * c.phi.tail(N);
    for (Eigen::Index k = 0; k < N; ++k) {
      out.eta.push_back(0.5 * l * (1.0 + t_[k]));
      out.opening.push_back(0.5 * l * c.g(k));
      out.slip.push_back(0.5 * l * h(k));
      out.pressure.push_back(c.state[k] == 0 ? 0.0 : -c.Tn(k));
      out.shear.push_back(c.state[k] == 0 ? 0.0 : c.Tt(k));
      out.state.push_back(c.state[k] == 0   ? CrackFaces::State::open
                          : c.state[k] == 1 ? CrackFaces::State::stick
                                            : CrackFaces::State::slip);
    }
  }
  return out;
}

CrackFaces CrackSolver::faces(double l, const Load& normal, const Load& shear) const {
  if (!(l > 0.0)) throw InputError(fmt::format("crack length {} m: must be > 0", l));
  std::vector<double> n(t_.size()), s(t_.size());
  for (std::size_t k = 0; k < t_.size(); ++k) {
    const double eta = 0.5 * l * (1.0 + t_[k]);
    n[k] = normal ? normal(eta) : 0.0;
    s[k] = shear ? shear(eta) : 0.0;
  }
  return from_loads(l, n, s, true);
}

CrackSif CrackSolver::sif(double l, const Load& normal, const Load& shear) const {
  return faces(l, normal, shear).sif;
}

std::vector<double> CrackSolver::density(double l, const Load& load) const {
  const Eigen::Index N = Eigen::Index(t_.size());
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * N);
  for (Eigen::Index k = 0; k < N; ++k) rhs(k) = -load(0.5 * l * (1.0 + t_[k]));
  const Eigen::VectorXd phi = open_density(rhs);
  return {phi.data(), phi.data() + N};
}

CrackResult CrackSolver::solve(const SurfaceTractions& t, double x_c, std::span<const double> lengths) const {
  const auto start = std::chrono::steady_clock::now();
  CrackResult result;
  result.x_c = x_c;
  if (lengths.empty()) return result;
  for (double l : lengths)
    if (!(l > 0.0)) throw InputError(fmt::format("crack length {} m: must be > 0", l));
  // The stress at every length's own collocation points, evaluated there (no table between): a length's SIFs are
  // the same whatever other lengths are listed with it.
  const std::size_t N = t_.size();
  std::vector<double> r;
  r.reserve(lengths.size() * N);
  for (double l : lengths)
    for (std::size_t k = 0; k < N; ++k) r.push_back(0.5 * l * (1.0 + t_[k]));
  const std::vector<Stress> sigma = stress_along_line(t, x_c, crack_.angle_deg, r);
  const auto [c, sn] = direction(crack_.angle_deg);
  std::vector<double> n(N), s(N);
  result.sifs.reserve(lengths.size());
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    for (std::size_t k = 0; k < N; ++k) std::tie(n[k], s[k]) = resolve(sigma[i * N + k], c, sn);
    result.sifs.push_back(from_loads(lengths[i], n, s, false).sif);
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace fretwear
