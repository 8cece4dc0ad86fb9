#include "contact/elastic_pair.hpp"

#include <cassert>

#include "common/error.hpp"

namespace fretwear {

std::string to_string(PlaneState s) { return s == PlaneState::strain ? "strain" : "stress"; }

PlaneState plane_state_from_string(std::string_view word) {
  if (word == "strain") return PlaneState::strain;
  if (word == "stress") return PlaneState::stress;
  throw InputError("plane: '" + std::string(word) + "' is not a plane state; use \"strain\" or \"stress\"");
}

namespace {
double kolosov(double nu, PlaneState plane) {
  return plane == PlaneState::strain ? 3.0 - 4.0 * nu : (3.0 - nu) / (1.0 + nu);
}
}  // namespace

ElasticPair::ElasticPair(Material pad, Material specimen, PlaneState plane)
    : pad_(pad), specimen_(specimen), plane_(plane) {
  assert(pad.E > 0 && specimen.E > 0);
  kappa1_ = kolosov(pad.nu, plane);
  kappa2_ = kolosov(specimen.nu, plane);
  mu1_ = pad.E / (2.0 * (1.0 + pad.nu));
  mu2_ = specimen.E / (2.0 * (1.0 + specimen.nu));
  A_ = (kappa1_ + 1.0) / (4.0 * mu1_) + (kappa2_ + 1.0) / (4.0 * mu2_);
  const double gamma = mu2_ / mu1_;
  const double den = gamma * (kappa1_ + 1.0) + (kappa2_ + 1.0);
  alpha_ = (gamma * (kappa1_ + 1.0) - (kappa2_ + 1.0)) / den;
  beta_ = (gamma * (kappa1_ - 1.0) - (kappa2_ - 1.0)) / den;
}

}  // namespace fretwear
