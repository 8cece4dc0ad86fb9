// Two elastic half-planes in contact: the compliance that couples pressure to surface displacement, and Dundurs'
// mismatch parameters.
//
//   A = 2/E* = Σ_i (κ_i + 1) / (4 μ_i)        (= 2 Σ (1 − ν_i²)/E_i in plane strain, 2 Σ 1/E_i in plane stress)
//   κ = 3 − 4ν (plane strain), (3 − ν)/(1 + ν) (plane stress);   μ = E / (2(1 + ν))
//   Γ = μ2/μ1,  α = [Γ(κ1 + 1) − (κ2 + 1)] / [Γ(κ1 + 1) + (κ2 + 1)],  β = [Γ(κ1 − 1) − (κ2 − 1)] / [Γ(κ1 + 1) + (κ2 + 1)]
//
// Body 1 is the pad, body 2 the specimen (Dundurs 1969). β = 0 for
// similar bodies: then the normal and tangential problems are uncoupled.
#pragma once

#include <string>
#include <string_view>

namespace fretwear {

struct Material {
  double E = 0.0;   // Young's modulus (Pa), > 0
  double nu = 0.0;  // Poisson's ratio, in (−1, 0.5)
};

enum class PlaneState { strain, stress };

std::string to_string(PlaneState s);
// Throws InputError naming the accepted words.
PlaneState plane_state_from_string(std::string_view word);

class ElasticPair {
 public:
  ElasticPair(Material pad, Material specimen, PlaneState plane);

  double A() const { return A_; }            // composite compliance 2/E* (1/Pa)
  double E_star() const { return 2.0 / A_; } // composite modulus (Pa)
  double alpha() const { return alpha_; }    // Dundurs α
  double beta() const { return beta_; }      // Dundurs β: couples normal and tangential problems
  double kappa_pad() const { return kappa1_; }
  double kappa_specimen() const { return kappa2_; }
  double mu_pad() const { return mu1_; }      // shear modulus of the pad (Pa)
  double mu_specimen() const { return mu2_; } // shear modulus of the specimen (Pa)
  // The surface strain ε_xx of the specimen under a bulk stress σ (Pa) along its surface: σ (κ₂ + 1) / (8 μ₂), in
  // plane strain σ (1 − ν²)/E (PHYSICS.md, "Partial slip": the bulk stress enters as this strain).
  double bulk_strain(double sigma) const { return sigma * (kappa2_ + 1.0) / (8.0 * mu2_); }
  const Material& pad() const { return pad_; }
  const Material& specimen() const { return specimen_; }
  PlaneState plane() const { return plane_; }
  bool similar() const { return pad_.E == specimen_.E && pad_.nu == specimen_.nu; }

 private:
  Material pad_, specimen_;
  PlaneState plane_;
  double kappa1_, kappa2_, mu1_, mu2_, A_, alpha_, beta_;
};

}  // namespace fretwear
