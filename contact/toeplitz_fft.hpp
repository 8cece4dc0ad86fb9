// y = T x for a symmetric n×n Toeplitz matrix T (T_ij = t[|i − j|]) in O(n log n): T is embedded in a circulant of
// size 2n (zero padding, so no periodic images), and the product is two real FFTs and a pointwise product with the
// circulant's spectrum, which is computed once. FFTW plans are made once per instance.
//
// An instance owns scratch buffers: apply() is not reentrant; use one instance per thread.
#pragma once

#include <complex>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

namespace fretwear {

// FFTW's planner is not thread-safe (its execution of distinct plans on distinct buffers is): every plan of the
// program is made and destroyed under this lock.
std::mutex& fftw_planner_mutex();

class ToeplitzFFT {
 public:
  // first_column[k] = t[k], k = 0..n−1.
  explicit ToeplitzFFT(std::span<const double> first_column);
  ~ToeplitzFFT();
  ToeplitzFFT(const ToeplitzFFT&) = delete;
  ToeplitzFFT& operator=(const ToeplitzFFT&) = delete;

  int size() const { return n_; }
  // y = T x; x and y have size() entries and may alias.
  void apply(std::span<const double> x, std::span<double> y) const;
  // y = F x where F is the operator with the given spectrum on the same 2n circulant (used by preconditioners):
  // spectrum has n + 1 entries (the real-FFT half spectrum), already divided by 2n.
  void apply_spectrum(std::span<const std::complex<double>> spectrum, std::span<const double> x,
                      std::span<double> y) const;
  // The circulant's half spectrum, divided by 2n (n + 1 entries).
  std::span<const std::complex<double>> spectrum() const { return kernel_spec_; }

 private:
  struct Plans;
  int n_;
  std::unique_ptr<Plans> plans_;
  std::vector<std::complex<double>> kernel_spec_;
};

}  // namespace fretwear
