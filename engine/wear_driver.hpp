// Driving a wear stepper through the record times so that a run can stop at any step boundary and be continued
// later, exactly: odeint's integrate_times with its loop state held by the caller (DriveState), which a checkpoint
// saves (engine/checkpoint.hpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

#include <boost/numeric/odeint/integrate/max_step_checker.hpp>
#include <boost/numeric/odeint/stepper/controlled_step_result.hpp>

namespace fretwear {

// Where the driver stands between two steps: all a resumed run needs besides the state w and the steppers' own.
struct DriveState {
  double N = 0.0;        // cycles done
  double dt = 0.0;       // the step size to try next (cycles)
  std::size_t next = 0;  // index of the next record time to observe
  long steps = 0;        // accepted steps
};

// odeint's integrate_times for a controlled stepper (boost/numeric/odeint/integrate/detail/integrate_times.hpp),
// step for step, with its loop state held in `s` instead of locals, so that it can stop at any step boundary and be
// continued later from a saved `s`: observe(w, t) at each record time, then boundary(s, true); boundary(s, false)
// after each accepted step. A false from boundary stops the run (false is returned) unless all is recorded.
template <class Stepper, class System, class Observe, class Boundary>
bool drive_times(Stepper& stepper, System system, std::vector<double>& w, const std::vector<double>& times,
                 DriveState& s, Observe observe, Boundary boundary) {
  namespace odeint = boost::numeric::odeint;
  odeint::failed_step_checker checker;
  auto before = [](double t1, double t2) { return t2 - t1 > std::numeric_limits<double>::epsilon(); };
  while (s.next < times.size()) {
    while (before(s.N, times[s.next])) {
      double current = std::min(s.dt, times[s.next] - s.N);  // end exactly on the record time
      if (stepper.try_step(system, w, s.N, current) == odeint::controlled_step_result::success) {
        ++s.steps;
        checker.reset();
        s.dt = std::max(s.dt, current);  // continue with the step size the record time had cut
        if (!boundary(s, false)) return false;
      } else {
        checker();
        s.dt = current;
      }
    }
    observe(w, times[s.next]);
    ++s.next;
    if (!boundary(s, true) && s.next < times.size()) return false;
  }
  return true;
}

// A stepper without error control (odeint's euler) in the controlled interface: every step succeeds at the size asked.
template <class Stepper>
struct AlwaysAccepted {
  Stepper stepper;
  template <class System>
  boost::numeric::odeint::controlled_step_result try_step(System system, std::vector<double>& w, double& N,
                                                          double& dN) {
    stepper.do_step(system, w, N, dN);
    N += dN;
    return boost::numeric::odeint::controlled_step_result::success;
  }
};

}  // namespace fretwear
