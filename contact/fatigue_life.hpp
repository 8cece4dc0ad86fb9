// Fretting-fatigue life (PHYSICS.md, "Fretting-fatigue life"): the cycles to start a crack from the Smith–Watson–Topper
// parameter of contact/fatigue_measures.hpp, damage summed over changing states by Miner's rule, and the cycles to
// grow the crack by Paris' law from tables of its stress intensity factors against its length.
//
// Initiation. Basquin–Coffin–Manson in the SWT form (Smith, Watson and Topper 1970; the strain–life curve of Basquin
// 1910, Coffin 1954 and Manson 1954):
//     SWT(N) = (σf′)²/E (2N)^{2b} + σf′ εf′ (2N)^{b+c},     b < 0, c < 0,
// decreasing in N, so N_i(SWT) is the one root of SWT(N) = SWT on ln N, found by TOMS 748 (Boost.Math) to a relative
// 1e-12 in N. Below SWT(kMaxLife) the point never initiates (N_i = +∞); above SWT(kMinLife), N_i = kMinLife. Critical
// distance by Taylor's line method (Taylor 2007): the stresses averaged over depth y ∈ [0, ℓ] below a surface point
// (line_average, trapezoids, linear between the samples), then SWT on the critical plane of the mean history
// (engine/life_stage.hpp); ℓ = 0 is the surface value (the point method).
// Miner's rule over states k held for ΔN_k cycles: D = Σ ΔN_k / N_i(SWT_k); initiation where D first reaches 1.
//
// Propagation. Paris and Erdogan (1963): da/dN = C ΔK^m where ΔK exceeds the threshold, 0 below it; ΔK = K_max − K_min
// from the closed-crack SIFs at the top and the bottom of the cycle (mode I), or √(ΔK_I² + ΔK_II²) (equivalent).
// Threshold ΔK_th, or with El Haddad, Topper and Smith's (1979) short-crack correction ΔK_th √(a/(a + a₀)),
// a₀ = (1/π)(ΔK_th/(1.12 Δσ_e))². The SIFs of one contact state are a table against crack length (a few dozen lengths
// from the crack solver), interpolated by PCHIP (Fritsch and Carlson 1980; Boost.Math) in K/√a against ln a, which
// is constant for a crack in uniform tension (K = 1.1215 σ √(πa)) and smooth where the contact's field decays.
// The states change with the cycle count (wear records: the state k holds from N_k until N_{k+1}, the last for ever);
// a(N) is integrated across them by Boost.Odeint's Dormand–Prince with dense output (relative tolerance kGrowthTolerance),
// each state from its start to the next, and the end — a reaching a_final, or K_max reaching K_c — located within the
// step on the dense output by TOMS 748. A crack whose ΔK is at or below the threshold in the last state, at a length
// it has reached, arrests there: its propagation life is infinite. Past cycles_max the run stops as a runout.
//
// Check (PHYSICS.md): an edge crack in remote tension 0 → σ, ΔK = 1.1215 σ √(πa), m ≠ 2:
//     N = [a₀^{1−m/2} − a_f^{1−m/2}] / [C (1.1215 σ √π)^m (m/2 − 1)].
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace fretwear {

// The strain–life constants of the specimen's material.
struct InitiationConstants {
  double sigma_f = 0.0;  // fatigue strength coefficient σf′ (Pa), > 0
  double b = 0.0;        // fatigue strength exponent, < 0
  double eps_f = 0.0;    // fatigue ductility coefficient εf′, > 0
  double c = 0.0;        // fatigue ductility exponent, < 0
  double E = 0.0;        // Young's modulus (Pa), > 0
};

constexpr double kMinLife = 0.5;   // cycles: a reversal
constexpr double kMaxLife = 1e30;  // cycles: "never" for any engineering purpose

// SWT(N) of the Basquin–Coffin–Manson curve (Pa).
double swt_of_life(const InitiationConstants& k, double N);

// N_i with SWT(N_i) = swt: +∞ at or below SWT(kMaxLife) (swt ≤ 0 included), kMinLife at or above SWT(kMinLife).
double initiation_life(const InitiationConstants& k, double swt);

// The mean of v over y ∈ [0, ell], v sampled at increasing depths y with y[0] = 0 (linear between samples); ell = 0
// gives v[0], and ell past the last sample is held to it (the caller warns). y and v of one size ≥ 1.
double line_average(std::span<const double> y, std::span<const double> v, double ell);

// Paris' law with its threshold.
struct GrowthConstants {
  double C = 0.0;           // m per cycle per (Pa·m^0.5)^m, > 0
  double m = 0.0;           // > 0
  double dK_th = 0.0;       // long-crack threshold (Pa·m^0.5), ≥ 0
  double a0 = 0.0;          // El Haddad's length (m); 0 without the short-crack correction
  double K_c = 0.0;         // fracture toughness (Pa·m^0.5); 0: not checked
  bool equivalent = false;  // ΔK = √(ΔK_I² + ΔK_II²) rather than ΔK_I
};

// El Haddad's a₀ = (1/π)(ΔK_th/(1.12 Δσ_e))² (m), Δσ_e the fatigue limit as a stress range (Pa).
double el_haddad_length(double dK_th, double delta_sigma_e);

// The threshold at length a: ΔK_th √(a/(a + a₀)) (ΔK_th when a₀ = 0).
double growth_threshold(const GrowthConstants& g, double a);

// The SIFs of one contact state against crack length (closed-crack values, Pa·m^0.5), interpolated (header).
class SifTable {
 public:
  // a: increasing lengths (m), at least two; each K list of the same size.
  SifTable(std::vector<double> a, std::vector<double> KI_top, std::vector<double> KI_bottom,
           std::vector<double> KII_top, std::vector<double> KII_bottom);
  SifTable(SifTable&&) noexcept;
  SifTable& operator=(SifTable&&) noexcept;
  ~SifTable();

  double a_min() const { return a_.front(); }
  double a_max() const { return a_.back(); }
  // ΔK_I, ΔK_II and max(K_I) at a in [a_min, a_max] (clamped outside).
  double dK_I(double a) const;
  double dK_II(double a) const;
  double K_max(double a) const;
  // ΔK of the mode the constants ask for.
  double dK(double a, const GrowthConstants& g) const;

  struct Curve;  // one interpolated SIF (the source defines it)

 private:
  double at(const Curve& curve, double a) const;
  std::vector<double> a_;
  std::unique_ptr<Curve> KI_top_, KI_bottom_, KII_top_, KII_bottom_;
};

// A contact state for the growth: its SIF table, from cycle N_from on.
struct GrowthState {
  double N_from = 0.0;
  const SifTable* table = nullptr;
};

enum class GrowthFate { failure, arrest, runout };
std::string to_string(GrowthFate fate);  // "failure", "arrest", "runout"

struct GrowthPoint {
  double N = 0.0, a = 0.0;         // cycles (counted from the start of growth's states), m
  double dK_I = 0.0, dK_II = 0.0;  // Pa·m^0.5
  double da_dN = 0.0;              // m per cycle
};

struct GrowthResult {
  double cycles = std::numeric_limits<double>::infinity();  // to failure from N_start; +∞ on arrest
  double final_length = 0.0;  // m: where it failed, arrested, or stood at cycles_max
  GrowthFate fate = GrowthFate::runout;
  std::vector<GrowthPoint> path;  // the accepted steps, from a_initial
};

constexpr double kGrowthTolerance = 1e-8;  // Dormand–Prince's relative (and absolute, times a_initial) tolerance

// Grows a crack from a_initial at cycle N_start to a_final (or K_max = K_c) through the states (sorted by N_from; the
// first must start at or before N_start), stopping at N_start + cycles_max. Lengths outside a state's table are
// clamped to it: give tables that span [a_initial, a_final].
GrowthResult grow_crack(const GrowthConstants& g, double a_initial, double a_final, double N_start,
                        std::span<const GrowthState> states, double cycles_max);

}  // namespace fretwear
