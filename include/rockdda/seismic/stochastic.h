/**
 * @file
 * Synthetic ground motion by the stochastic point-source method (Boore
 * 2003, SMSIM): a target Fourier amplitude spectrum of the S waves (Brune
 * source, geometric spreading, Q(f), kappa, crustal and site amplification)
 * imposed on windowed Gaussian white noise.
 */
#ifndef ROCKDDA_SEISMIC_STOCHASTIC_H
#define ROCKDDA_SEISMIC_STOCHASTIC_H

#include <rockdda/seismic/record.h>
#include <rockdda/seismic/site_amplification.h>

#include <cstdint>
#include <string>
#include <vector>

namespace rockdda::seismic
{
  /// The crustal amplification of the path from the source's depth to the
  /// surface (a site term besides kappa).
  enum class CrustalAmplification
  {
    /// None (A = 1).
    none,
    /// Boore & Joyner (1997), generic rock of western North America
    /// (Vs30 = 620 m/s), by quarter-wavelength; log-log interpolation of
    /// their table, 1 below 0.01 Hz, 4.0 above 61.2 Hz.
    generic_rock
  };

  /**
   * The parameters of a stochastic point-source simulation, in SI units.
   * The defaults describe crustal earthquakes in western North America
   * (California) on generic rock: Brune source with 70 bar (Boore 2003),
   * radiation, free-surface and partition factors of Boore (2003),
   * geometric spreading 1/R to 40 km and 1/sqrt(R) beyond, duration 1/fc +
   * 0.05 s/km R and pseudo-depth of Atkinson & Silva (2000), kappa0 0.04 s
   * and the generic-rock crustal amplification of Boore & Joyner (1997). Q0
   * is 600 (f^0.45) instead of the 180 of Atkinson & Silva (2000): with 180
   * the median PGA decays faster with distance than BJF97 (0.48 of it at M
   * 6, 50 km); 600 keeps it within 0.71-1.27 of BJF97 for M 6-7.5 at 10-50
   * km (doc/theory/seismic-synthetic.md).
   */
  struct StochasticParameters
  {
    /// Moment magnitude M (-); M0 = 10^(1.5 M + 9.05) N m (Hanks & Kanamori
    /// 1979, as Boore 2003).
    double magnitude = 7.;
    /// Horizontal distance from the site to the surface projection of the
    /// source, Rjb (m).
    double distance = 20e3;
    /// Depth h of the equivalent point source (m); 0: the pseudo-depth of
    /// Atkinson & Silva (2000), log10(h / 1 km) = -0.05 + 0.15 M, which
    /// stands for the finite extent of a large fault. R = sqrt(Rjb^2 + h^2).
    double depth = 0.;
    /// Brune stress parameter (Pa); 7 MPa = 70 bar.
    double stress_parameter = 7e6;
    /// Density rho (kg/m^3) and shear-wave velocity beta (m/s) near the
    /// source.
    double density = 2800., shear_velocity = 3500.;
    /// Average S-wave radiation pattern R_theta_phi (-), free-surface
    /// factor F (-) and partition onto one horizontal component V (-).
    double radiation_pattern = 0.55, free_surface = 2.,
           partition = 0.7071067811865476;
    /// Geometric spreading: (R0 / R)^near for R <= transition, then
    /// G(transition) (transition / R)^far, with R0 = 1 km.
    double spreading_near = 1., spreading_transition = 40e3,
           spreading_far = 0.5;
    /// Anelastic attenuation Q(f) = q0 f^q_exponent (f in Hz).
    double q0 = 600., q_exponent = 0.45;
    /// High-frequency diminution exp(-pi kappa0 f) (s).
    double kappa = 0.04;
    /// Crustal amplification.
    CrustalAmplification crustal = CrustalAmplification::generic_rock;
    /// Duration of ground motion T_gm = source_duration / fc +
    /// path_duration R (s): 1 / fc (Boore 2003) and 0.05 s/km (Atkinson &
    /// Silva 2000) = 5e-5 s/m.
    double source_duration = 1., path_duration = 5e-5;
    /// Saragoni & Hart (1974) window as Boore (2003) writes it: the window
    /// w(t) = a (t/t_eta)^b exp(-c t/t_eta) peaks (at 1) at t = epsilon
    /// t_eta and falls to eta at t_eta = window_factor T_gm.
    double window_epsilon = 0.2, window_eta = 0.05, window_factor = 2.;
    /// Time step of the simulated record (s).
    double dt = 0.005;
    /// Site (topographic) amplification multiplied into the target.
    SiteAmplification site;
  };

  /// Seismic moment M0 (N m) of moment magnitude @p magnitude.
  double
  seismic_moment(const double magnitude);

  /// Brune corner frequency fc = 0.4906 beta (stress / M0)^(1/3) (Hz).
  double
  corner_frequency(const StochasticParameters &p);

  /// Depth h of the point source (m): p.depth or the pseudo-depth.
  double
  source_depth(const StochasticParameters &p);

  /// Distance R = sqrt(Rjb^2 + h^2) from the point source (m).
  double
  source_distance(const StochasticParameters &p);

  /// Duration of ground motion T_gm (s).
  double
  motion_duration(const StochasticParameters &p);

  /// Geometric spreading G(R) (-) at distance @p r (m).
  double
  geometric_spreading(const StochasticParameters &p, const double r);

  /// Crustal amplification (-) at frequency @p f (Hz).
  double
  crustal_amplification(const CrustalAmplification type, const double f);

  /**
   * The target Fourier amplitude spectrum of acceleration (g s) at @p f
   * (Hz):
   *   A(f) = C M0 (2 pi f)^2 / (1 + (f/fc)^2) G(R) exp(-pi f R / (Q(f) beta))
   *          Amp(f) exp(-pi kappa f) Site(f) / g,
   *   C = R_theta_phi F V / (4 pi rho beta^3 R0), R0 = 1 km.
   * @p with_site false leaves the site amplification out.
   */
  double
  target_fourier_amplitude(const StochasticParameters &p,
                           const double                f,
                           const bool                  with_site = true);

  /**
   * One realisation (Boore 2003, Sec. 3): Gaussian white noise of unit
   * variance from std::mt19937_64 seeded with @p seed (Box-Muller on its
   * 53-bit uniforms, so the record depends on the seed alone, bit for bit),
   * multiplied by the Saragoni-Hart window, transformed by FFTW, divided by
   * the root mean square of its amplitude spectrum, multiplied by the
   * target (zero phase added) and transformed back. Zero pads of max(2 s,
   * 1/fc) lie before the window and after it; the record's length is an
   * FFT size, so its Fourier amplitude spectrum (spectra.h) on its own
   * length is the target times the normalised noise spectrum, bin by bin.
   * @p with_site false leaves the site amplification out (the same noise:
   * a realisation with and without the site shares its seed).
   */
  Record
  simulate(const StochasticParameters &p,
           const std::uint64_t         seed,
           const bool                  with_site = true);

  /// Time (s) at which the window of simulate() starts (its front pad).
  double
  window_start(const StochasticParameters &p);

  /// Simulated and target Fourier amplitudes in fractional-octave bands.
  struct BandSpectra
  {
    /// Geometric band centres (Hz).
    std::vector<double> frequency;
    /// Root of the band mean of A(f)^2 over the FFT bins in the band (g s).
    std::vector<double> target;
    /// Root of the mean of |X(f)|^2 over the same bins and over every
    /// realisation added (g s): the quadratic mean, whose expectation is
    /// the target (the arithmetic mean of a Rayleigh-like amplitude is
    /// sqrt(pi)/2 = 0.886 of it).
    std::vector<double> mean;
    /// Realisations averaged.
    std::size_t realisations = 0;
  };

  /**
   * Accumulates the Fourier power spectra of realisations of one scenario
   * (all of one length and time step, as simulate() makes them) and
   * compares their quadratic mean with the target in bands.
   */
  class SpectrumAverager
  {
  public:
    /// For realisations of @p p, with or without its site amplification.
    SpectrumAverager(const StochasticParameters &p, const bool with_site);

    /// Add the spectrum of @p record (Fourier amplitude spectrum of
    /// spectra.h on the record's own length).
    void
    add(const Record &record);

    /**
     * Bands of 1/@p per_octave octave centred on f_low 2^(j/per_octave),
     * j = 0, 1, ... up to @p f_high, each spanning a factor 2^(1/per_octave)
     * (bands with no FFT bin are skipped).
     */
    BandSpectra
    bands(const double       f_low,
          const double       f_high,
          const unsigned int per_octave) const;

  private:
    StochasticParameters parameters;
    bool                 with_site;
    double               df    = 0.;
    std::size_t          count = 0;
    std::vector<double>  power;
  };

  /// One line describing @p p, for logs.
  std::string
  describe(const StochasticParameters &p);
} // namespace rockdda::seismic

#endif
