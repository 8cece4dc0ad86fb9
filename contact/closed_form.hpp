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

// The stick zone [centre − c, centre + c] of the Hertz contact at the top of a cycle to Q/fP = q_ratio with a bulk
// tension sigma (Pa) in phase (PHYSICS.md, "Partial slip"): c/a = √(1 − Q/fP) (Cattaneo 1938, Mindlin 1949), shifted
// toward the leading edge by e/a = σ/(4 f p0) (Nowell and Hills 1987). Valid short of reverse slip, e + c ≤ a.
struct StickZone {
  double centre, c;  // m
};
StickZone hertz_stick(const Hertz& h, double q_ratio, double f, double sigma);

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
// Stick half-width c (m) of the rounded punch at Q/fP = q_ratio ∈ [0, 1], no bulk stress (paper 000 eq 9 as
// corrected in PHYSICS.md): Q/fP = 1 − (c/b)² D(ψ0)/D(φ0), sin ψ0 = a/c, a ≤ c ≤ b.
double rounded_punch_stick(const RoundedPunch& r, double q_ratio);
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
