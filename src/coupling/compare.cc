#include <rockdda/coupling/compare.h>
#include <rockdda/io/error.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace rockdda::coupling
{
  namespace
  {
    constexpr double pi = 3.14159265358979323846;

    /// A uniform number in (0, 1) from the top 53 bits of one draw.
    double
    uniform(std::mt19937_64 &engine)
    {
      return (static_cast<double>(engine() >> 11) + 0.5) * 0x1.0p-53;
    }
  } // namespace



  double
  GutenbergRichter::recurrence_of(const double m) const
  {
    if (m <= min_magnitude)
      return recurrence;
    if (m > max_magnitude)
      return std::numeric_limits<double>::infinity();
    // Truncated: N(>= m) = N0 (10^(-b (m - m0)) - 10^(-b (m1 - m0))) /
    // (1 - 10^(-b (m1 - m0))).
    const double tail
      = std::pow(10., -b_value * (max_magnitude - min_magnitude));
    const double frac
      = (std::pow(10., -b_value * (m - min_magnitude)) - tail) / (1. - tail);
    return recurrence / frac;
  }



  std::vector<CatalogueEvent>
  gutenberg_richter_catalogue(const GutenbergRichter &gr,
                              const double            window,
                              const std::uint64_t     seed)
  {
    require_in_range(gr.b_value > 0. && std::isfinite(gr.b_value),
                     "Compare/b-value",
                     gr.b_value,
                     "> 0");
    require_in_range(gr.max_magnitude > gr.min_magnitude,
                     "Compare/Maximum magnitude",
                     gr.max_magnitude,
                     "> 'Minimum magnitude'");
    require_in_range(gr.recurrence > 0. && std::isfinite(gr.recurrence),
                     "Compare/Recurrence interval",
                     gr.recurrence,
                     "> 0 yr");
    require_in_range(window > 0. && std::isfinite(window),
                     "Compare/Window",
                     window,
                     "> 0 yr");
    std::mt19937_64             engine(seed);
    std::vector<CatalogueEvent> events;
    const double                span = gr.max_magnitude - gr.min_magnitude;
    const double                tail = 1. - std::pow(10., -gr.b_value * span);
    for (double t = -gr.recurrence * std::log(uniform(engine)); t < window;
         t -= gr.recurrence * std::log(uniform(engine)))
      {
        CatalogueEvent e;
        e.time      = t;
        e.magnitude = gr.min_magnitude
                      - std::log10(1. - uniform(engine) * tail) / gr.b_value;
        e.magnitude   = std::min(e.magnitude, gr.max_magnitude);
        e.motion_seed = seed * 100003u + events.size() + 1;
        events.push_back(e);
      }
    return events;
  }



  HistoryResult
  combined_history(const analytical::RatchetInput    &ratchet,
                   const unsigned int                 years,
                   const std::vector<CatalogueEvent> &events,
                   const std::vector<double>         &slips,
                   const bool                         keep_yearly)
  {
    if (slips.size() != events.size())
      throw std::invalid_argument("combined_history: one slip per event");
    analytical::RatchetInput in    = ratchet;
    const double  opening_per_slip = std::cos(in.slope_deg * pi / 180.);
    HistoryResult h;
    std::size_t   next = 0;
    for (unsigned int y = 0; y < years; ++y)
      {
        const analytical::RatchetResult r = analytical::ratchet(in);
        h.wedge_over_skin_depth
          = std::max(h.wedge_over_skin_depth, in.wedge_length / r.skin_depth);
        h.thermal += r.plastic_displacement;
        in.wedge_length += r.plastic_displacement * opening_per_slip;
        for (; next < events.size() && events[next].time < y + 1.; ++next)
          {
            h.seismic += slips[next];
            in.wedge_length += std::max(slips[next], 0.) * opening_per_slip;
          }
        if (keep_yearly)
          h.yearly.push_back(h.thermal + h.seismic);
      }
    // Events beyond the last year (none if the catalogue has the window).
    for (; next < events.size(); ++next)
      h.seismic += slips[next];
    h.total        = h.thermal + h.seismic;
    h.wedge_length = in.wedge_length;
    return h;
  }
} // namespace rockdda::coupling
