#include "contact/profile.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

// Boost 1.74's pchip.hpp and makima.hpp call isnan unqualified in a template; the declaration they need must be
// visible where they are included.
using std::isnan;
#include <boost/math/interpolators/cardinal_cubic_b_spline.hpp>
#include <boost/math/interpolators/makima.hpp>
#include <boost/math/interpolators/pchip.hpp>
#include <boost/math/tools/minima.hpp>

#include <fmt/format.h>

#include "common/error.hpp"

namespace fretwear {

// A table's curve between its points (pchip, makima, cubic), in the table's own x; linear tables have none.
struct TableInterpolant {
  std::function<double(double)> value, slope;
};

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kDeg = std::numbers::pi / 180.0;

struct TypeName {
  ProfileType type;
  const char* word;
};
constexpr TypeName kTypeNames[] = {
    {ProfileType::cylinder, "cylinder"},   {ProfileType::flat_rounded, "flat_rounded"},
    {ProfileType::flat, "flat"},           {ProfileType::wedge, "wedge"},
    {ProfileType::rounded_wedge, "rounded_wedge"}, {ProfileType::wavy, "wavy"},
    {ProfileType::table, "table"},         {ProfileType::sum, "sum"},
    {ProfileType::envelope, "envelope"},
};

// Gap of one node before normalisation, in global x.
double raw_gap(const ProfileSpec& s, double x) {
  const double t = x - s.offset_x;
  double g = 0.0;
  switch (s.type) {
    case ProfileType::cylinder:
      g = t * t / (2.0 * s.R);
      break;
    case ProfileType::flat_rounded: {
      const double e = std::max(std::abs(t) - s.a, 0.0);
      g = e * e / (2.0 * s.R);
      break;
    }
    case ProfileType::flat:
      g = std::abs(t) <= s.b ? 0.0 : kInf;
      break;
    case ProfileType::wedge:
      g = std::abs(t) * std::tan(s.angle_deg * kDeg);
      break;
    case ProfileType::rounded_wedge: {
      const double m = std::tan(s.angle_deg * kDeg), xt = s.R * m, at = std::abs(t);
      g = at <= xt ? t * t / (2.0 * s.R) : at * m - 0.5 * s.R * m * m;
      break;
    }
    case ProfileType::wavy:
      g = s.amplitude * (1.0 - std::cos(2.0 * std::numbers::pi * t / s.wavelength));
      break;
    case ProfileType::table: {
      if (t < s.x.front() || t > s.x.back()) return kInf;
      if (s.curve) {
        g = s.curve->value(t);
        break;
      }
      auto it = std::upper_bound(s.x.begin(), s.x.end(), t);
      std::size_t i = std::min<std::size_t>(std::max<std::ptrdiff_t>(it - s.x.begin(), 1), s.x.size() - 1);
      const double w = (t - s.x[i - 1]) / (s.x[i] - s.x[i - 1]);
      g = (1.0 - w) * s.h[i - 1] + w * s.h[i];
      break;
    }
    case ProfileType::sum:
      for (const auto& term : s.terms) g += raw_gap(term, t);
      break;
    case ProfileType::envelope:
      g = kInf;
      for (const auto& term : s.terms) g = std::min(g, raw_gap(term, t));
      break;
  }
  return g + s.tilt_rad * x;
}

double raw_slope(const ProfileSpec& s, double x) {
  const double t = x - s.offset_x;
  double d = 0.0;
  switch (s.type) {
    case ProfileType::cylinder:
      d = t / s.R;
      break;
    case ProfileType::flat_rounded: {
      const double e = std::max(std::abs(t) - s.a, 0.0);
      d = std::copysign(e / s.R, t);
      break;
    }
    case ProfileType::flat:
      d = 0.0;
      break;
    case ProfileType::wedge:
      d = t == 0.0 ? 0.0 : std::copysign(std::tan(s.angle_deg * kDeg), t);
      break;
    case ProfileType::rounded_wedge: {
      const double m = std::tan(s.angle_deg * kDeg), xt = s.R * m;
      d = std::abs(t) <= xt ? t / s.R : std::copysign(m, t);
      break;
    }
    case ProfileType::wavy:
      d = s.amplitude * 2.0 * std::numbers::pi / s.wavelength *
          std::sin(2.0 * std::numbers::pi * t / s.wavelength);
      break;
    case ProfileType::table: {
      if (t < s.x.front() || t > s.x.back()) return 0.0;
      if (s.curve) {
        d = s.curve->slope(t);
        break;
      }
      auto it = std::upper_bound(s.x.begin(), s.x.end(), t);
      std::size_t i = std::min<std::size_t>(std::max<std::ptrdiff_t>(it - s.x.begin(), 1), s.x.size() - 1);
      d = (s.h[i] - s.h[i - 1]) / (s.x[i] - s.x[i - 1]);
      break;
    }
    case ProfileType::sum:
      for (const auto& term : s.terms) d += raw_slope(term, t);
      break;
    case ProfileType::envelope: {
      double g = kInf;
      for (const auto& term : s.terms) {
        const double gt = raw_gap(term, t);
        if (gt < g) g = gt, d = raw_slope(term, t);
      }
      break;
    }
  }
  return d + s.tilt_rad;
}

void collect_kinks(const ProfileSpec& s, double shift, std::vector<double>& out) {
  const double o = shift + s.offset_x;
  switch (s.type) {
    case ProfileType::flat_rounded:
      out.insert(out.end(), {o - s.a, o + s.a});
      break;
    case ProfileType::flat:
      out.insert(out.end(), {o - s.b, o + s.b});
      break;
    case ProfileType::wedge:
      out.push_back(o);
      break;
    case ProfileType::rounded_wedge: {
      const double xt = s.R * std::tan(s.angle_deg * kDeg);
      out.insert(out.end(), {o - xt, o + xt});
      break;
    }
    case ProfileType::table:
      if (s.interpolation == Interpolation::linear)
        for (double xi : s.x) out.push_back(o + xi);
      else  // C¹ between the ends
        out.insert(out.end(), {o + s.x.front(), o + s.x.back()});
      break;
    case ProfileType::sum:
    case ProfileType::envelope:
      for (const auto& term : s.terms) collect_kinks(term, o, out);
      break;
    default:
      break;
  }
}

std::pair<double, double> raw_support(const ProfileSpec& s) {
  switch (s.type) {
    case ProfileType::flat:
      return {s.offset_x - s.b, s.offset_x + s.b};
    case ProfileType::table:
      return {s.offset_x + s.x.front(), s.offset_x + s.x.back()};
    case ProfileType::sum: {
      std::pair<double, double> r{-kInf, kInf};
      for (const auto& term : s.terms) {
        auto [lo, hi] = raw_support(term);
        r = {std::max(r.first, lo + s.offset_x), std::min(r.second, hi + s.offset_x)};
      }
      return r;
    }
    case ProfileType::envelope: {
      std::pair<double, double> r{kInf, -kInf};
      for (const auto& term : s.terms) {
        auto [lo, hi] = raw_support(term);
        r = {std::min(r.first, lo + s.offset_x), std::max(r.second, hi + s.offset_x)};
      }
      return r;
    }
    default:
      return {-kInf, kInf};
  }
}

// The centre (in the frame of s's parent) about which s is even and convex, if it is: untilted cylinders, rounded
// punches, wedges and rounded wedges, and sums of them sharing one centre (nested offsets included).
std::optional<double> symmetry_centre(const ProfileSpec& s) {
  if (s.tilt_rad != 0.0) return std::nullopt;
  switch (s.type) {
    case ProfileType::cylinder:
    case ProfileType::flat_rounded:
    case ProfileType::wedge:
    case ProfileType::rounded_wedge:
      return s.offset_x;
    case ProfileType::sum: {
      if (s.terms.empty()) return std::nullopt;
      const auto first = symmetry_centre(s.terms.front());
      if (!first) return std::nullopt;
      for (const auto& t : s.terms)
        if (symmetry_centre(t) != first) return std::nullopt;
      return s.offset_x + *first;
    }
    default:
      return std::nullopt;
  }
}

bool is_periodic(const ProfileSpec& s) {
  if (s.type == ProfileType::wavy) return true;
  if (s.type == ProfileType::sum)
    return std::all_of(s.terms.begin(), s.terms.end(), [](const ProfileSpec& t) { return is_periodic(t); });
  return false;
}

double mean_offset(const ProfileSpec& s) {
  if ((s.type == ProfileType::sum || s.type == ProfileType::envelope) && !s.terms.empty()) {
    double m = 0.0;
    for (const auto& t : s.terms) m += mean_offset(t);
    return s.offset_x + m / double(s.terms.size());
  }
  return s.offset_x;
}

}  // namespace

std::string to_string(ProfileType t) {
  for (const auto& n : kTypeNames)
    if (n.type == t) return n.word;
  return "?";
}

std::string profile_type_words() {
  std::string s;
  for (const auto& n : kTypeNames) s += (s.empty() ? "" : ", ") + std::string(n.word);
  return s;
}

ProfileType profile_type_from_string(std::string_view word) {
  for (const auto& n : kTypeNames)
    if (word == n.word) return n.type;
  throw InputError("profile type '" + std::string(word) + "' is unknown; use one of " + profile_type_words());
}

namespace {

constexpr std::pair<Interpolation, const char*> kInterpolationWords[] = {{Interpolation::linear, "linear"},
                                                                         {Interpolation::pchip, "pchip"},
                                                                         {Interpolation::makima, "makima"},
                                                                         {Interpolation::cubic, "cubic"}};

// A Boost.Math interpolant of the table's points (pchip, makima: both take x and h and give value and prime),
// held by the curve's value and slope.
template <class Interpolant>
void hold(TableInterpolant& curve, const ProfileSpec& s) {
  auto f = std::make_shared<const Interpolant>(std::vector<double>(s.x), std::vector<double>(s.h));
  curve.value = [f](double t) { return (*f)(t); };
  curve.slope = [f](double t) { return f->prime(t); };
}

// The curve of a table read with a cubic interpolant; throws InputError when the table does not suit it.
std::shared_ptr<const TableInterpolant> make_curve(const ProfileSpec& s) {
  const std::size_t n = s.x.size();
  if (s.interpolation == Interpolation::linear && n >= 2 && n == s.h.size()) return nullptr;
  if (n != s.h.size() || n < min_table_points(s.interpolation))
    throw InputError(fmt::format("profile: a table read with {} interpolation needs at least {} points with one h "
                                 "per x; it has {} x and {} h",
                                 to_string(s.interpolation), min_table_points(s.interpolation), n, s.h.size()));
  auto curve = std::make_shared<TableInterpolant>();
  switch (s.interpolation) {
    case Interpolation::linear:
      break;
    case Interpolation::pchip:
      hold<boost::math::interpolators::pchip<std::vector<double>>>(*curve, s);
      break;
    case Interpolation::makima:
      hold<boost::math::interpolators::makima<std::vector<double>>>(*curve, s);
      break;
    case Interpolation::cubic: {
      if (!uniformly_spaced(s.x))
        throw InputError("profile: cubic interpolation needs uniformly spaced x (a cardinal B-spline); use \"makima\" "
                         "or \"pchip\" for a table on non-uniform x");
      const double x0 = s.x.front(), step = (s.x.back() - x0) / double(n - 1), x1 = x0 + step * double(n - 1);
      auto f = std::make_shared<const boost::math::interpolators::cardinal_cubic_b_spline<double>>(
          s.h.data(), n, x0, step);
      // Nodes within kUniformTolerance of a spacing: the spline's ends may differ from x's by round-off.
      curve->value = [f, x0, x1](double t) { return (*f)(std::clamp(t, x0, x1)); };
      curve->slope = [f, x0, x1](double t) { return f->prime(std::clamp(t, x0, x1)); };
      break;
    }
  }
  return curve;
}

void build_curves(ProfileSpec& s) {
  if (s.type == ProfileType::table) s.curve = make_curve(s);
  for (auto& term : s.terms) build_curves(term);
}

}  // namespace

std::string to_string(Interpolation i) {
  for (const auto& [value, word] : kInterpolationWords)
    if (value == i) return word;
  return "?";
}

std::string interpolation_words() {
  std::string s;
  const std::size_t n = std::size(kInterpolationWords);
  for (std::size_t k = 0; k < n; ++k)
    s += (k == 0 ? "" : k + 1 == n ? " or " : ", ") + fmt::format("\"{}\"", kInterpolationWords[k].second);
  return s;
}

Interpolation interpolation_from_string(std::string_view word) {
  for (const auto& [value, w] : kInterpolationWords)
    if (word == w) return value;
  throw InputError(fmt::format("\"{}\" is not an interpolation; use {}", word, interpolation_words()));
}

std::size_t min_table_points(Interpolation i) {
  switch (i) {
    case Interpolation::pchip:
    case Interpolation::makima:
      return 4;  // Boost.Math's pchip and makima
    case Interpolation::cubic:
      return 5;  // the cardinal B-spline with its end slopes estimated from the data
    default:
      return 2;
  }
}

bool uniformly_spaced(const std::vector<double>& x) {
  if (x.size() < 2) return false;
  const double step = (x.back() - x.front()) / double(x.size() - 1);
  for (std::size_t i = 0; i < x.size(); ++i)
    if (std::abs(x[i] - (x.front() + double(i) * step)) > kUniformTolerance * step) return false;
  return true;
}

namespace {
[[noreturn]] void throw_unbounded() {
  throw InputError("profile: the gap has no lowest point within 1 km of the profile's centre: a tilt_rad steeper "
                   "than the profile's flanks makes the bodies interpenetrate without bound");
}
}  // namespace

Profile::Profile(ProfileSpec spec) : spec_(std::move(spec)) {
  build_curves(spec_);
  support_ = raw_support(spec_);
  symmetric_ = symmetry_centre(spec_).has_value();
  periodic_ = is_periodic(spec_) && spec_.tilt_rad == 0.0;
  if (support_.first >= support_.second)
    throw InputError("profile: the terms of the sum have no common support (their tables or flats do not overlap)");

  // The lowest point: sample ever wider windows about the terms' centre until the minimum is interior, then refine.
  const double centre = std::isfinite(support_.first) && std::isfinite(support_.second)
                            ? 0.5 * (support_.first + support_.second)
                            : mean_offset(spec_);
  constexpr int kSamples = 4001;
  for (double L = 1e-7; L <= 1e3; L *= 4.0) {
    const double lo = std::max(centre - L, support_.first), hi = std::min(centre + L, support_.second);
    const double dx = (hi - lo) / (kSamples - 1);
    int i_min = 0;
    double g_min = kInf;
    for (int i = 0; i < kSamples; ++i) {
      const double g = raw_gap(spec_, lo + i * dx);
      if (g < g_min) g_min = g, i_min = i;
    }
    const bool at_lo = i_min == 0 && lo > support_.first;
    const bool at_hi = i_min == kSamples - 1 && hi < support_.second;
    if (!std::isfinite(g_min) || at_lo || at_hi) continue;
    // A run of equal minima (a flat) has its midpoint as the lowest point; an isolated minimum is refined.
    const double scale = std::max(std::abs(g_min), 1e-300);
    auto flat_at = [&](int i) { return std::abs(raw_gap(spec_, lo + i * dx) - g_min) <= 1e-14 * scale; };
    int i_lo = i_min, i_hi = i_min;
    while (i_lo > 0 && flat_at(i_lo - 1)) --i_lo;
    while (i_hi < kSamples - 1 && flat_at(i_hi + 1)) ++i_hi;
    if (i_hi > i_lo) {
      x_low_ = lo + 0.5 * (i_lo + i_hi) * dx;
    } else {
      // Brent in the bracket's own unit: its absolute tolerance (a quarter of √ε) would otherwise be in metres, far
      // coarser than a micrometre-sized contact.
      const double a = lo + std::max(i_min - 1, 0) * dx, b = lo + std::min(i_min + 1, kSamples - 1) * dx;
      const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
      auto r = boost::math::tools::brent_find_minima([&](double u) { return raw_gap(spec_, mid + u * half); }, -1.0,
                                                     1.0, std::numeric_limits<double>::digits);
      x_low_ = lo + i_min * dx;
      double g_best = g_min;
      if (r.second < g_best) x_low_ = mid + r.first * half, g_best = r.second;
      // A minimum at a kink (a wedge's apex, a table's node) is exact there, which Brent only approaches.
      for (double k : kinks()) {
        if (k < a || k > b) continue;
        const double gk = raw_gap(spec_, k);
        if (gk <= g_best) x_low_ = k, g_best = gk;
      }
    }
    g_low_ = std::min(g_min, raw_gap(spec_, x_low_));
    // An interior minimum is not a lowest point when the gap falls below it far away (a tilted waviness).
    for (double far : {x_low_ - 1e3, x_low_ + 1e3}) {
      if (far < support_.first || far > support_.second) continue;
      if (raw_gap(spec_, far) < g_low_) throw_unbounded();
    }
    return;
  }
  throw_unbounded();
}

double Profile::gap(double x) const {
  const double g = raw_gap(spec_, x);
  return std::isfinite(g) ? std::max(g - g_low_, 0.0) : kInf;
}

double Profile::slope(double x) const { return raw_slope(spec_, x); }

std::vector<double> Profile::kinks() const {
  std::vector<double> k;
  collect_kinks(spec_, 0.0, k);
  std::sort(k.begin(), k.end());
  k.erase(std::unique(k.begin(), k.end()), k.end());
  return k;
}

}  // namespace fretwear
