#include "contact/toeplitz_fft.hpp"

#include <cassert>
#include <mutex>

#include <fftw3.h>
#include <pthread.h>

namespace fretwear {

std::mutex& fftw_planner_mutex() {
  static std::mutex m;
  // A process forked while another of its threads plans would hold the lock in the child for good, where no thread
  // releases it: the fork waits for the lock, then releases it on both sides (a Python pool forks while a thread
  // runs fretwear).
  static const bool fork_safe = [] {
    return ::pthread_atfork([] { m.lock(); }, [] { m.unlock(); }, [] { m.unlock(); }) == 0;
  }();
  (void)fork_safe;
  return m;
}

namespace {
// FFTW_MEASURE plans cost 0.4 s (n = 1024) to 7 s (n = 65536) and bought no measurable speed on a shared core
// (docs/PERFORMANCE.md); the grid of a scene changes with every convergence level, so plans are estimated.
constexpr unsigned kPlannerFlags = FFTW_ESTIMATE;
}  // namespace

struct ToeplitzFFT::Plans {
  int m = 0;                    // circulant size 2n
  double* real = nullptr;       // m (+ 2 of padding), aliases spec
  fftw_complex* spec = nullptr; // m/2 + 1
  fftw_plan forward = nullptr, inverse = nullptr;

  explicit Plans(int m_) : m(m_) {
    std::lock_guard lock(fftw_planner_mutex());
    // In place: the real input shares the spectrum's storage, which halves the memory a product streams through.
    spec = fftw_alloc_complex(m / 2 + 1);
    real = reinterpret_cast<double*>(spec);
    forward = fftw_plan_dft_r2c_1d(m, real, spec, kPlannerFlags);
    inverse = fftw_plan_dft_c2r_1d(m, spec, real, kPlannerFlags);
  }
  ~Plans() {
    std::lock_guard lock(fftw_planner_mutex());
    fftw_destroy_plan(forward);
    fftw_destroy_plan(inverse);
    fftw_free(spec);
  }
};

ToeplitzFFT::ToeplitzFFT(std::span<const double> first_column)
    : n_(int(first_column.size())), plans_(std::make_unique<Plans>(2 * int(first_column.size()))) {
  const int m = plans_->m;
  double* c = plans_->real;
  c[0] = first_column[0];
  for (int k = 1; k < n_; ++k) c[k] = c[m - k] = first_column[k];
  c[n_] = 0.0;  // never reached by a product with zero-padded input
  fftw_execute(plans_->forward);
  kernel_spec_.resize(m / 2 + 1);
  for (int k = 0; k <= m / 2; ++k)
    kernel_spec_[k] = std::complex<double>(plans_->spec[k][0], plans_->spec[k][1]) / double(m);
}

ToeplitzFFT::~ToeplitzFFT() = default;

void ToeplitzFFT::apply(std::span<const double> x, std::span<double> y) const {
  apply_spectrum(kernel_spec_, x, y);
}

void ToeplitzFFT::apply_spectrum(std::span<const std::complex<double>> spectrum, std::span<const double> x,
                                 std::span<double> y) const {
  assert(int(x.size()) == n_ && int(y.size()) == n_ && int(spectrum.size()) == plans_->m / 2 + 1);
  const int m = plans_->m;
  double* r = plans_->real;
  std::copy(x.begin(), x.end(), r);
  std::fill(r + n_, r + m, 0.0);
  fftw_execute(plans_->forward);
  // The product written out: std::complex's operator* guards against infinities and NaN (C99 Annex G), a branch and
  // a library call per entry that keep the loop from vectorising; the spectra here are finite.
  fftw_complex* s = plans_->spec;
  for (int k = 0; k <= m / 2; ++k) {
    const double a = s[k][0], b = s[k][1], c = spectrum[k].real(), d = spectrum[k].imag();
    s[k][0] = a * c - b * d;
    s[k][1] = a * d + b * c;
  }
  fftw_execute(plans_->inverse);
  std::copy(r, r + n_, y.begin());
}

}  // namespace fretwear
