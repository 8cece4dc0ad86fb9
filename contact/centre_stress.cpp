#include "contact/centre_stress.hpp"

#include <cassert>
#include <cmath>
#include <memory>
#include <numbers>

#include <fftw3.h>

#include "contact/toeplitz_fft.hpp"

namespace fretwear {
namespace {

// The smallest 2^a 3^b 5^c ≥ m: sizes FFTW transforms with its fastest codelets (2n + 2 itself often has a large
// prime factor, 2050 = 2 · 5² · 41).
int smooth_size(int m) {
  for (int L = m;; ++L) {
    int r = L;
    for (int f : {2, 3, 5})
      while (r % f == 0) r /= f;
    if (r == 1) return L;
  }
}

// Aligned FFTW buffers: L reals and L/2 + 1 complex values.
struct Buffers {
  double* real;
  fftw_complex* spec;
  explicit Buffers(int L) : real(fftw_alloc_real(std::size_t(L))), spec(fftw_alloc_complex(std::size_t(L / 2 + 1))) {}
  ~Buffers() {
    fftw_free(real);
    fftw_free(spec);
  }
  Buffers(const Buffers&) = delete;
  Buffers& operator=(const Buffers&) = delete;
};

std::complex<double>* as_complex(fftw_complex* c) { return reinterpret_cast<std::complex<double>*>(c); }

}  // namespace

// Out-of-place r2c and c2r plans of size L, made under the planner's lock; executed with fftw_execute_dft_* on other
// aligned buffers of the same size, which FFTW allows from any thread.
struct CentreStresses::Plans {
  fftw_plan forward = nullptr, inverse = nullptr;
  explicit Plans(int L) {
    std::lock_guard lock(fftw_planner_mutex());
    Buffers b(L);
    forward = fftw_plan_dft_r2c_1d(L, b.real, b.spec, FFTW_ESTIMATE);
    inverse = fftw_plan_dft_c2r_1d(L, b.spec, b.real, FFTW_ESTIMATE | FFTW_DESTROY_INPUT);
  }
  ~Plans() {
    std::lock_guard lock(fftw_planner_mutex());
    fftw_destroy_plan(forward);
    fftw_destroy_plan(inverse);
  }
};

CentreStresses::~CentreStresses() = default;

CentreStresses::CentreStresses(const Grid& grid, std::vector<double> depths)
    : grid_(grid), depths_(std::move(depths)), L_(smooth_size(2 * grid.n + 2)), plans_(std::make_unique<Plans>(L_)) {
  const int n = grid.n, L = L_, half = L / 2 + 1;
  const double h = grid.h();
  const Plans& plans = *plans_;
  Buffers b(L);
  for (auto* spectra : {&a_, &b_, &c_, &d_}) spectra->resize(depths_.size() * std::size_t(half));
  // One kernel at depth y into the spectrum `out` (scaled by −1/(π L), the inverse transform's 1/L included).
  auto transform = [&](auto&& kernel, double y, std::complex<double>* out) {
    std::fill(b.real, b.real + L, 0.0);
    for (int m = -n; m < n; ++m) {
      const double X = (m + 0.5) * h;
      b.real[m >= 0 ? m : L + m] = kernel(X, y);
    }
    fftw_execute_dft_r2c(plans.forward, b.real, b.spec);
    const double scale = -1.0 / (std::numbers::pi * L);
    for (int k = 0; k < half; ++k) out[k] = as_complex(b.spec)[k] * scale;
  };
  for (std::size_t k = 0; k < depths_.size(); ++k) {
    const double y = depths_[k];
    assert(y >= 0.0);
    const std::size_t at = k * std::size_t(half);
    // X ≠ 0 at every centre, so r² > 0 even on the surface.
    transform([](double X, double yy) { return std::atan2(X, yy) - X * yy / (X * X + yy * yy); }, y, &a_[at]);
    transform([](double X, double yy) { return std::atan2(X, yy) + X * yy / (X * X + yy * yy); }, y, &b_[at]);
    transform([](double X, double yy) { return X * X / (X * X + yy * yy); }, y, &c_[at]);
    transform([](double X, double yy) { return std::log(X * X + yy * yy) + yy * yy / (X * X + yy * yy); }, y,
              &d_[at]);
  }
}

std::vector<Stress> CentreStresses::operator()(const SurfaceTractions& t) const {
  const int n = grid_.n, L = L_, half = L / 2 + 1;
  assert(t.grid.n == n && int(t.p.size()) == n);
  const Plans& plans = *plans_;
  Buffers b(L);
  // The jumps Δ_b = value right of ξ_b − value left of it, b = 0 … n (zero beyond the grid), and their spectra.
  auto jump_spectrum = [&](std::span<const double> v) {
    std::vector<std::complex<double>> s(std::size_t(half), 0.0);
    if (v.empty()) return s;
    std::fill(b.real, b.real + L, 0.0);
    for (int j = 0; j <= n; ++j) b.real[j] = (j < n ? v[j] : 0.0) - (j > 0 ? v[j - 1] : 0.0);
    fftw_execute_dft_r2c(plans.forward, b.real, b.spec);
    std::copy(as_complex(b.spec), as_complex(b.spec) + half, s.begin());
    return s;
  };
  const std::vector<std::complex<double>> P = jump_spectrum(t.p), Q = jump_spectrum(t.q);
  std::vector<Stress> out(depths_.size() * std::size_t(n));
  // One component: the inverse transform of Δp ∗ kp + Δq ∗ kq, written at the centres through `member`.
  auto component = [&](const std::complex<double>* kp, const std::complex<double>* kq, double Stress::*member,
                       std::size_t row, double add) {
    std::complex<double>* s = as_complex(b.spec);
    for (int k = 0; k < half; ++k) s[k] = P[std::size_t(k)] * kp[k] + Q[std::size_t(k)] * kq[k];
    fftw_execute_dft_c2r(plans.inverse, b.spec, b.real);
    for (int i = 0; i < n; ++i) out[row * std::size_t(n) + std::size_t(i)].*member = b.real[i] + add;
  };
  for (std::size_t k = 0; k < depths_.size(); ++k) {
    const std::size_t at = k * std::size_t(half);
    component(&a_[at], &d_[at], &Stress::xx, k, t.sigma_bulk);
    component(&b_[at], &c_[at], &Stress::yy, k, 0.0);
    component(&c_[at], &a_[at], &Stress::xy, k, 0.0);
  }
  return out;
}

}  // namespace fretwear
