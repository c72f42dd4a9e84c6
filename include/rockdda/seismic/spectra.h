/**
 * @file
 * Fourier amplitude spectrum and elastic response spectrum of a record.
 */
#ifndef ROCKDDA_SEISMIC_SPECTRA_H
#define ROCKDDA_SEISMIC_SPECTRA_H

#include <rockdda/seismic/record.h>

#include <vector>

namespace rockdda::seismic
{
  /// One-sided Fourier amplitude spectrum of an acceleration record.
  struct FourierSpectrum
  {
    /// Frequencies k df, k = 0 .. n/2 (Hz).
    std::vector<double> frequency;
    /// |X(f)| = dt |sum_j a_j exp(-2 pi i f t_j)| (g s): the continuous
    /// transform of the sampled record.
    std::vector<double> amplitude;
  };

  /**
   * The Fourier amplitude spectrum of @p record by FFTW, zero-padded to at
   * least @p min_length samples (0: the record's own length), rounded up to
   * a fast FFT size.
   */
  FourierSpectrum
  fourier_amplitude_spectrum(const Record     &record,
                             const std::size_t min_length = 0);

  /// Relative displacement and velocity of a damped linear oscillator.
  struct OscillatorResponse
  {
    /// Time step of the values (s): the record's dt / subdivisions.
    double dt = 0.;
    /// Relative displacement (m) and velocity (m/s) at t = i dt.
    std::vector<double> displacement, velocity;
  };

  /**
   * Response of the oscillator u'' + 2 zeta w u' + w^2 u = -a(t) (w = 2 pi /
   * @p period, zeta = @p damping, at rest at t = 0) to the record, taken as
   * piecewise linear between samples: the exact recursion of Nigam &
   * Jennings (1969), with each sample interval split into @p subdivisions
   * sub-steps (same input, more output points; they only sharpen the peaks).
   * 0 <= damping < 1, period > 0.
   */
  OscillatorResponse
  oscillator_response(const Record      &record,
                      const double       period,
                      const double       damping,
                      const unsigned int subdivisions = 1);

  /// An elastic response spectrum.
  struct ResponseSpectrum
  {
    /// Damping ratio (-).
    double damping = 0.05;
    /// Periods (s).
    std::vector<double> period;
    /// SD = max |u| (m).
    std::vector<double> displacement;
    /// PSV = w SD (m/s).
    std::vector<double> pseudo_velocity;
    /// PSA = w^2 SD (g); tends to PGA as the period tends to 0.
    std::vector<double> pseudo_acceleration;
  };

  /// The response spectrum of @p record at @p periods (see
  /// oscillator_response for the method and the arguments); @p subdivisions
  /// 0 picks, per period T, the fewest sub-steps with dt / m <= T / 20.
  ResponseSpectrum
  response_spectrum(const Record              &record,
                    const std::vector<double> &periods,
                    const double               damping      = 0.05,
                    const unsigned int         subdivisions = 1);

  /// @p n periods from @p first to @p last, evenly spaced in log(T).
  std::vector<double>
  log_spaced_periods(const double       first,
                     const double       last,
                     const unsigned int n);
} // namespace rockdda::seismic

#endif
