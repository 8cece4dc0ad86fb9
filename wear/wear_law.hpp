// Wear laws (paper 002, §3; PHYSICS.md, "Wear"): the wear depth per cycle, both bodies together,
//     archard:  dw/dN = k p s          (k in 1/Pa)
//     energy:   dw/dN = α |q| s        (α in 1/Pa)
// with s the slip travelled in the cycle. Wear happens only where a point slips, and there |q| = f p, so both laws
// are dw/dN = c p s with c = k (Archard) or c = α f (energy): one rate coefficient serves both, and the
// contact-implicit step treats both alike.
#pragma once

#include <string>
#include <string_view>

namespace fretwear::wear {

enum class Law { archard, energy };
std::string to_string(Law law);
// Throws InputError listing the accepted words.
Law law_from_string(std::string_view word);

struct WearLaw {
  Law law = Law::archard;
  double coefficient = 0.0;   // k (Archard) or α (energy), 1/Pa, > 0
  double friction = 0.0;      // f: the energy law wears by |q| = f p in the slip zones
  double pad_fraction = 0.5;  // share of the wear on the pad, in [0, 1]

  // c in dw/dN = c p s (1/Pa).
  double rate_coefficient() const { return law == Law::archard ? coefficient : coefficient * friction; }
};

}  // namespace fretwear::wear
