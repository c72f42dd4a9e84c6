/**
 * @file
 * Empirical site and topographic amplification functions A(f) and their
 * zero-phase application to a record through its Fourier spectrum.
 */
#ifndef ROCKDDA_SEISMIC_SITE_AMPLIFICATION_H
#define ROCKDDA_SEISMIC_SITE_AMPLIFICATION_H

#include <rockdda/seismic/record.h>

#include <string>
#include <vector>

namespace rockdda::seismic
{
  /// One resonant mode of a site amplification function.
  struct ResonantMode
  {
    /// Resonance frequency f_i (Hz), > 0.
    double frequency = 1.;
    /// Amplification at f_i (-), > 0 (below 1: a trough).
    double peak = 2.;
    /// Full width of the mode's excess at half its height, the half-power
    /// bandwidth (Hz), > 0.
    double width = 0.5;
  };

  /**
   * A real, non-negative amplification function A(f) of frequency, applied
   * to the Fourier spectrum of a motion without a phase shift. Either
   *
   * - a table (f_k, A_k), f_k > 0 increasing, A_k >= 0, interpolated
   *   linearly in (log f, log A) between the points (linearly in A on an
   *   interval with an end at A = 0) and held constant beyond the first and
   *   the last point; or
   * - a sum of resonant modes times a high cut:
   *     A(f) = [1 + sum_i c_i L_i(f)] G(f),
   *     L_i(f) = 1 / (1 + Q_i^2 (f/f_i - f_i/f)^2),  Q_i = f_i / w_i,
   *   each L_i the unit-peak response of a second-order resonance (the
   *   squared gain of a band-pass, as an oscillator's power response):
   *   L_i = 1/2 at exactly two frequencies w_i apart (its full width at half
   *   height, the half-power bandwidth f_i / Q_i), and L_i = 0 at f = 0 and
   *   f -> infinity, so that A = 1 at low frequencies (the long waves do not
   *   see the topography) and G at high ones. G is the gain of a zero-phase
   *   Butterworth low-pass of the given corner and order (1 without a cut).
   *   The excesses c_i solve the n x n system A(f_j) = p_j (j = 1..n), so
   *   that at each mode frequency the amplification is exactly that mode's
   *   peak p_j, whatever the overlap of the other modes' tails (for well
   *   separated modes c_i ~ p_i - 1;
   *   the local maximum moves from f_i by a fraction of w_i of the order of
   *   the overlap). The function must stay >= 0 at every frequency; a set
   *   of modes for which it does not is rejected.
   *
   * The default object is A(f) = 1.
   */
  class SiteAmplification
  {
  public:
    /// A(f) = 1.
    SiteAmplification() = default;

    /**
     * The table (@p frequency, @p amplification); @p source names where it
     * came from in messages. Throws InputError (naming @p source and the
     * point's @p lines entry, if given) for fewer than 2 points, f <= 0,
     * frequencies not increasing, or A < 0 or not finite.
     */
    static SiteAmplification
    from_table(const std::vector<double>       &frequency,
               const std::vector<double>       &amplification,
               const std::string               &source,
               const std::vector<unsigned int> &lines = {});

    /**
     * Read a table file: two columns f (Hz) and A (-) separated by blanks,
     * commas or semicolons; '#' comments and blank lines skipped; one header
     * line of names allowed before the first point. Throws InputError naming
     * the file and the line (a malformed or negative value, frequencies not
     * increasing, a missing file).
     */
    static SiteAmplification
    read_table(const std::string &file_name);

    /**
     * The modes @p modes with a Butterworth high cut of corner
     * @p cut_frequency (Hz; 0: none) and order @p cut_order. Throws
     * InputError naming the mode for a frequency, peak or width <= 0, two
     * modes at one frequency, a peak above the cut that the cut removes
     * (G(f_i) < 1e-3), or modes whose sum is negative somewhere.
     */
    static SiteAmplification
    from_modes(const std::vector<ResonantMode> &modes,
               const double                     cut_frequency = 0.,
               const unsigned int               cut_order     = 8);

    /**
     * The approximation of the empirical topographic response of the top
     * of Masada (thesis Fig. 5-14B, after Zaslavsky et al. 2002) that
     * rockdda ships: modes at 1.3, 3.8 and 6.5 Hz (the frequencies the
     * thesis states) with the peaks and widths of masada_modes() and an
     * order-8 cut at 10 Hz ('frequencies higher than 10 Hz filtered out').
     * The peaks and widths are not in the text: see masada_modes().
     */
    static SiteAmplification
    masada();

    /**
     * The modes of masada(): (1.3 Hz, 2.5, 0.8 Hz), (3.8 Hz, 3.0, 1.2 Hz),
     * (6.5 Hz, 2.0, 1.5 Hz). The peaks are estimates chosen so that the PGA
     * of rock motions is amplified about 1.7 times, as the thesis's example
     * (0.275 g at the foot to 0.465 g at the top, Fig. 5-14A, C); widths of
     * about 0.2-0.6 f_i as usual for topographic H/V peaks.
     */
    static std::vector<ResonantMode>
    masada_modes();

    /// The cut of masada() (Hz).
    static constexpr double masada_cut_frequency = 10.;

    /// A(f) (-) at frequency @p f >= 0 (Hz).
    double
    operator()(const double f) const;

    /// True for the default A(f) = 1.
    bool
    is_unity() const
    {
      return kind == Kind::unity;
    }

    /// One line for logs, e.g. "3 modes (1.3 Hz x 2.5, ...), cut 10 Hz".
    const std::string &
    description() const
    {
      return text;
    }

  private:
    enum class Kind
    {
      unity,
      table,
      modes
    };
    Kind                      kind = Kind::unity;
    std::vector<double>       log_f, values;
    std::vector<ResonantMode> mode_list;
    std::vector<double>       excess;
    double                    cut       = 0.;
    unsigned int              cut_order = 8;
    std::string               text      = "none (A = 1)";

    /// 1 + sum_i c_i L_i(f), without the cut.
    double
    mode_sum(const double f) const;
  };

  /**
   * @p record with its Fourier spectrum multiplied by @p amplification (zero
   * phase), by FFTW: the record is padded with zeros to at least twice its
   * length (so that the spreading of the product in time does not wrap
   * around), transformed, multiplied, transformed back and cut to its
   * original span. A steady sinusoid of frequency f comes out A(f) times
   * larger away from the ends.
   */
  Record
  apply_site_amplification(const Record            &record,
                           const SiteAmplification &amplification);
} // namespace rockdda::seismic

#endif
