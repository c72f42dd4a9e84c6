/**
 * @file
 * The comparison of thermal and seismic displacement (issue 15, item 3):
 * the Gutenberg-Richter catalogue and the combined history.
 */
#include <rockdda/coupling/compare.h>
#include <rockdda/io/error.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

using namespace rockdda;
using namespace rockdda::coupling;

// The recurrence of the thesis' intervals (300, 1100, 4000 yr for Mw >= 6,
// 6.5, 7) is a Gutenberg-Richter law truncated at Mw 7.5 with b = 1.0:
// from 300 yr it gives 1021 and 4249 yr, within 8 % of the thesis' values
// (b = 1.12 fits the untruncated law, but the truncation lengthens the
// intervals of the large events: 5343 yr at Mw 7).
TEST(Compare, RecurrenceOfTheThesisIsGutenbergRichter)
{
  GutenbergRichter gr;
  EXPECT_DOUBLE_EQ(gr.b_value, 1.);
  EXPECT_DOUBLE_EQ(gr.recurrence_of(6.), 300.);
  EXPECT_NEAR(gr.recurrence_of(6.5) / 1100., 1., 0.08);
  EXPECT_NEAR(gr.recurrence_of(7.) / 4000., 1., 0.08);
  // Untruncated limit: 10^(b dM).
  gr.max_magnitude = 20.;
  EXPECT_NEAR(gr.recurrence_of(7.), 3000., 1e-9);
}

// A catalogue's statistics: over many catalogues the mean number of events
// is window / recurrence (Poisson) and the fraction at or above M is
// T(M_min) / T(M) (the magnitude law), within 4 standard errors; the same
// seed gives the same catalogue; magnitudes stay in [M_min, M_max] and
// times in [0, window).
TEST(Compare, CatalogueStatistics)
{
  GutenbergRichter gr;
  const double     window = 5000.;
  const int        n      = 400;
  double           events = 0., above7 = 0.;
  for (int s = 1; s <= n; ++s)
    for (const auto &e : gutenberg_richter_catalogue(gr, window, s))
      {
        ++events;
        above7 += e.magnitude >= 7. ? 1. : 0.;
        ASSERT_GE(e.magnitude, gr.min_magnitude);
        ASSERT_LE(e.magnitude, gr.max_magnitude);
        ASSERT_GE(e.time, 0.);
        ASSERT_LT(e.time, window);
      }
  const double mean = window / gr.recurrence; // 16.7 per catalogue
  EXPECT_NEAR(events / n, mean, 4. * std::sqrt(mean / n));
  const double p = gr.recurrence / gr.recurrence_of(7.);
  EXPECT_NEAR(above7 / events, p, 4. * std::sqrt(p * (1. - p) / events));
  const auto a = gutenberg_richter_catalogue(gr, window, 7);
  const auto b = gutenberg_richter_catalogue(gr, window, 7);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k)
    {
      EXPECT_EQ(a[k].time, b[k].time);
      EXPECT_EQ(a[k].magnitude, b[k].magnitude);
      EXPECT_EQ(a[k].motion_seed, b[k].motion_seed);
    }
}

// Bad catalogue input is an InputError naming the key.
TEST(Compare, BadCatalogueNamesTheKey)
{
  const auto expect_key
    = [](GutenbergRichter gr, const double window, const std::string &key) {
        try
          {
            gutenberg_richter_catalogue(gr, window, 1);
            ADD_FAILURE() << "no error for " << key;
          }
        catch (const InputError &e)
          {
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos)
              << e.what();
          }
      };
  GutenbergRichter gr;
  gr.b_value = 0.;
  expect_key(gr, 100., "Compare/b-value");
  gr            = GutenbergRichter();
  gr.recurrence = -1.;
  expect_key(gr, 100., "Compare/Recurrence interval");
  gr               = GutenbergRichter();
  gr.max_magnitude = 5.;
  expect_key(gr, 100., "Compare/Maximum magnitude");
  expect_key(GutenbergRichter(), 0., "Compare/Window");
}

// Without earthquakes the history is the thermal ratchet alone: the first
// year's slip is delta_p(L_W0) of the analytical model, and the sum over
// the years equals the sum of delta_p over the wedge lengths it passes
// through (each year's wedge = the previous one + delta_p cos(dip)),
// checked by an independent loop.
TEST(Compare, ThermalHistoryIsTheRatchetYearByYear)
{
  analytical::RatchetInput in;
  in.wedge_length     = 0.;
  const auto h        = combined_history(in, 1000, {}, {}, true);
  double     expected = 0., wedge = 0.;
  for (int y = 0; y < 1000; ++y)
    {
      analytical::RatchetInput r = in;
      r.wedge_length             = wedge;
      const double d             = analytical::ratchet(r).plastic_displacement;
      expected += d;
      wedge += d * std::cos(19. * M_PI / 180.);
    }
  EXPECT_NEAR(h.thermal, expected, 1e-12 * expected);
  EXPECT_EQ(h.seismic, 0.);
  EXPECT_NEAR(h.yearly.front(),
              analytical::ratchet(in).plastic_displacement,
              1e-15);
  EXPECT_NEAR(h.wedge_length, wedge, 1e-12);
  // Thesis Fig. 5-13 / 5.6.2: 0.181 mm/yr at L_W = 0, rising with the
  // wedge (0.210 mm/yr at 0.2 m): the mean over 1000 yr lies between.
  EXPECT_GT(h.thermal / 1000., analytical::ratchet(in).plastic_displacement);
}

// Conservation and the one interaction of the model: the seismic part of a
// combined history is exactly the sum of the slips, and an earthquake adds
// its slip once and then raises every later year's thermal slip (the crack
// opened by s cos(dip) is filled by infill: a longer wedge). So the
// combined total exceeds thermal-alone + seismic-alone by
// sum_y [delta_p(L_W + s cos) - delta_p(L_W)] > 0, and by more the earlier
// the earthquake comes; an event in the last year changes nothing thermal.
TEST(Compare, EarthquakeOpensTheCrackAndRaisesTheRatchet)
{
  analytical::RatchetInput in;
  const unsigned int       years    = 2000;
  const double             slip     = 0.1;
  const auto               thermal  = combined_history(in, years, {}, {});
  double                   previous = std::numeric_limits<double>::infinity();
  for (const double t : {10.5, 1000.5, 1999.5})
    {
      CatalogueEvent e;
      e.time       = t;
      e.magnitude  = 7.;
      const auto h = combined_history(in, years, {e}, {slip});
      EXPECT_DOUBLE_EQ(h.seismic, slip);
      const double interaction = h.total - (thermal.total + slip);
      // d delta_p / d L_W from the analytical model, times the opening,
      // times the years left: the first-order interaction.
      analytical::RatchetInput a = in, b = in;
      a.wedge_length     = 0.1;
      b.wedge_length     = 0.1 + 1e-3;
      const double slope = (analytical::ratchet(b).plastic_displacement
                            - analytical::ratchet(a).plastic_displacement)
                           / 1e-3;
      const double first_order = slope * slip * std::cos(19. * M_PI / 180.)
                                 * (years - 1 - std::floor(t));
      std::printf("event at %.1f yr: interaction %.4e m (first order %.4e)\n",
                  t,
                  interaction,
                  first_order);
      EXPECT_GE(interaction, 0.);
      EXPECT_LT(interaction, previous);
      previous = interaction;
      // Within 20 %: delta_p(L_W) is not linear and its slope, taken at
      // L_W = 0.1 m, changes along the history's path (the wedge grows
      // from 0 to 0.5 m over 2000 yr); measured 1.15 and 1.07.
      if (first_order > 0.)
        EXPECT_NEAR(interaction / first_order, 1., 0.2);
      else
        EXPECT_NEAR(interaction, 0., 1e-15);
    }
}
