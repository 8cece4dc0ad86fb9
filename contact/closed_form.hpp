// Closed-form normal contacts (PHYSICS.md, "Normal contact"), used to verify the solver and to report errors.
#pragma once

namespace fretwear::closed_form {

// Hertz cylinder of radius R (m) under load P (N/m), composite compliance A (1/Pa).
struct Hertz {
  double a;   // half-width (m): √(2 P A R / π) = √(4 P R / (π E*))
  double p0;  // peak pressure (Pa): 2P/(πa)
  double pressure(double x) const;               // p0 √(1 − x²/a²), 0 outside
  double cell_average(double x0, double x1) const;  // (1/(x1 − x0)) ∫ p dx
};
Hertz hertz(double P, double A, double R);

// Flat punch of flat half-length a with parabolic corners of radius R (paper 000, eqs 3–4, corrected in PHYSICS.md).
struct RoundedPunch {
  double a, R, P;
  double b;     // contact half-width (m)
  double phi0;  // asin(a/b)
  double pressure(double x) const;     // b p / P = (2/π) B(φ; φ0) / D(φ0), x = b sin φ
  double peak() const;                 // max p (Pa)
  double peak_x() const;               // where (m, ≥ 0)
};
// Throws InputError if the load cannot be carried (never: every P > 0 has a solution).
RoundedPunch rounded_punch(double P, double A, double a, double R);
// D(θ) = π − 2θ − sin 2θ and B(φ; φ0) of PHYSICS.md.
double D(double theta);
double B(double phi, double phi0);

// Sharp flat punch of half-width b: p = P / (π √(b² − x²)), complete contact.
struct FlatPunch {
  double b, P;
  double pressure(double x) const;
  double cell_average(double x0, double x1) const;
};
FlatPunch flat_punch(double P, double b);

}  // namespace fretwear::closed_form
