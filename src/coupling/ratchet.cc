#include <rockdda/coupling/ratchet.h>
#include <rockdda/dda/block_matrices.h>
#include <rockdda/dda/contact_law.h>
#include <rockdda/io/binary_stream.h>
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>

namespace rockdda::coupling
{



  RatchetRun::RatchetRun(const RatchetScene             &scene_,
                         const PeriodicBlockTemperature &temperature_,
                         const SeasonalForcing          &forcing_,
                         const double                    alpha_,
                         const RatchetControls          &controls)
      : scene(scene_)
      , temperature(temperature_)
      , forcing(forcing_)
      , alpha(alpha_)
      , ctrl(controls)
  {
    require_in_range(alpha >= 0.,
                     "Ratchet/Thermal expansion coefficient",
                     alpha,
                     ">= 0 1/K");
    require_in_range(ctrl.steps_per_cycle >= 4,
                     "Ratchet/Steps per cycle",
                     ctrl.steps_per_cycle,
                     ">= 4");
    dda::Controls c;
    c.dynamic        = 0.;
    c.max_iterations = 30;
    // A wedge contact that cycles more than the engine's default 12 times
    // in a static step settles once held by the slip bound (after 8
    // changes); 24 lets it. With 12 the 5 cm crack stopped in cycle 1
    // ("the open-close iteration cycles", step cut below the minimum).
    c.cycle_limit = 24;
    c.law.normal_penalty
      = ctrl.penalty > 0.
          ? ctrl.penalty
          : dda::automatic_penalty(scene.blocks, scene.blocks.gravity.norm());
    pseudo_time_step   = ctrl.pseudo_time_step > 0.
                           ? ctrl.pseudo_time_step
                           : quasi_static_time_step(scene, c.law.normal_penalty);
    c.time_step        = pseudo_time_step;
    c.solver.threads   = ctrl.threads;
    c.cut_exact_cycles = ctrl.cut_exact_cycles;
    next_jump     = std::max(1u, std::min(ctrl.jump_max, 2 * ctrl.jump_window));
    engine        = std::make_unique<dda::DdaSystem>(scene.blocks, c);
    heat_map      = scene.heat_map;
    double height = 0.;
    for (const int b : scene.block_slices)
      {
        const auto &p = engine->system().blocks[b].polygon;
        block_area += p.area();
        height = std::max(height, (p.vertices[3] - p.vertices[0]).norm());
      }
    tolerance = ctrl.equilibrium_tolerance * height;
    // Settle under gravity at the temperatures of phase 0.
    engine->set_eigenstrains(thermal_eigenstrains(
      engine->system(), heat_map, temperature, forcing, alpha, 0.));
    engine->settle(ctrl.settle_steps);
    aperture0     = raw_aperture();
    base_corners0 = vertex(scene.heel) + vertex(scene.toe);
    if (scene.infill >= 0)
      {
        fragments     = {scene.infill};
        fragment_tops = {scene.infill_top - engine->system().origin[1]};
      }
  }



  const geometry::Point &
  RatchetRun::vertex(const std::pair<int, int> &v) const
  {
    return engine->system().blocks[v.first].polygon.vertices[v.second];
  }



  double
  RatchetRun::quasi_static_time_step(const RatchetScene &scene,
                                     const double        penalty)
  {
    // The static step's inertia term 2 M / dt^2 of the heaviest block that
    // moves is 1e-9 of the contact penalty: a negligible regularisation
    // (the quasi-static limit). With 1 s (1e-7 of the penalty for Block 1)
    // the inertia changed which contacts slide on the way to each
    // equilibrium, and the slip of a narrow crack by 30 %. Scale-free: dt
    // grows with the block's size as sqrt(M / p).
    double mass = 0.;
    for (const int b : scene.block_slices)
      {
        const auto &block = scene.blocks.blocks[b];
        mass              = std::max(mass,
                        scene.blocks.materials[block.material].density
                          * block.polygon.area());
      }
    return std::sqrt(2. * mass / (1e-9 * penalty));
  }



  double
  RatchetRun::face_x(const std::pair<int, int> &a,
                     const std::pair<int, int> &b,
                     const double               y) const
  {
    const geometry::Point &p = vertex(a), &q = vertex(b);
    return p[0] + (y - p[1]) / (q[1] - p[1]) * (q[0] - p[0]);
  }



  void
  RatchetRun::supply(const double time)
  {
    if (!(scene.supply_distance > 0.) || fragments.empty())
      return;
    const auto &system = engine->system();
    if (fragment_tops.back()
          - system.blocks[fragments.back()].polygon.bounding_box()[3]
        < scene.supply_distance)
      return;
    // The infill's initial heights in engine coordinates (the engine works
    // relative to its origin).
    const double                 ya = scene.infill_top - system.origin[1];
    const double                 yz = scene.infill_bottom - system.origin[1];
    std::vector<geometry::Point> v;
    for (const double y : {yz, ya})
      {
        const double left  = face_x(scene.cliff_foot, scene.cliff_top, y);
        const double right = face_x(scene.heel, scene.back_top, y);
        const double gap   = 1e-3 * (right - left);
        v.emplace_back(left + gap, y);
        v.emplace_back(right - gap, y);
      }
    dda::Block b       = system.blocks[scene.infill];
    b.id               = static_cast<int>(system.blocks.size());
    b.polygon.vertices = {v[0], v[1], v[3], v[2]};
    for (auto &p : b.polygon.vertices)
      p += system.origin;
    // At the air's temperature, as the infill (BlockHeatMap index -1).
    b.eigenstrain
      = dda::thermal_eigenstrain(system.materials[b.material],
                                 alpha * (forcing.air(time) - forcing.mean));
    const int i = engine->add_block(b);
    heat_map.index.push_back(-1);
    heat_map.pieces.emplace_back();
    fragments.push_back(i);
    fragment_tops.push_back(ya);
  }



  double
  RatchetRun::displacement() const
  {
    // The mean of the displacements of the base's two corners: the slip
    // on the bedding plane, free of the block's own expansion (symmetric
    // about the mid-base point) and of its rotation.
    return 0.5
           * (vertex(scene.heel) + vertex(scene.toe) - base_corners0)
               .dot(scene.downslope);
  }



  double
  RatchetRun::raw_aperture() const
  {
    const auto &s = engine->system();
    return vertex(scene.back_top)[0]
           - s.blocks[scene.cliff_slices.front()].polygon.vertices[2][0];
  }



  double
  RatchetRun::aperture() const
  {
    return raw_aperture() - aperture0;
  }



  double
  RatchetRun::infill_descent() const
  {
    return scene.infill >= 0 ? -engine->centroid_displacement(scene.infill)[1]
                             : 0.;
  }



  void
  RatchetRun::equilibrate(const double time, CycleRecord &record)
  {
    engine->set_eigenstrains(thermal_eigenstrains(
      engine->system(), heat_map, temperature, forcing, alpha, time));
    double last = 0.;
    // The window of the stationarity test: slip and aperture per step.
    constexpr unsigned int            window = 100;
    std::deque<std::array<double, 2>> recent;
    // A bounded limit cycle (a light fragment that rocks between the crack's
    // faces, flipping its contacts every few tens of static steps): the
    // means of the slip and the aperture over two successive windows of
    // cycle_window steps agree within the tolerance, and the cycle's
    // amplitude is at most cycle_amplitude tolerances. The sample is then in
    // equilibrium within that amplitude (1e-7 of the block height: 1.5 um
    // for Block 1, under 1 % of a ratchet cycle), recorded as chatter.
    constexpr unsigned int cycle_window    = 200;
    constexpr double       cycle_amplitude = 10.;
    // Largest spread and mean of component i over recent[lo, hi).
    const auto spread_of = [&recent](const std::size_t lo,
                                     const std::size_t hi,
                                     const std::size_t i) {
      double a = 1e300, b = -1e300, sum = 0.;
      for (std::size_t j = lo; j < hi; ++j)
        {
          a = std::min(a, recent[j][i]);
          b = std::max(b, recent[j][i]);
          sum += recent[j][i];
        }
      return std::array<double, 2>{{b - a, sum / (hi - lo)}};
    };
    double moved = 0.;
    for (unsigned int k = 0; k < ctrl.max_steps_per_sample; ++k)
      {
        const dda::StepReport r = engine->step();
        ++record.steps;
        record.cuts += r.cuts;
        last = r.max_displacement;
        if (r.max_displacement <= tolerance && r.cuts == 0)
          return;
        // Steps cut on the way count too: the test is on the slip and the
        // aperture that the ratchet measures.
        moved = std::max(moved, r.max_displacement);
        recent.push_back({{displacement(), aperture()}});
        if (recent.size() > 2 * cycle_window)
          recent.pop_front();
        const std::size_t n = recent.size();
        if (n < window)
          continue;
        double spread = 0.;
        for (const std::size_t i : {std::size_t(0), std::size_t(1)})
          spread = std::max(spread, spread_of(n - window, n, i)[0]);
        if (spread <= tolerance)
          {
            ++record.stationary_samples;
            record.chatter = std::max(record.chatter, moved);
            return;
          }
        if (n < 2 * cycle_window)
          continue;
        double amplitude = 0., drift = 0.;
        for (const std::size_t i : {std::size_t(0), std::size_t(1)})
          {
            const auto first  = spread_of(0, cycle_window, i);
            const auto second = spread_of(cycle_window, n, i);
            amplitude         = std::max({amplitude, first[0], second[0]});
            drift             = std::max(drift, std::abs(second[1] - first[1]));
          }
        if (drift <= tolerance && amplitude <= cycle_amplitude * tolerance)
          {
            ++record.stationary_samples;
            record.chatter = std::max({record.chatter, moved, amplitude});
            return;
          }
      }
    // Diagnosis: over the last steps, did the slip and the aperture drift
    // (something slides away or creeps at its friction limit) or cycle
    // without drift (contact states that flip between steps)?
    std::string       diagnosis;
    const std::size_t n = recent.size();
    if (n >= 2)
      {
        const std::size_t half      = n / 2;
        double            amplitude = 0., drift = 0.;
        for (const std::size_t i : {std::size_t(0), std::size_t(1)})
          {
            const auto first  = spread_of(0, half, i);
            const auto second = spread_of(half, n, i);
            amplitude         = std::max({amplitude, first[0], second[0]});
            drift             = std::max(drift, std::abs(second[1] - first[1]));
          }
        const double slip_change = recent.back()[0] - recent.front()[0];
        diagnosis
          = "; over the last " + std::to_string(n)
            + " steps the base slip changed by "
            + io::format_number(slip_change, 3)
            + " m, the means of slip and aperture over their two halves by "
            + io::format_number(drift, 3) + " m, with an amplitude of "
            + io::format_number(amplitude, 3) + " m: "
            + (drift > tolerance
                 ? "the scene still moves (a block or the infill slides "
                   "or creeps at its friction limit; check the friction, "
                   "the slope and the infill's position, or raise 'Max "
                   "steps per sample')"
                 : "contact states cycle between steps without drift "
                   "(raise 'Equilibrium tolerance', or try another "
                   "'Pseudo time step')");
      }
    throw dda::DdaFailure(
      "cycle " + std::to_string(n_cycles + 1)
      + ": the scene did not reach equilibrium within "
      + std::to_string(ctrl.max_steps_per_sample)
      + " static steps at t = " + io::format_number(time / forcing.period, 6)
      + " periods (the last step moved a vertex by "
      + io::format_number(last, 3) + " m, the tolerance is "
      + io::format_number(tolerance, 3) + " m)" + diagnosis);
  }



  CycleRecord
  RatchetRun::run_cycle(std::vector<SampleRecord> *samples)
  {
    CycleRecord r;
    r.cycle = n_cycles + 1;
    if (samples != nullptr)
      samples->clear();
    for (unsigned int k = 1; k <= ctrl.steps_per_cycle; ++k)
      {
        const double phase = static_cast<double>(k) / ctrl.steps_per_cycle;
        const double time  = (n_cycles + phase) * forcing.period;
        equilibrate(time, r);
        if (samples != nullptr)
          {
            SampleRecord s;
            s.phase     = phase;
            s.air       = forcing.air(time);
            double mean = 0.;
            for (const int b : scene.block_slices)
              mean += engine->system().blocks[b].polygon.area()
                      * heat_map.temperature(b, temperature, forcing, time);
            s.block_mean   = mean / block_area;
            s.displacement = displacement();
            s.aperture     = aperture();
            samples->push_back(s);
          }
      }
    ++n_cycles;
    r.displacement                = displacement();
    r.permanent                   = r.displacement - last_displacement;
    last_displacement             = r.displacement;
    r.aperture                    = aperture();
    r.infill_descent              = infill_descent();
    const std::size_t n_fragments = fragments.size();
    supply(n_cycles * forcing.period);
    r.fragments = static_cast<unsigned int>(fragments.size());
    // The window of the next jump (a supplied fragment starts a new one).
    if (fragments.size() != n_fragments)
      history.clear();
    else
      {
        std::vector<geometry::Point> c;
        for (std::size_t b = 0; b < engine->system().blocks.size(); ++b)
          c.push_back(
            dda::block_moments(engine->system().blocks[b].polygon).centroid);
        history.push_back(std::move(c));
        if (history.size() > ctrl.jump_window + 1)
          history.pop_front();
      }
    const dda::EnergyLedger energy = engine->energy();
    r.stored_energy = energy.strain + energy.contact + energy.fixed;
    for (const auto &c : engine->contacts())
      {
        if (c.state == dda::ContactState::open)
          ++r.n_open;
        else if (c.state == dda::ContactState::sliding)
          ++r.n_sliding;
        else
          ++r.n_locked;
      }
    return r;
  }



  std::array<double, 2>
  RatchetRun::window_slip() const
  {
    const auto         &system = engine->system();
    std::vector<double> per_cycle;
    for (std::size_t k = 1; k < history.size(); ++k)
      {
        double slip = 0., area = 0.;
        for (const int b : scene.block_slices)
          {
            const double a = system.blocks[b].polygon.area();
            slip
              += a * (history[k][b] - history[k - 1][b]).dot(scene.downslope);
            area += a;
          }
        per_cycle.push_back(slip / area);
      }
    const double n    = static_cast<double>(per_cycle.size());
    double       mean = 0., var = 0.;
    for (const double v : per_cycle)
      mean += v / n;
    for (const double v : per_cycle)
      var += (v - mean) * (v - mean) / std::max(1., n - 1.);
    return {{mean, std::sqrt(var / n)}};
  }



  JumpRecord
  RatchetRun::jump(const unsigned int cycles)
  {
    JumpRecord j;
    j.displacement_before = j.displacement_after = displacement();
    j.aperture_before = j.aperture_after = aperture();
    j.descent_before = j.descent_after = infill_descent();
    if (cycles == 0 || ctrl.jump_max == 0 || ctrl.jump_window == 0
        || cycles_in_window() < ctrl.jump_window)
      return j;
    const auto       &system = engine->system();
    const std::size_t n      = system.blocks.size();
    const double      window = static_cast<double>(history.size() - 1);
    // Mean motion of block b per cycle over the window.
    const auto rate = [&](const std::size_t b) -> geometry::Point {
      return (history.back()[b] - history.front()[b]) / window;
    };
    const auto   window_mean = window_slip();
    const double slip        = window_mean[0];
    unsigned int m           = std::min(cycles, next_jump);
    // With a supply rule, stop short of the newest fragment's supply.
    if (scene.supply_distance > 0. && !fragments.empty())
      {
        const double descent = -rate(fragments.back())[1];
        const double left
          = scene.supply_distance
            - (fragment_tops.back()
               - system.blocks[fragments.back()].polygon.bounding_box()[3]);
        if (descent > 0.)
          m = static_cast<unsigned int>(
            std::min<double>(m, std::max(0., std::floor(left / descent))));
      }
    if (m == 0)
      return j;

    // The shifts of a jump of k cycles, and the smallest fraction of its
    // drift that a fragment got and the largest sideways offset.
    std::vector<geometry::Point> shift;
    const auto                   place = [&](const unsigned int k) {
      // The block's slices together, along the bedding plane.
      shift.assign(n, geometry::Point::Zero());
      for (const int b : scene.block_slices)
        shift[b] = static_cast<double>(k) * slip * scene.downslope;
      j.infill_fraction = 1.;
      j.infill_offset   = 0.;
      // Each fragment, oldest first, as far along its drift as it goes
      // without a vertex deeper in a neighbour than the deepest one it has
      // once the block moved. Where its path would press it into one face,
      // a sideways offset (normal to the path, up to four times the excess
      // depth: the estimate's error, not the motion) that maximises its
      // smallest gap is added: it sits between the faces as it did.
      for (const int f : fragments)
        {
          const geometry::Point full = static_cast<double>(k) * rate(f);
          const double          length = full.norm();
          if (!(length > 0.))
            continue;
          const geometry::Point side(-full[1] / length, full[0] / length);
          const auto            box = system.blocks[f].polygon.bounding_box();
          const double size = std::hypot(box[2] - box[0], box[3] - box[1]);
          const double reach = 1e-3 * size;
          const double deepest = std::min(0., engine->min_gap(f, shift, reach));
          const auto   gap = [&](const double a, const double b) {
            shift[f] = a * full + b * side;
            return std::min(engine->min_gap(f, shift, reach), 1e300);
          };
          // The offset with the largest smallest gap at fraction a: the
          // smallest gap is the lower of the two faces' (one rising, one
          // falling with the offset), so a golden-section search finds it.
          const auto best_offset = [&](const double a) {
            const double straight = gap(a, 0.);
            if (straight >= deepest)
              return 0.;
            constexpr double golden = 0.6180339887498949;
            const double     range = 4. * (deepest - straight);
            double           lo = -range, hi = range;
            for (int it = 0; it < 60; ++it)
              {
                const double b1 = hi - golden * (hi - lo);
                const double b2 = lo + golden * (hi - lo);
                if (gap(a, b1) < gap(a, b2))
                  lo = b1;
                else
                  hi = b2;
              }
            return 0.5 * (lo + hi);
          };
          const auto fits
            = [&](const double a) { return gap(a, best_offset(a)) >= deepest; };
          double lo = 0., hi = 1.;
          if (fits(1.))
            lo = 1.;
          else
            for (int it = 0; it < 40; ++it)
              {
                const double mid      = 0.5 * (lo + hi);
                (fits(mid) ? lo : hi) = mid;
              }
          const double b    = best_offset(lo);
          shift[f]          = lo * full + b * side;
          j.infill_fraction = std::min(j.infill_fraction, lo);
          j.infill_offset = std::max(j.infill_offset, std::abs(b) / length);
        }
    };
    place(m);
    // A fragment that cannot follow its drift (the wedge reaches the
    // crack's bottom) ends the jump where it stops: the block's slip
    // follows the wedge's descent, so the rest is simulated.
    if (j.infill_fraction < 0.99 && m > 1)
      {
        m = std::max(
          1u, static_cast<unsigned int>(std::floor(j.infill_fraction * m)));
        place(m);
      }
    pending_state.clear(); // the saved state holds no earlier one
    pending_state  = checkpoint();
    pending_cycles = m;
    pending_slip   = slip;
    pending_error  = window_mean[1];
    engine->translate_blocks(shift);
    n_cycles += m;
    j.cycles             = m;
    j.displacement_after = displacement();
    last_displacement    = j.displacement_after;
    j.aperture_after     = aperture();
    j.descent_after      = infill_descent();
    history.clear();
    return j;
  }



  bool
  RatchetRun::review_jump(double *change)
  {
    if (pending_state.empty() || cycles_in_window() < ctrl.jump_window)
      return false;
    // The change beyond what the two windows' scatter explains (two
    // standard errors of the difference of their means), relative.
    const auto   w     = window_slip();
    const double noise = 2. * std::hypot(w[1], pending_error);
    const double c
      = std::max(0., std::abs(w[0] - pending_slip) - noise)
        / std::max({std::abs(pending_slip), std::abs(w[0]), tolerance});
    if (change != nullptr)
      *change = c;
    const unsigned int m = pending_cycles;
    if (c <= ctrl.jump_tolerance || m <= 1)
      {
        pending_state.clear();
        next_jump = c <= ctrl.jump_tolerance ? std::min(2 * m, ctrl.jump_max)
                                             : std::max(1u, m / 2);
        return false;
      }
    const std::string state = std::move(pending_state);
    restore(state, "cycle jump");
    next_jump = std::max(1u, m / 2);
    return true;
  }



  EpisodeRecord
  RatchetRun::run_episode(const seismic::Record &record,
                          const EpisodeControls &ec)
  {
    require_in_range(ec.time_step > 0. && std::isfinite(ec.time_step),
                     ec.time_step_key,
                     ec.time_step,
                     "> 0 s");
    require_in_range(ec.rest_time >= 0. && std::isfinite(ec.rest_time),
                     ec.rest_time_key,
                     ec.rest_time,
                     ">= 0 s");
    require_in_range(ec.contact_damping >= 0.
                       && std::isfinite(ec.contact_damping),
                     ec.contact_damping_key,
                     ec.contact_damping,
                     ">= 0");
    EpisodeRecord r;
    // A jump extrapolates thermal cycles only.
    history.clear();
    pending_state.clear();
    // The thermal time of the end of the last cycle: the eigenstrains stay
    // those set there (or at settling, before the first cycle).
    const double thermal_time = n_cycles * forcing.period;
    const double d0 = displacement(), a0 = aperture();
    const auto   top = [this]() {
      return fragments.empty() ? 0.
                                 : engine->system()
                                   .blocks[fragments.back()]
                                   .polygon.bounding_box()[3];
    };
    const double      top0        = top();
    const std::size_t n_fragments = fragments.size();

    // The dynamic steps under the record.
    dda::SeismicInput input;
    input.mode                 = dda::SeismicInput::Mode::inertial;
    input.record               = record;
    input.g                    = ec.g;
    input.direction            = engine->system().seismic.direction;
    const double        start  = engine->time();
    const double        end    = start + record.duration() + ec.rest_time;
    const unsigned long steps0 = engine->n_steps, cuts0 = engine->n_cuts;
    engine->set_time_step(ec.time_step);
    engine->set_dynamic(1.);
    // The joints' dashpots act in the dynamic steps only (the static steps
    // of the cycles are not damped by them in any case).
    const double damping_before = engine->controls().contact_damping;
    engine->set_contact_damping(ec.contact_damping,
                                engine->controls().contact_step_damping);
    engine->set_seismic_input(input, start);
    const dda::EnergyLedger e0 = engine->energy();
    try
      {
        while (engine->time() < end - 1e-3 * ec.time_step)
          {
            engine->run_until(std::min(end, engine->time() + ec.time_step));
            for (const int b : scene.block_slices)
              r.max_rotation
                = std::max(r.max_rotation,
                           std::abs(engine->system().blocks[b].rotation));
          }
      }
    catch (const dda::DdaFailure &x)
      {
        throw dda::DdaFailure("dynamic steps of an earthquake, "
                              + io::format_number(engine->time() - start, 4)
                              + " s into its record: " + x.what());
      }
    const dda::EnergyLedger e1 = engine->energy();
    r.energy_gain              = e1.balance() - e0.balance();
    r.energy_scale             = e1.scale();
    r.dynamic_steps            = engine->n_steps - steps0;
    r.dynamic_cuts             = engine->n_cuts - cuts0;
    r.dynamic_slip             = displacement() - d0;

    engine->set_contact_damping(damping_before,
                                engine->controls().contact_step_damping);
    // Back to static steps at the run's pseudo time step: the step grows
    // back from the dynamic one (static steps, the inertia term shrinking),
    // then the scene is brought to equilibrium as at a sample.
    engine->set_seismic_input(dda::SeismicInput(), engine->time());
    engine->set_dynamic(0.);
    engine->set_time_step(pseudo_time_step);
    CycleRecord back;
    try
      {
        for (unsigned int k = 0; engine->time_step() < pseudo_time_step; ++k)
          {
            if (k >= ctrl.max_steps_per_sample)
              throw dda::DdaFailure(
                "after an earthquake in cycle " + std::to_string(n_cycles)
                + ": the static step did not grow back to the pseudo time step "
                  "within "
                + std::to_string(ctrl.max_steps_per_sample) + " steps");
            const dda::StepReport s = engine->step();
            ++back.steps;
            back.cuts += s.cuts;
          }
        equilibrate(thermal_time, back);
      }
    catch (const dda::DdaFailure &x)
      {
        throw dda::DdaFailure("return to static steps after an earthquake: "
                              + std::string(x.what()));
      }
    r.static_steps = back.steps;
    r.static_cuts  = back.cuts;
    r.slip         = displacement() - d0;
    r.aperture     = aperture() - a0;
    if (n_fragments > 0)
      r.infill_descent = top0 - top();
    // The next cycle's permanent displacement is the thermal one alone.
    last_displacement = displacement();
    supply(thermal_time);
    r.fragments = static_cast<unsigned int>(fragments.size());
    return r;
  }



  std::string
  RatchetRun::checkpoint() const
  {
    io::BinaryWriter w;
    w.put_string("rockdda ratchet 2");
    w.put<std::uint32_t>(n_cycles);
    w.put(aperture0);
    w.put(last_displacement);
    w.put(base_corners0[0]);
    w.put(base_corners0[1]);
    w.put<std::uint32_t>(static_cast<std::uint32_t>(fragments.size()));
    for (std::size_t k = 0; k < fragments.size(); ++k)
      {
        w.put<std::int32_t>(fragments[k]);
        w.put(fragment_tops[k]);
      }
    w.put_string(engine->checkpoint());
    // The cycle jumps' state (version 2).
    w.put<std::uint32_t>(next_jump);
    w.put_string(pending_state);
    w.put<std::uint32_t>(pending_cycles);
    w.put(pending_slip);
    w.put(pending_error);
    w.put<std::uint32_t>(static_cast<std::uint32_t>(history.size()));
    for (const auto &c : history)
      {
        w.put<std::uint32_t>(static_cast<std::uint32_t>(c.size()));
        for (const auto &p : c)
          {
            w.put(p[0]);
            w.put(p[1]);
          }
      }
    return w.bytes;
  }



  void
  RatchetRun::restore(const std::string &bytes, const std::string &source)
  {
    io::BinaryReader  r(bytes, source);
    const std::string tag = r.get_string();
    if (tag == "rockdda ratchet")
      throw InputError(source
                       + ": a ratchet checkpoint of an older rockdda (without "
                         "the cycle-jump window); rerun without 'Resume'");
    if (tag != "rockdda ratchet 2")
      throw InputError(source + ": not a rockdda ratchet checkpoint");
    const auto          cycles = r.get<std::uint32_t>();
    const double        a0     = r.get<double>();
    const double        last   = r.get<double>();
    const double        cx     = r.get<double>();
    const double        cy     = r.get<double>();
    const auto          n      = r.get<std::uint32_t>();
    std::vector<int>    f;
    std::vector<double> tops;
    for (std::uint32_t k = 0; k < n && k < 1000000; ++k)
      {
        f.push_back(r.get<std::int32_t>());
        tops.push_back(r.get<double>());
      }
    engine->restore(r.get_string(), source);
    const std::size_t n_blocks    = engine->system().blocks.size();
    const auto        jump_length = r.get<std::uint32_t>();
    const std::string jump_state  = r.get_string();
    const auto        jump_cycles = r.get<std::uint32_t>();
    const double      jump_slip   = r.get<double>();
    const double      jump_error  = r.get<double>();
    std::deque<std::vector<geometry::Point>> window;
    const auto                               n_window = r.get<std::uint32_t>();
    if (n_window > ctrl.jump_window + 1)
      throw InputError(source + ": the checkpoint is damaged (jump window)");
    for (std::uint32_t k = 0; k < n_window; ++k)
      {
        const auto n_points = r.get<std::uint32_t>();
        if (n_points != n_blocks)
          throw InputError(source
                           + ": the checkpoint is damaged (jump window)");
        std::vector<geometry::Point> c;
        for (std::uint32_t i = 0; i < n_points; ++i)
          {
            const double x = r.get<double>();
            c.emplace_back(x, r.get<double>());
          }
        window.push_back(std::move(c));
      }
    for (const int b : f)
      if (b < 0 || static_cast<std::size_t>(b) >= n_blocks)
        throw InputError(source + ": the checkpoint is damaged (fragment "
                         + std::to_string(b) + ")");
    // The supplied fragments take the air's temperature, as the infill.
    heat_map = scene.heat_map;
    heat_map.index.resize(n_blocks, -1);
    heat_map.pieces.resize(n_blocks);
    fragments         = std::move(f);
    fragment_tops     = std::move(tops);
    history           = std::move(window);
    next_jump         = jump_length;
    pending_state     = jump_state;
    pending_cycles    = jump_cycles;
    pending_slip      = jump_slip;
    pending_error     = jump_error;
    n_cycles          = cycles;
    aperture0         = a0;
    last_displacement = last;
    base_corners0     = geometry::Point(cx, cy);
  }
} // namespace rockdda::coupling
