// The initial gap g0(x) ≥ 0 between the undeformed bodies (PHYSICS.md, "Conventions"): 0 where they first touch,
// +∞ where the pad has no material (beyond a sharp flat punch's corners, outside a measured table).
//
// A profile is a tree of plain data (ProfileSpec) read from the scene; Profile evaluates it. Every node may carry
// offset_x (shifts it along +x) and tilt_rad (adds tilt_rad·x: the +x side lifts). The top-level gap is shifted so
// that its minimum is 0.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace fretwear {

enum class ProfileType { cylinder, flat_rounded, flat, wedge, rounded_wedge, wavy, table, sum, envelope };

std::string to_string(ProfileType t);
// Throws InputError listing the accepted words.
ProfileType profile_type_from_string(std::string_view word);
// The accepted words, comma separated (for messages and docs).
std::string profile_type_words();

// How a table is read between its points (SCENES.md, "Measured profiles"). linear: straight segments, a kink at every
// point. pchip: Fritsch & Carlson's (1980) monotone piecewise cubic Hermite interpolant; makima: Akima's (1970)
// piecewise cubic Hermite with the modified weights that keep flat runs flat; both C¹, on any increasing x, from 4
// points. cubic: the C² cubic B-spline interpolant on uniformly spaced x (Boost.Math's cardinal_cubic_b_spline, its
// end slopes estimated from the data), from 5 points; Boost 1.74 has no C² cubic spline for non-uniform x.
enum class Interpolation { linear, pchip, makima, cubic };
std::string to_string(Interpolation i);
// Throws InputError listing the accepted words.
Interpolation interpolation_from_string(std::string_view word);
std::string interpolation_words();  // "linear", "pchip", "makima" or "cubic"
// The fewest table points each interpolation takes.
std::size_t min_table_points(Interpolation i);
// True when the x are uniformly spaced, as cubic needs: every x_i within kUniformTolerance of a spacing of
// x0 + i (x_n − x0)/n.
constexpr double kUniformTolerance = 1e-6;
bool uniformly_spaced(const std::vector<double>& x);

// Where a table was read from, for the resolved scene; empty file for a table given inline.
struct TableSource {
  std::string file;      // the path as resolved against the scene's folder
  std::string x_unit = "m", h_unit = "m";
  std::string checksum;  // "fnv1a64:" and the file's FNV-1a 64-bit hash in 16 hex digits
};

struct TableInterpolant;  // the table's curve, built by Profile

struct ProfileSpec {
  ProfileType type = ProfileType::cylinder;
  double R = 0.0;           // cylinder, flat_rounded, rounded_wedge: radius (m)
  double a = 0.0;           // flat_rounded: flat half-length (m)
  double b = 0.0;           // flat: half-width (m)
  double angle_deg = 0.0;   // wedge, rounded_wedge: flank angle to the surface (degrees, 0 < angle < 90)
  double amplitude = 0.0;   // wavy: g0 = amplitude (1 − cos(2πx/wavelength)) (m)
  double wavelength = 0.0;  // wavy (m)
  std::vector<double> x, h; // table: g0 = h at increasing x (m), interpolated between, +∞ outside [x.front(), x.back()]
  Interpolation interpolation = Interpolation::linear;  // table
  TableSource source;       // table: where x and h came from
  std::shared_ptr<const TableInterpolant> curve;  // table: set by Profile (immutable, shared by copies)
  std::vector<ProfileSpec> terms;  // sum, envelope
  double offset_x = 0.0;    // m
  double tilt_rad = 0.0;    // rad
};

class Profile {
 public:
  // Throws InputError if a table has fewer points than its interpolation takes (or cubic non-uniform x), or if the
  // profile has no lowest point (a tilt steeper than the flanks, a tilted waviness). A
  // lone waviness has one but repeats it: periodic() is then true and the scene must give the window.
  explicit Profile(ProfileSpec spec);

  double gap(double x) const;    // g0(x) ≥ 0 (m); +∞ where the pad has no material
  double slope(double x) const;  // g0′(x); one-sided at kinks
  // The midpoint of the set where g0 = 0 (m).
  double lowest_point() const { return x_low_; }
  // Finite where the pad ends (a flat punch's corners, a table's ends); ±∞ otherwise.
  std::pair<double, double> support() const { return support_; }
  // x where g0′ jumps (kinks) or the pad ends, sorted; quadratures split there.
  std::vector<double> kinks() const;
  // True when g0 is even about lowest_point(), convex and finite: then the contact is a single incomplete zone and
  // the load–size integral of PHYSICS.md applies.
  bool symmetric_single_zone() const { return symmetric_; }
  // True for a lone waviness (or any profile whose lowest point repeats): the window must be given.
  bool periodic() const { return periodic_; }
  const ProfileSpec& spec() const { return spec_; }

 private:
  ProfileSpec spec_;
  double g_low_ = 0.0;  // raw gap at the lowest point
  double x_low_ = 0.0;
  std::pair<double, double> support_;
  bool symmetric_ = false;
  bool periodic_ = false;
};

}  // namespace fretwear
