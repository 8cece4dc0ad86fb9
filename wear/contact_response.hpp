// What wear needs from the contact, and all it knows of it: the steady cycle on a worn profile, and the pressure of
// the contact-implicit step. The engine implements it on top of contact/; wear/ never includes contact/.
#pragma once

#include <span>
#include <utility>
#include <vector>

namespace fretwear::wear {

// The contact in one wear state w (the wear depth per cell, both bodies together, m).
struct CycleResponse {
  std::vector<double> p;  // pressure per cell under P (Pa)
  std::vector<double> s;  // slip travelled per cycle per cell (m); 0 in the stick zone and off the contact
  // The slip a cell would travel per cycle were it touching (m), where the contact knows it: equal to s on the
  // contact and, off it, the relative slip of the surfaces there (the analogy route, outside the stick zone) or, in
  // gross slip, s continued over the cells out of contact (the bodies slide past every x alike). The rate c p s is
  // the same with either (p = 0 off the contact); the contact-implicit step's operator is not
  // (wear/implicit_stepper.hpp). Empty: s itself (a cell out of contact or in the stick zone taken not to slip).
  std::vector<double> s_touching;
  const std::vector<double>& slip_if_touching() const { return s_touching.empty() ? s : s_touching; }
  double stick_left = 0.0, stick_right = 0.0;  // the stick zone (m); equal when there is none
  bool has_stick = false;
  // Every stick zone, left to right (m), when the contact has several: [stick_left, stick_right] is their hull.
  // Empty means the one zone [stick_left, stick_right] (or none).
  std::vector<std::pair<double, double>> stick_zones;
};

class ContactResponse {
 public:
  virtual ~ContactResponse() = default;
  virtual int cells() const = 0;
  virtual double cell_width() const = 0;  // m
  // The steady cycle on the profile worn by w. out.p, when it holds one value per cell, is the normal solve's warm
  // start (the stepper knows a pressure close to w's: the contact-implicit solution that produced w).
  virtual void respond(std::span<const double> w, CycleResponse& out) = 0;
  // The pressure p that satisfies the contact conditions with gap g0 + w + d p − δ (operator K + diag(d)), i.e. the
  // end-of-step pressure of a contact-implicit step with d = ΔN c s. p holds a warm start on entry. Returns false
  // when the solve did not reach its tolerance (p is then unusable): the stepper retries with a smaller ΔN, whose
  // smaller d is better conditioned.
  virtual bool implicit_pressure(std::span<const double> w, std::span<const double> d, std::vector<double>& p) = 0;
};

}  // namespace fretwear::wear
