/**
 * @file
 * A small RAII wrapper around the SUNDIALS CVODE integrator (BDF with Newton
 * iterations and a dense direct linear solver) for small stiff ODE systems
 * dy/dt = f(t, y). Used by the rate-and-state friction models; meant to be
 * reusable by any subsystem with a handful of stiff unknowns.
 *
 * Reference: Hindmarsh, A.C., Brown, P.N., Grant, K.E., Lee, S.L., Serban, R.,
 * Shumaker, D.E., Woodward, C.S. (2005). SUNDIALS: Suite of nonlinear and
 * differential/algebraic equation solvers. ACM Trans. Math. Softw. 31(3),
 * 363-396.
 */
#ifndef ROCKDDA_ANALYTICAL_STIFF_ODE_H
#define ROCKDDA_ANALYTICAL_STIFF_ODE_H

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace rockdda::analytical
{
  /**
   * Thrown when the ODE integrator fails: a CVODE error flag (the message
   * names the flag, e.g. CV_TOO_MUCH_WORK, and the time reached), a right-hand
   * side that keeps producing non-finite values, or a non-finite solution.
   */
  class OdeError : public std::runtime_error
  {
  public:
    explicit OdeError(const std::string &message)
        : std::runtime_error(message)
    {}
  };



  /**
   * Settings of the stiff integrator. The defaults are a tight general-purpose
   * choice; the callers set tolerances scaled to their unknowns.
   */
  struct StiffOdeSettings
  {
    /// Relative tolerance (-), > 0.
    double relative_tolerance = 1e-8;
    /// Absolute tolerance applied to every component (units of y), > 0.
    /// Ignored if absolute_tolerances is not empty.
    double absolute_tolerance = 1e-12;
    /// Per-component absolute tolerances (units of each y_i); empty = use
    /// absolute_tolerance for all components.
    std::vector<double> absolute_tolerances;
    /// Maximum BDF order, 1..5 (CVODE default 5).
    int max_order = 5;
    /// Maximum number of internal steps per call of advance().
    long max_steps = 500000;
    /// Largest internal step (s); 0 = unlimited.
    double max_step = 0.;
    /// First internal step (s); 0 = let CVODE estimate it.
    double initial_step = 0.;
  };



  /**
   * Integrates a small stiff system dy/dt = f(t, y) with CVODE: variable-order
   * (1..max_order) BDF, modified Newton iterations, dense direct linear
   * solver; the Jacobian is taken from the user if given, otherwise CVODE
   * builds it by difference quotients.
   *
   * The object owns the SUNContext, the CVODE memory, the vector, the matrix
   * and the linear solver and frees them in its destructor; it cannot be
   * copied. Every CVODE failure is turned into an OdeError naming the CVODE
   * flag. Exceptions thrown by the right-hand side are caught inside the
   * callback (they must not cross the C library) and re-thrown from advance().
   * If the right-hand side returns a non-finite component the step is rejected
   * as recoverable (CVODE retries with a smaller step) and, if that does not
   * help, an OdeError is thrown. After every internal step the solution is
   * checked to be finite; the solver never hands back NaN.
   */
  class StiffOdeSolver
  {
  public:
    /// Right-hand side: fill ydot (already sized) with f(t, y).
    using RightHandSide = std::function<void(const double               t,
                                             const std::vector<double> &y,
                                             std::vector<double>       &ydot)>;
    /// Jacobian df/dy, row-major: jacobian[i * n + j] = d f_i / d y_j
    /// (already sized n*n and zeroed).
    using Jacobian = std::function<void(const double               t,
                                        const std::vector<double> &y,
                                        std::vector<double>       &jacobian)>;

    /**
     * Set up the integrator for the initial value problem y(t0) = y0.
     * Throws std::invalid_argument for an empty y0, non-finite y0 or
     * non-positive tolerances, OdeError if CVODE cannot be set up.
     */
    StiffOdeSolver(RightHandSide              rhs,
                   const std::vector<double> &y0,
                   const double               t0,
                   const StiffOdeSettings    &settings = StiffOdeSettings(),
                   Jacobian                   jacobian = Jacobian());

    /// Frees all SUNDIALS objects.
    ~StiffOdeSolver();

    StiffOdeSolver(const StiffOdeSolver &) = delete;
    StiffOdeSolver &
    operator=(const StiffOdeSolver &)
      = delete;

    /**
     * Advance the solution to time @p t_out (> current time) and return y at
     * t_out. CVODE steps past t_out in one-step mode and interpolates, unless
     * a stop time is set (see set_stop_time()), which it never steps past.
     * Throws OdeError on failure.
     */
    const std::vector<double> &
    advance(const double t_out);

    /**
     * Forbid CVODE to step past @p t_stop (s), e.g. at a discontinuity of the
     * right-hand side. Cleared once reached.
     */
    void
    set_stop_time(const double t_stop);

    /// Restart from y(t0) = y0 (same system size), discarding the history.
    void
    reinit(const double t0, const std::vector<double> &y0);

    /// The current time (s): the last output time.
    double
    time() const;

    /// The solution at time().
    const std::vector<double> &
    state() const;

    /// Called after every internal CVODE step with its time (s) and
    /// solution.
    using StepObserver
      = std::function<void(const double t, const std::vector<double> &y)>;

    /**
     * Call @p observer after every internal step of advance() (e.g. to take
     * the maximum of a quantity over all steps, not only at output times);
     * an empty function removes it.
     */
    void
    set_step_observer(StepObserver observer);

    /// Number of internal CVODE steps taken since construction or reinit.
    long
    n_steps() const;

    /// Root (event) functions: fill g (already sized n_roots) with g_i(t, y).
    using RootFunctions = std::function<void(const double               t,
                                             const std::vector<double> &y,
                                             std::vector<double>       &g)>;

    /**
     * Locate the zeros of @p n_roots event functions g_i(t, y) during the
     * integration (CVodeRootInit: CVODE checks the signs of g_i at the end
     * of every internal step and locates a sign change by the Illinois
     * modified secant method, Hiebert and Shampine 1980). @p directions,
     * if not empty, has one entry per function: +1 reports only zeros where
     * g_i increases, -1 only where it decreases, 0 both. A g_i that is
     * exactly zero at the initial time (after construction or reinit()) is
     * ignored until it moves away from zero. The functions and directions
     * survive reinit(). Roots are only reported by advance_to_root();
     * advance() steps over them.
     */
    void
    set_root_functions(const unsigned int     n_roots,
                       RootFunctions          g,
                       const std::vector<int> directions = {});

    /**
     * Like advance(), but never steps past @p t_out (a stop time) and
     * returns early at the first zero of an event function: then time() is
     * the root (s), state() the solution there, and the return value is
     * true; otherwise it returns false with time() = t_out. See
     * roots_found() for which function vanished. Restart with reinit() at
     * the root to look for further roots: a second root within the same
     * internal step is not reported.
     */
    bool
    advance_to_root(const double t_out);

    /**
     * After advance_to_root() returned true: one entry per event function,
     * +1 if g_i vanished increasing, -1 decreasing, 0 if it did not vanish.
     */
    std::vector<int>
    roots_found() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl;
  };
} // namespace rockdda::analytical

#endif
