#include "wear/implicit_stepper.hpp"

#include <fmt/format.h>

namespace fretwear::wear {

using boost::numeric::odeint::controlled_step_result;

bool ImplicitWearStepper::euler(ContactResponse& contact, const state_type& w, const std::vector<double>& s,
                                double dN, std::vector<double>& p, state_type& out) {
  const std::size_t n = w.size();
  d_.resize(n);
  for (std::size_t i = 0; i < n; ++i) d_[i] = dN * c_ * s[i];
  ++stats_.implicit_solves;
  if (!contact.implicit_pressure(w, d_, p)) return false;
  out.resize(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = w[i] + d_[i] * p[i];
  return true;
}

controlled_step_result ImplicitWearStepper::try_step_impl(ContactResponse& contact, state_type& w, time_type& N,
                                                          time_type& dN) {
  if (!response_valid_ || state_at_ != w) {
    // The last step's end-of-step pressure is the contact pressure of a profile within one extrapolation of w: the
    // normal solve's warm start.
    response_.p = p_full_;
    contact.respond(w, response_);
    ++stats_.responses;
    state_at_ = w;
    response_valid_ = true;
  }
  if (p_full_.size() != w.size()) p_full_ = response_.p;
  if (p_half_.size() != w.size()) p_half_ = response_.p;

  std::vector<double> p_two;
  const bool solved = euler(contact, w, response_.slip_if_touching(), dN, p_full_, w_full_) &&
                      euler(contact, w, response_.slip_if_touching(), 0.5 * dN, p_half_, w_half_) &&
                      (half_.p = p_half_, contact.respond(w_half_, half_), ++stats_.responses, p_two = p_half_,
                       euler(contact, w_half_, half_.slip_if_touching(), 0.5 * dN, p_two, w_two_));
  if (!solved) {
    ++stats_.rejected;
    ++stats_.unconverged;
    if (dN <= 1.0)
      throw ImplicitSolveFailure(fmt::format("wear: the contact-implicit solve did not converge at cycle {:.0f} even "
                                             "for a jump of {:.3g} cycles",
                                             N, dN));
    p_full_ = p_half_ = response_.p;  // the failed solves' iterates are no warm start
    dN *= 0.25;
    return controlled_step_result::fail;
  }

  // A cell that starts to wear within the step (it enters the contact or the slip zone in the first half: no slip at
  // w_n, so the one step of ΔN does not wear it, the second half step does) has worn between one and two times the
  // half steps' increment (it entered between N and N + ΔN/2). Extrapolating would take the upper end; the midpoint
  // is kept, and the half-width of that range is its error. Elsewhere the Richardson difference is the error.
  // (No slip at w_n, so the one step did not wear the cell; the two half steps did.)
  const std::vector<double>& s_lagged = response_.slip_if_touching();
  auto starts_wearing = [&s_lagged](std::size_t i, double two) { return s_lagged[i] == 0.0 && two > 0.0; };
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) scale = std::max(scale, std::abs(w_two_[i]));
  for (std::size_t i = 0; i < w.size(); ++i) {
    const double full = w_full_[i] - w[i], two = w_two_[i] - w[i];
    diff = std::max(diff, starts_wearing(i, two) ? 0.5 * two : std::abs(two - full));
  }
  const double err = scale > 0.0 ? diff / (tolerance_ * scale) : 0.0;
  stats_.last_error = err;
  if (!(err <= 1.0)) {
    ++stats_.rejected;
    if (dN < kMinJump)
      throw ConvergenceError(fmt::format(
          "wear: the implicit stepper's error estimate does not fall with its jump (error {:.3g} times the tolerance "
          "{:.3g} at a jump of {:.3g} cycles, at cycle {:.6g}): the contact's response is not smooth enough in the "
          "worn profile here; use effects.wear.stepper \"cycle_by_cycle\", or a looser tolerance",
          err, tolerance_, dN, N));
    dN *= std::clamp(0.9 / std::sqrt(err), 0.2, 0.9);
    return controlled_step_result::fail;
  }
  for (std::size_t i = 0; i < w.size(); ++i) {
    const double two = w_two_[i] - w[i];
    w[i] = starts_wearing(i, two) ? w[i] + 1.5 * two : std::max(w[i], 2.0 * w_two_[i] - w_full_[i]);
  }
  N += dN;
  dN *= err > 0.0 ? std::clamp(0.9 / std::sqrt(err), 1.0, 4.0) : 4.0;
  ++stats_.accepted;
  p_full_ = p_two;
  p_half_ = p_two;
  response_valid_ = false;
  return controlled_step_result::success;
}

}  // namespace fretwear::wear
