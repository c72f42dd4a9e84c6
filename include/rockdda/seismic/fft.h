/**
 * @file
 * Real discrete Fourier transforms of records, computed by FFTW3.
 */
#ifndef ROCKDDA_SEISMIC_FFT_H
#define ROCKDDA_SEISMIC_FFT_H

#include <complex>
#include <cstddef>
#include <vector>

namespace rockdda::seismic
{
  /// The smallest n' >= @p n whose prime factors are 2, 3, 5 and 7 (sizes
  /// FFTW transforms fastest).
  std::size_t
  fast_fft_size(const std::size_t n);

  /**
   * X_k = sum_j x_j exp(-2 pi i j k / n), k = 0 .. n/2, of @p x padded with
   * zeros to length @p n (n >= x.size(); FFTW r2c, unnormalised).
   */
  std::vector<std::complex<double>>
  forward_real_fft(const std::vector<double> &x, const std::size_t n);

  /**
   * The inverse of forward_real_fft: x_j = (1/n) sum_k X_k exp(2 pi i j k /
   * n) for the Hermitian spectrum @p spectrum (n/2 + 1 values) of a real
   * sequence of length @p n (FFTW c2r, normalised here).
   */
  std::vector<double>
  inverse_real_fft(const std::vector<std::complex<double>> &spectrum,
                   const std::size_t                        n);
} // namespace rockdda::seismic

#endif
