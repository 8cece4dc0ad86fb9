// Where gross slip takes a worn contact. In gross slip every contact cell slides the stroke each cycle, the worn area
// grows by c ∫ p s dx a cycle, and the contact wears flat without limit, widening as the profile flattens. The worn
// profile is about the original gap g0 cut flat at the depth d that holds the worn area,
//     W(d) = ∫ max(0, d − g0(x)) dx,
// whose ends are where g0 = d: on examples/gross_slip_displacement_wear.json the flat after 18 000 cycles ends at
// ±0.244 mm where the run's contact ends at ±0.246 mm, and with 2e6 cycles the run reached the window's end (±0.6 mm)
// at cycle 260 747 where this puts it at 2.67e5. The estimate is optimistic on both counts (the elastic contact
// reaches a little past the flat, and the slip per cycle grows as the contact flattens), so its users take the worn
// area kFlatMargin larger where they must hold the run (engine/preflight.cpp, engine/setup.cpp).
#pragma once

#include <utility>

#include "contact/profile.hpp"

namespace fretwear {

inline constexpr double kFlatMargin = 0.1;

// W(d) (m²) and where g0 = d, left and right of the profile's lowest point (m), for the gap d (m) the profile is cut
// flat at: the worn gap is max(g0, d).
struct Flat {
  double area = 0.0, left = 0.0, right = 0.0, depth = 0.0;
};

// The flat at depth d (m), integrated outward from the lowest point in steps of h/4 (trapezoids).
Flat flat_at(const Profile& profile, double d, double h);

// The flat that holds `area` (m²): the depth found by TOMS 748 on W(d) − area, bracketed by doubling. A profile that
// holds less than `area` down to a depth of 1 m gives that flat.
Flat flat_holding(const Profile& profile, double area, double h);

// The window that holds a contact whose unworn ends are [left, right] (m) when it has worn `area` (m²) flat: that
// flat or the unworn contact, whichever reaches further, and U (m) beyond it each side (the specimen's scar with each
// body in its own frame), centred on the lowest point with 20 % to spare.
std::pair<double, double> window_holding(const Profile& profile, double area, double h, double U, double left,
                                         double right);

}  // namespace fretwear
