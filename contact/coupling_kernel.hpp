// The Dundurs-β coupling between the normal and the tangential problems of two dissimilar elastic half-planes.
//
// Derivation in fretwear's conventions (PHYSICS.md: x along the surface, y into the specimen, body 1 the pad above,
// body 2 the specimen below, p > 0 compression, q the traction the pad exerts on the specimen in +x). A half-plane
// loaded on its surface by a pressure p and a shear q (in +x on it) has, with a_i = (κ_i + 1)/(4μ_i),
// b_i = (κ_i − 1)/(4μ_i) and H[t](x) = (1/π) PV∫ t(ξ)/(x − ξ) dξ (Johnson 1985, eqs 2.25a,b, z into the body),
//     ∂u_x/∂x = −b p − a H[q],      ∂u_z/∂x = −a H[p] + b q.
// The specimen is such a body with z = y; the pad is one with z = −y that carries −q. So the gap
// g = g0 + u_y(specimen) − u_y(pad) − δ and the relative tangential displacement s = u_x(specimen) − u_x(pad) obey
//     ∂g/∂x = g0′ − A H[p] − A β q,         ∂s/∂x = −A H[q] + A β p,
// since a_1 + a_2 = A and b_1 − b_2 = A β for Dundurs' β = [Γ(κ1 − 1) − (κ2 − 1)]/[Γ(κ1 + 1) + (κ2 + 1)], Γ = μ2/μ1
// (elastic_pair.hpp). In contact (g′ = 0): (1/π) PV∫ p/(x − ξ) dξ + β q = g0′/A — Hills, Nowell and Sackfield
// (1993, "Mechanics of Elastic Contacts", §2.5) and Barber (2018, "Contact Mechanics", §3.7) write the same pair of
// equations with the signs of their own axes and body order; the signs above are checked, term by term, by
// tests/unit/test_coupling_kernel.cpp against ElasticPair and by β → −β under the exchange of the bodies.
//
// The β terms are local in the derivative, so in the displacement they are a step kernel: a uniform traction t on
// the cell [ξ_j − h/2, ξ_j + h/2] adds to a displacement at x the amount (1/2) ∫_cell sgn(x − ξ) dξ (the constant
// half of the step is a rigid displacement, taken up by δ or by the rigid shift λ). At the cell centres this is
// exactly
//     S_ij = (h/2) sgn(i − j),       S_ii = 0,
// an antisymmetric Toeplitz matrix. On the grid, with K the HalfPlaneKernel:
//     gap:  g = g0 + K p − A β S q − δ,        tangential:  s = K q + A β S p + ε x − λ.
// S t is two running sums, O(n) and exact (cheaper than the FFT product K uses, and with no round-off growth
// beyond the sums').
#pragma once

#include <span>

#include "contact/grid.hpp"

namespace fretwear {

class CouplingKernel {
 public:
  explicit CouplingKernel(const Grid& grid) : grid_(grid) {}

  // The displacement at x (m) per unit traction on cell j (m/Pa): (1/2) ∫_cell sgn(x − ξ) dξ.
  double coefficient(double x, int j) const;
  // S_ij = coefficient(x_i, j): (h/2) sgn(i − j).
  double matrix(int i, int j) const { return i == j ? 0.0 : (i > j ? 0.5 : -0.5) * grid_.h(); }
  // u = scale · S t (t and u have grid.n entries and may not alias).
  void apply(std::span<const double> t, std::span<double> u, double scale = 1.0) const;
  const Grid& grid() const { return grid_; }

 private:
  Grid grid_;
};

}  // namespace fretwear
