/**
 * @file
 * Record processing: baseline correction, acausal Butterworth filtering in
 * the frequency domain with zero padding (Boore & Bommer 2005), resampling.
 */
#ifndef ROCKDDA_SEISMIC_PROCESSING_H
#define ROCKDDA_SEISMIC_PROCESSING_H

#include <rockdda/seismic/record.h>

#include <string>

namespace rockdda::seismic
{
  /**
   * Remove a polynomial baseline of degree @p degree (0, 1 or 2) from the
   * acceleration: the polynomial q(t) whose trapezoidal integral Q best fits
   * the velocity in least squares, subject to Q(T) = v(T), is subtracted.
   * The corrected record's velocity therefore ends at zero (to round-off).
   * Degree 0 removes the constant that zeroes the final velocity.
   */
  void
  remove_baseline(Record &record, const unsigned int degree);

  /**
   * Gain of the zero-phase Butterworth low-pass filter of order @p order
   * and corner @p corner (Hz) at frequency @p f: 1 / sqrt(1 + (f/fc)^(2n)),
   * the magnitude of an order-n Butterworth filter, with no phase shift:
   * -3.01 dB at the corner. (A causal order-n/2 filter run forward and
   * backward, as in Boore & Bommer 2005, has the gain 1/(1 + (f/fc)^n):
   * -6 dB at the corner.)
   */
  double
  low_pass_gain(const double f, const double corner, const unsigned int order);

  /// Gain of the zero-phase high-pass: 1 / sqrt(1 + (fc/f)^(2n)); 0 at f = 0.
  double
  high_pass_gain(const double f, const double corner, const unsigned int order);

  /// Zero padding (s) added before and after a record for acausal
  /// filtering: half of T_pad = 1.5 n / fc each (Boore & Bommer 2005,
  /// Eq. 1, with fc the lowest corner).
  double
  filter_padding(const double       high_pass,
                 const double       low_pass,
                 const unsigned int order);

  /**
   * Filter @p record acausally (zero phase) with a high-pass at @p high_pass
   * and a low-pass at @p low_pass (Hz; 0 leaves that side open): pad
   * filter_padding() of zeros at both ends, transform with FFTW, multiply by
   * the gains, transform back. With @p keep_padding the padded record is
   * returned (the filter's transients lie in the pads: integrating it is
   * consistent, Boore & Bommer 2005), otherwise the original span. Returns
   * the padding before the record (s).
   */
  double
  filter_acausal(Record            &record,
                 const double       high_pass,
                 const double       low_pass,
                 const unsigned int order,
                 const bool         keep_padding);

  /// How resample() interpolates.
  enum class ResampleMethod
  {
    /// Band-limited (FFT): exact for a record with no energy above the
    /// lower of the two Nyquist frequencies; an ideal anti-alias low-pass
    /// when the step grows.
    fourier,
    /// Linear interpolation (aliases when the step grows).
    linear
  };

  /**
   * Resample @p record at step @p dt (s) over the same duration. The
   * Fourier method needs dt / record.dt to be a ratio of integers up to
   * 1000 (e.g. 0.01 -> 0.005, 0.005 -> 0.02); otherwise InputError.
   */
  Record
  resample(const Record &record, const double dt, const ResampleMethod method);

  /// The processing steps, in the order applied.
  struct ProcessingOptions
  {
    /// Resampling step (s); 0: keep the record's step.
    double         resample_dt = 0.;
    ResampleMethod method      = ResampleMethod::fourier;
    /// Baseline degree 0, 1 or 2; -1: none.
    int baseline_degree = -1;
    /// Corners (Hz); 0: no filter on that side.
    double       high_pass = 0., low_pass = 0.;
    unsigned int order        = 4;
    bool         keep_padding = true;
  };

  /// What process() did.
  struct ProcessingReport
  {
    /// Zero padding added before the record (s) and kept in it.
    double padding = 0.;
    /// One line for the log.
    std::string description;
  };

  /// Resample, remove the baseline and filter, in this order.
  Record
  process(const Record            &record,
          const ProcessingOptions &options,
          ProcessingReport        *report = nullptr);
} // namespace rockdda::seismic

#endif
