// The load–size relation of a symmetric single-zone incomplete contact (PHYSICS.md; paper 002, eq 14):
//     P(b) = (1/A) ∫_{−b}^{b} g0′(t) t / √(b² − t²) dt
// about the profile's lowest point. With t = b sin θ the integrand is bounded, and the quadrature is split at the
// profile's kinks, so Gauss–Kronrod gives P(b) to round-off; a bracketing root find gives b.
#pragma once

#include "contact/profile.hpp"

namespace fretwear {

// P(b) for half-width b (m); A is the composite compliance (1/Pa). Returns N/m.
double load_for_half_width(const Profile& profile, double A, double b);

// The half-width b (m) that carries load P (N/m), to a relative tolerance of about 1e-13.
// Requires profile.symmetric_single_zone(); throws InputError otherwise.
double half_width_for_load(const Profile& profile, double A, double P);

}  // namespace fretwear
