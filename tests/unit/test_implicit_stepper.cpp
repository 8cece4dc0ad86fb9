// The contact-implicit wear stepper (wear/implicit_stepper.hpp) when a contact-implicit solve does not converge: the
// step is rejected and retried with a quarter of the jump; below one cycle the stepper gives up with
// ImplicitSolveFailure, which the engine reports as a ConvergenceError with the solve's residual.
#include <algorithm>
#include <vector>

#include <doctest/doctest.h>

#include "common/error.hpp"
#include "engine/simulation.hpp"
#include "engine/wear_contacts.hpp"
#include "engine/wear_stage.hpp"
#include "scenes.hpp"
#include "wear/implicit_stepper.hpp"

using namespace fretwear;

namespace {

// The real contact, whose contact-implicit solves "fail" while the largest shift d exceeds a threshold, as the
// constrained CG can stall for very large jumps near the asymptote (4096 cells, hertz_wear).
class FailingAboveShift : public wear::ContactResponse {
 public:
  FailingAboveShift(AnalogyContactResponse& real, double d_limit) : real_(real), d_limit_(d_limit) {}
  int cells() const override { return real_.cells(); }
  double cell_width() const override { return real_.cell_width(); }
  void respond(std::span<const double> w, wear::CycleResponse& out) override { real_.respond(w, out); }
  bool implicit_pressure(std::span<const double> w, std::span<const double> d, std::vector<double>& p) override {
    if (*std::max_element(d.begin(), d.end()) > d_limit_) {
      ++refused;
      std::fill(p.begin(), p.end(), -1.0);  // what a stalled solve leaves is not to be used
      return false;
    }
    return real_.implicit_pressure(w, d, p);
  }
  int refused = 0;

 private:
  AnalogyContactResponse& real_;
  double d_limit_;
};

}  // namespace

TEST_CASE("an implicit step whose solve does not converge is retried with a quarter of the jump") {
  const Scene s = test::hertz_wear(1e5, 0.5, 1e4, 256);
  const Model m = make_model(s);
  AnalogyContactResponse real(s, m, cyclic_load(s, m.pair));
  wear::CycleResponse r;
  real.respond(std::vector<double>(m.grid.n, 0.0), r);
  // The slip the step lags (on touching: beyond the contact too), whose largest shift the failing contact watches.
  const std::vector<double>& lagged = r.slip_if_touching();
  const double s_max = *std::max_element(lagged.begin(), lagged.end());
  const double c = 1e-12;
  // Solves fail for jumps above 100 cycles: a first try of 1000 is cut to 250, then to 62.5, which succeeds.
  FailingAboveShift contact(real, 100.0 * c * s_max);
  wear::ImplicitWearStepper stepper(c, 0.1);  // a loose tolerance: the third try passes on its error
  std::vector<double> w(m.grid.n, 0.0);
  double N = 0.0, dN = 1000.0;
  using boost::numeric::odeint::controlled_step_result;
  CHECK(stepper.try_step(wear::ResponseRef{&contact}, w, N, dN) == controlled_step_result::fail);
  CHECK(dN == 250.0);
  CHECK(N == 0.0);
  CHECK(*std::max_element(w.begin(), w.end()) == 0.0);  // a failed step leaves the state alone
  CHECK(stepper.try_step(wear::ResponseRef{&contact}, w, N, dN) == controlled_step_result::fail);
  CHECK(dN == 62.5);
  CHECK(stepper.try_step(wear::ResponseRef{&contact}, w, N, dN) == controlled_step_result::success);
  CHECK(N == 62.5);
  CHECK(stepper.stats().unconverged == 2);
  CHECK(stepper.stats().rejected == 2);
  CHECK(stepper.stats().accepted == 1);
  const double w_max = *std::max_element(w.begin(), w.end());
  CHECK(w_max > 0.0);
  CHECK(*std::min_element(w.begin(), w.end()) >= 0.0);  // no trace of the failed iterates' −1 pressures

  // The same step taken by a stepper whose solves never fail gives the same wear.
  AnalogyContactResponse fresh(s, m, cyclic_load(s, m.pair));
  wear::ImplicitWearStepper reference(c, 0.1);
  std::vector<double> w_ref(m.grid.n, 0.0);
  double N_ref = 0.0, dN_ref = 62.5;
  REQUIRE(reference.try_step(wear::ResponseRef{&fresh}, w_ref, N_ref, dN_ref) == controlled_step_result::success);
  for (int i = 0; i < m.grid.n; ++i) CHECK(std::abs(w[i] - w_ref[i]) <= 1e-6 * w_max);
}

TEST_CASE("below one cycle the implicit stepper gives up, the engine names the solve and its residual") {
  const Scene s = test::hertz_wear(1e5, 0.5, 1e4, 256);
  const Model m = make_model(s);
  AnalogyContactResponse real(s, m, cyclic_load(s, m.pair));
  FailingAboveShift contact(real, 0.0);  // every solve fails
  wear::ImplicitWearStepper stepper(1e-12, 1e-3);
  std::vector<double> w(m.grid.n, 0.0);
  double N = 0.0, dN = 16.0;
  using boost::numeric::odeint::controlled_step_result;
  for (int k = 0; k < 2; ++k)  // 16 → 4 → 1
    CHECK(stepper.try_step(wear::ResponseRef{&contact}, w, N, dN) == controlled_step_result::fail);
  CHECK(dN == 1.0);
  CHECK_THROWS_AS(stepper.try_step(wear::ResponseRef{&contact}, w, N, dN), wear::ImplicitSolveFailure);
}

namespace {

// The real contact with a slip that jumps threefold as soon as anything has worn: the one step (slip lagged at
// w = 0) and the two half steps (the second at the threefold slip) then differ by a fixed fraction of the wear
// at any jump, as a response that is not smooth in w makes them.
class RoughResponse : public wear::ContactResponse {
 public:
  explicit RoughResponse(AnalogyContactResponse& real) : real_(real) {}
  int cells() const override { return real_.cells(); }
  double cell_width() const override { return real_.cell_width(); }
  void respond(std::span<const double> w, wear::CycleResponse& out) override {
    real_.respond(w, out);
    const double factor = *std::max_element(w.begin(), w.end()) > 0.0 ? 3.0 : 1.0;
    for (double& s : out.s) s *= factor;
    for (double& s : out.s_touching) s *= factor;
  }
  bool implicit_pressure(std::span<const double> w, std::span<const double> d, std::vector<double>& p) override {
    return real_.implicit_pressure(w, d, p);
  }

 private:
  AnalogyContactResponse& real_;
};

}  // namespace

TEST_CASE("an error estimate that does not fall with the jump stops the stepper with a ConvergenceError") {
  const Scene s = test::hertz_wear(1e5, 0.5, 1e4, 256);
  const Model m = make_model(s);
  AnalogyContactResponse real(s, m, cyclic_load(s, m.pair));
  RoughResponse contact(real);
  wear::ImplicitWearStepper stepper(1e-12, 1e-3);
  std::vector<double> w(m.grid.n, 0.0);
  double N = 0.0, dN = 10.0;
  int tries = 0;
  using boost::numeric::odeint::controlled_step_result;
  auto step_until_stopped = [&] {
    while (tries < 10000) {
      ++tries;
      stepper.try_step(wear::ResponseRef{&contact}, w, N, dN);
    }
  };
  CHECK_THROWS_AS(step_until_stopped(), ConvergenceError);
  CHECK(dN < wear::kMinJump);
  CHECK(tries < 100);  // each rejection cuts the jump by at least 0.9: from 10 to 1e-6 in at most 153 ...
  CHECK(N == 0.0);     // ... and by 0.2 at an error this large: in a dozen
}
