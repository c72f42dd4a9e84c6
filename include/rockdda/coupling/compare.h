/**
 * @file
 * Thermal against seismic displacement of Masada Block 1 (thesis 5.6.2,
 * Fig. 5-19) and one combined history (issue 15, item 3): a seeded
 * Gutenberg-Richter catalogue of earthquakes over a window of years, each
 * event's slip from DDA of Block 1 (block1_seismic.h), the seasonal thermal
 * ratchet of Pasten (2012) (analytical/ratchet.h) every year, and the
 * tension crack's wedge that grows with every opening of the crack, so that
 * an earthquake that opens the crack raises the thermal rate of the years
 * after it. doc/theory/compare.md describes the model and what it
 * simplifies.
 */
#ifndef ROCKDDA_COUPLING_COMPARE_H
#define ROCKDDA_COUPLING_COMPARE_H

#include <rockdda/analytical/ratchet.h>

#include <cstdint>
#include <vector>

namespace rockdda::coupling
{
  /**
   * A truncated Gutenberg-Richter (1944) magnitude distribution,
   * log10 N(>= M) = a - b M for min_magnitude <= M <= max_magnitude, with
   * Poisson occurrence in time; a is set by the mean interval between
   * events of at least min_magnitude.
   */
  struct GutenbergRichter
  {
    /// b-value (-), > 0 (the thesis' recurrence intervals 300, 1100 and
    /// 4000 yr for Mw >= 6, 6.5, 7 within 8 % with the truncation at 7.5).
    double b_value = 1.;
    /// Smallest and largest magnitude of the catalogue (-).
    double min_magnitude = 6., max_magnitude = 7.5;
    /// Mean interval between events of magnitude >= min_magnitude (yr), > 0.
    double recurrence = 300.;

    /// Mean interval (yr) between events of magnitude >= @p m.
    double
    recurrence_of(const double m) const;
  };

  /// One event of a catalogue.
  struct CatalogueEvent
  {
    /// Time from the start of the window (yr) and moment magnitude (-).
    double time = 0., magnitude = 0.;
    /// Seed of its synthetic motion.
    std::uint64_t motion_seed = 0;
  };

  /**
   * A catalogue over [0, @p window) years: exponential inter-event times
   * of mean GutenbergRichter::recurrence and magnitudes from the truncated
   * exponential distribution by inversion, from std::mt19937_64 seeded with
   * @p seed (uniform numbers from its top 53 bits, so a seed gives the same
   * catalogue on every platform). Event k (0-based) gets the motion seed
   * @p seed x 100003 + k + 1. Throws InputError naming the key for a b-value
   * <= 0, max <= min magnitude, a recurrence or window <= 0.
   */
  std::vector<CatalogueEvent>
  gutenberg_richter_catalogue(const GutenbergRichter &gr,
                              const double            window,
                              const std::uint64_t     seed);

  /// What a history gives at the end of its window (m, along the plane).
  struct HistoryResult
  {
    /// Displacement by the thermal cycles and by the earthquakes in the
    /// combined history, and their sum.
    double thermal = 0., seismic = 0., total = 0.;
    /// Wedge length (crack opening filled by the infill) at the end (m).
    double wedge_length = 0.;
    /// Largest wedge length / skin depth over the history (-): the model
    /// holds while it is below 1 (Pasten 2012; thesis 5.6.2).
    double wedge_over_skin_depth = 0.;
    /// Total displacement at the end of each year (m), if asked for.
    std::vector<double> yearly;
  };

  /**
   * One history of @p years annual cycles. Each year the thermal ratchet
   * slips the block by the plastic displacement delta_p(L_W) of
   * analytical::ratchet() with the wedge length L_W of that year; then the
   * earthquakes of that year slip it by @p slips[k] (m, those of
   * @p events in [year, year + 1)). Every slip s opens the crack
   * horizontally by max(s, 0) cos(dip) and the infill fills the opening at
   * once: L_W grows by that much (thesis 5.6.2: the rate grows with the
   * crack's opening). @p ratchet is the input of the first year (its
   * wedge_length the initial L_W). Without events this is the thermal
   * history alone.
   */
  HistoryResult
  combined_history(const analytical::RatchetInput    &ratchet,
                   const unsigned int                 years,
                   const std::vector<CatalogueEvent> &events,
                   const std::vector<double>         &slips,
                   const bool                         keep_yearly = false);
} // namespace rockdda::coupling

#endif
