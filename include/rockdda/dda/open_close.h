/**
 * @file
 * The open-close iteration's driver, written once for both DDA engines
 * (Shi 1988, ch. 4; doc/theory/dda.md, "Open-close iteration and time
 * stepping"): solve with the current contact states, check every contact,
 * repeat until no state and no friction force changes; stop with a
 * diagnosis when the states do not settle or a contact cycles.
 */
#ifndef ROCKDDA_DDA_OPEN_CLOSE_H
#define ROCKDDA_DDA_OPEN_CLOSE_H

#include <cstdint>
#include <cstring>
#include <string>
#include <utility>

namespace rockdda::dda
{
  /**
   * The limits of one attempt's open-close iteration: at most
   * @p max_iterations iterations that change a contact state, and as many
   * more that only update friction forces; a contact that changes state
   * @p cycle_limit times within the attempt cycles.
   */
  struct OpenCloseLimits
  {
    unsigned max_iterations = 12;
    unsigned cycle_limit    = 12;
  };

  /**
   * What the state check of one iteration found: the number of contacts
   * that changed state, of sliding contacts whose friction force has not
   * converged, the most state changes of one contact in this attempt, and
   * whether the states settled on an inexact solve that a solve to the
   * solver's tolerance must confirm.
   */
  struct OpenCloseCheck
  {
    unsigned state_changes    = 0;
    unsigned friction_changes = 0;
    unsigned most_changes     = 0;
    bool     confirm          = false;
  };

  /**
   * A 128-bit fingerprint of a sequence of words (two independent 64-bit
   * multiply-xorshift mixes): the open-close iteration's exact state (the
   * increments, each contact's state, anchor and forces, the escalated
   * tolerances), to recognise an iteration that has returned bit for bit
   * to an earlier iterate. The iteration is a deterministic map of that
   * state, so it then cycles for good and would be cut at the cycle limit
   * or the iteration limit anyway: the accepted steps are those of running
   * the cycle out.
   */
  class IterateFingerprint
  {
  public:
    void
    add(const std::uint64_t w)
    {
      a = (a ^ w) * 0x9e3779b97f4a7c15ull;
      a ^= a >> 32;
      b = (b + w) * 0xc2b2ae3d27d4eb4full;
      b ^= b >> 29;
    }
    void
    add(const double x)
    {
      std::uint64_t w;
      std::memcpy(&w, &x, sizeof w);
      add(w);
    }
    std::pair<std::uint64_t, std::uint64_t>
    value() const
    {
      return {a, b};
    }

  private:
    std::uint64_t a = 0xcbf29ce484222325ull;
    std::uint64_t b = 0x94d049bb133111ebull;
  };

  /**
   * Runs the open-close iteration of one attempt of a step. Each iteration
   * calls
   * - @p may_continue(iterations_so_far, why): false (with @p why) stops
   *   the attempt before the iteration (an iteration that returned to an
   *   earlier iterate cycles for good);
   * - @p solve(iteration, why): assembles with the current states and
   *   solves (1-based @p iteration); false (with @p why) fails the attempt;
   * - @p check(iteration): the state check of the solve (OpenCloseCheck),
   *   which updates the states;
   * and @p most_changed() names the contact that changed most often for
   * the diagnosis of a cycle. Returns true when an iteration changes no
   * state and no friction force (and needs no confirming solve), with the
   * number of @p iterations; otherwise false with the diagnosis in @p why:
   * a contact that changed state cycle_limit times, or the limits reached.
   */
  template <typename MayContinue,
            typename Solve,
            typename Check,
            typename MostChanged>
  bool
  run_open_close(const OpenCloseLimits &limits,
                 MayContinue          &&may_continue,
                 Solve                &&solve,
                 Check                &&check,
                 MostChanged          &&most_changed,
                 unsigned              &iterations,
                 std::string           &why)
  {
    unsigned       state_iterations = 0;
    OpenCloseCheck last;
    iterations = 0;
    while (state_iterations < limits.max_iterations
           && iterations < 2 * limits.max_iterations)
      {
        if (!may_continue(iterations, why))
          return false;
        ++iterations;
        if (!solve(iterations, why))
          return false;
        last = check(iterations);
        if (last.state_changes == 0 && last.friction_changes == 0)
          {
            if (last.confirm)
              continue;
            return true;
          }
        if (last.state_changes > 0)
          ++state_iterations;
        // A contact that keeps changing state (although held, where the
        // engine holds): the iteration cycles; a shorter step resolves the
        // contact.
        if (last.most_changes >= limits.cycle_limit)
          {
            why = "the open-close iteration cycles (" + most_changed() + ")";
            return false;
          }
      }
    why = "the open-close iteration did not converge in "
          + std::to_string(iterations) + " iterations ("
          + std::to_string(last.state_changes) + " contacts changing state, "
          + std::to_string(last.friction_changes)
          + " sliding contacts whose friction force has not converged)";
    return false;
  }
} // namespace rockdda::dda

#endif
