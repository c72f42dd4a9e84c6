#include <rockdda/analytical/stiff_ode.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <cmath>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <utility>

namespace rockdda::analytical
{
  struct StiffOdeSolver::Impl
  {
    RightHandSide       rhs;
    Jacobian            jacobian;
    std::size_t         n          = 0;
    SUNContext          context    = nullptr;
    void               *cvode_mem  = nullptr;
    N_Vector            y          = nullptr;
    N_Vector            y_out      = nullptr;
    SUNMatrix           matrix     = nullptr;
    SUNLinearSolver     linsol     = nullptr;
    double              t_output   = 0.; // last output time
    double              t_internal = 0.; // time CVODE has integrated to
    std::vector<double> y_buffer, ydot_buffer, jacobian_buffer, output;
    /// Called after every internal step (may be empty).
    StepObserver observer;
    /// Event functions (may be empty) and their number.
    RootFunctions       roots;
    std::size_t         n_roots = 0;
    std::vector<double> root_buffer;
    /// The solution handed to the observer.
    std::vector<double> observed;
    /// An exception thrown by a user callback, re-thrown from advance().
    std::exception_ptr pending;
    /// The last message CVODE sent to its error handler.
    std::string last_message;
    /// Number of callback evaluations that produced non-finite values.
    long n_nonfinite = 0;

    /// Throw std::invalid_argument naming @p method if @p t_out is not
    /// finite or lies before the last output time.
    void
    check_output_time(const char *method, const double t_out) const
    {
      if (std::isfinite(t_out) && t_out >= t_output)
        return;
      std::ostringstream message;
      message << "StiffOdeSolver::" << method << ": output time " << t_out
              << " s is before the current time " << t_output << " s";
      throw std::invalid_argument(message.str());
    }

    ~Impl()
    {
      if (cvode_mem != nullptr)
        CVodeFree(&cvode_mem);
      if (linsol != nullptr)
        SUNLinSolFree(linsol);
      if (matrix != nullptr)
        SUNMatDestroy(matrix);
      if (y_out != nullptr)
        N_VDestroy(y_out);
      if (y != nullptr)
        N_VDestroy(y);
      if (context != nullptr)
        SUNContext_Free(&context);
    }

    /// Throw OdeError if @p flag is a CVODE error.
    void
    check(const int flag, const std::string &call) const
    {
      if (flag >= 0)
        return;
      std::string name = "flag " + std::to_string(flag);
      if (char *s = CVodeGetReturnFlagName(flag))
        {
          name = s;
          std::free(s);
        }
      std::ostringstream message;
      message << "CVODE: " << call << " failed with " << name
              << " at t = " << t_internal << " s";
      if (!last_message.empty())
        message << " (" << last_message << ")";
      if (n_nonfinite > 0)
        message << "; the right-hand side or Jacobian returned non-finite "
                   "values "
                << n_nonfinite << " time(s)";
      throw OdeError(message.str());
    }

    /// Throw OdeError if the CVODE vector @p v holds a non-finite value.
    void
    check_finite(const N_Vector v, const double t) const
    {
      const double *data = N_VGetArrayPointer(v);
      for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(data[i]))
          {
            std::ostringstream message;
            message << "CVODE: the solution component " << i
                    << " became non-finite (" << data[i] << ") at t = " << t
                    << " s";
            throw OdeError(message.str());
          }
    }

    static int
    rhs_callback(realtype t, N_Vector y, N_Vector ydot, void *user_data)
    {
      Impl *self = static_cast<Impl *>(user_data);
      try
        {
          const double *in = N_VGetArrayPointer(y);
          for (std::size_t i = 0; i < self->n; ++i)
            {
              if (!std::isfinite(in[i]))
                {
                  ++self->n_nonfinite;
                  return 1; // recoverable: CVODE reduces the step
                }
              self->y_buffer[i] = in[i];
            }
          std::fill(self->ydot_buffer.begin(), self->ydot_buffer.end(), 0.);
          self->rhs(t, self->y_buffer, self->ydot_buffer);
          double *out = N_VGetArrayPointer(ydot);
          for (std::size_t i = 0; i < self->n; ++i)
            {
              if (!std::isfinite(self->ydot_buffer[i]))
                {
                  ++self->n_nonfinite;
                  return 1;
                }
              out[i] = self->ydot_buffer[i];
            }
          return 0;
        }
      catch (...)
        {
          self->pending = std::current_exception();
          return -1; // unrecoverable
        }
    }

    static int
    jacobian_callback(realtype t,
                      N_Vector y,
                      N_Vector /*fy*/,
                      SUNMatrix jac,
                      void     *user_data,
                      N_Vector /*tmp1*/,
                      N_Vector /*tmp2*/,
                      N_Vector /*tmp3*/)
    {
      Impl *self = static_cast<Impl *>(user_data);
      try
        {
          const double *in = N_VGetArrayPointer(y);
          for (std::size_t i = 0; i < self->n; ++i)
            self->y_buffer[i] = in[i];
          std::fill(self->jacobian_buffer.begin(),
                    self->jacobian_buffer.end(),
                    0.);
          self->jacobian(t, self->y_buffer, self->jacobian_buffer);
          for (std::size_t i = 0; i < self->n; ++i)
            for (std::size_t j = 0; j < self->n; ++j)
              {
                const double value = self->jacobian_buffer[i * self->n + j];
                if (!std::isfinite(value))
                  {
                    ++self->n_nonfinite;
                    return 1;
                  }
                SM_ELEMENT_D(jac, i, j) = value;
              }
          return 0;
        }
      catch (...)
        {
          self->pending = std::current_exception();
          return -1;
        }
    }

    static int
    root_callback(realtype t, N_Vector y, realtype *gout, void *user_data)
    {
      Impl *self = static_cast<Impl *>(user_data);
      try
        {
          const double *in = N_VGetArrayPointer(y);
          for (std::size_t i = 0; i < self->n; ++i)
            self->y_buffer[i] = in[i];
          std::fill(self->root_buffer.begin(), self->root_buffer.end(), 0.);
          self->roots(t, self->y_buffer, self->root_buffer);
          for (std::size_t i = 0; i < self->n_roots; ++i)
            {
              if (!std::isfinite(self->root_buffer[i]))
                throw OdeError("CVODE: event function " + std::to_string(i)
                               + " returned a non-finite value at t = "
                               + std::to_string(t) + " s");
              gout[i] = self->root_buffer[i];
            }
          return 0;
        }
      catch (...)
        {
          self->pending = std::current_exception();
          return -1;
        }
    }

    /**
     * Take internal steps until t_out; if @p stop_at_roots, return true at
     * the first root (output = the solution there). Otherwise roots are
     * stepped over.
     */
    bool
    step_to(const double t_out, const bool stop_at_roots)
    {
      while (t_internal < t_out)
        {
          double    t_return = t_internal;
          const int flag = CVode(cvode_mem, t_out, y, &t_return, CV_ONE_STEP);
          rethrow_pending();
          check(flag, "CVode");
          check_finite(y, t_return);
          if (flag == CV_ROOT_RETURN)
            {
              // y is the solution at the root t_return; CVODE's internal
              // time is the end of the step, from which it continues.
              realtype t_current = t_return;
              check(CVodeGetCurrentTime(cvode_mem, &t_current),
                    "CVodeGetCurrentTime");
              t_internal = t_current;
              if (stop_at_roots && t_return <= t_out)
                {
                  const double *data = N_VGetArrayPointer(y);
                  output.assign(data, data + n);
                  t_output = t_return;
                  return true;
                }
              continue;
            }
          t_internal = t_return;
          if (observer)
            {
              const double *data = N_VGetArrayPointer(y);
              observed.assign(data, data + n);
              observer(t_return, observed);
            }
        }

      if (t_internal == t_out)
        N_VScale(1., y, y_out);
      else
        check(CVodeGetDky(cvode_mem, t_out, 0, y_out), "CVodeGetDky");
      check_finite(y_out, t_out);
      const double *data = N_VGetArrayPointer(y_out);
      output.assign(data, data + n);
      t_output = t_out;
      return false;
    }

    static void
    error_handler(int /*error_code*/,
                  const char * /*module*/,
                  const char *function,
                  char       *msg,
                  void       *user_data)
    {
      Impl *self         = static_cast<Impl *>(user_data);
      self->last_message = std::string(function ? function : "") + ": "
                           + std::string(msg ? msg : "");
    }

    /// Re-throw a pending callback exception, if any.
    void
    rethrow_pending()
    {
      if (pending)
        {
          std::exception_ptr p = pending;
          pending              = nullptr;
          std::rethrow_exception(p);
        }
    }
  };



  StiffOdeSolver::StiffOdeSolver(RightHandSide              rhs,
                                 const std::vector<double> &y0,
                                 const double               t0,
                                 const StiffOdeSettings    &settings,
                                 Jacobian                   jacobian)
      : impl(std::make_unique<Impl>())
  {
    if (!rhs)
      throw std::invalid_argument("StiffOdeSolver: empty right-hand side");
    if (y0.empty())
      throw std::invalid_argument("StiffOdeSolver: empty initial state");
    for (const double v : y0)
      if (!std::isfinite(v))
        throw std::invalid_argument("StiffOdeSolver: non-finite initial state");
    if (!std::isfinite(t0))
      throw std::invalid_argument("StiffOdeSolver: non-finite initial time");
    if (!(settings.relative_tolerance > 0.))
      throw std::invalid_argument(
        "StiffOdeSolver: relative_tolerance must be > 0");
    if (settings.absolute_tolerances.empty()
        && !(settings.absolute_tolerance > 0.))
      throw std::invalid_argument(
        "StiffOdeSolver: absolute_tolerance must be > 0");
    if (!settings.absolute_tolerances.empty())
      {
        if (settings.absolute_tolerances.size() != y0.size())
          throw std::invalid_argument(
            "StiffOdeSolver: absolute_tolerances must have one entry per "
            "component");
        for (const double a : settings.absolute_tolerances)
          if (!(a > 0.))
            throw std::invalid_argument(
              "StiffOdeSolver: absolute_tolerances must be > 0");
      }
    if (settings.max_order < 1 || settings.max_order > 5)
      throw std::invalid_argument(
        "StiffOdeSolver: max_order must be in 1..5 for BDF");

    Impl &d    = *impl;
    d.rhs      = std::move(rhs);
    d.jacobian = std::move(jacobian);
    d.n        = y0.size();
    d.y_buffer.assign(d.n, 0.);
    d.ydot_buffer.assign(d.n, 0.);
    d.jacobian_buffer.assign(d.n * d.n, 0.);
    d.output     = y0;
    d.t_output   = t0;
    d.t_internal = t0;

    if (SUNContext_Create(nullptr, &d.context) != 0 || d.context == nullptr)
      throw OdeError("CVODE: SUNContext_Create failed");
    const sunindextype n = static_cast<sunindextype>(d.n);
    d.y                  = N_VNew_Serial(n, d.context);
    d.y_out              = N_VNew_Serial(n, d.context);
    if (d.y == nullptr || d.y_out == nullptr)
      throw OdeError("CVODE: N_VNew_Serial failed");
    for (std::size_t i = 0; i < d.n; ++i)
      NV_Ith_S(d.y, i) = y0[i];

    d.cvode_mem = CVodeCreate(CV_BDF, d.context);
    if (d.cvode_mem == nullptr)
      throw OdeError("CVODE: CVodeCreate failed");
    d.check(CVodeSetErrHandlerFn(d.cvode_mem, &Impl::error_handler, &d),
            "CVodeSetErrHandlerFn");
    d.check(CVodeInit(d.cvode_mem, &Impl::rhs_callback, t0, d.y), "CVodeInit");
    d.check(CVodeSetUserData(d.cvode_mem, &d), "CVodeSetUserData");
    if (settings.absolute_tolerances.empty())
      d.check(CVodeSStolerances(d.cvode_mem,
                                settings.relative_tolerance,
                                settings.absolute_tolerance),
              "CVodeSStolerances");
    else
      {
        N_Vector atol = N_VNew_Serial(n, d.context);
        if (atol == nullptr)
          throw OdeError("CVODE: N_VNew_Serial failed");
        for (std::size_t i = 0; i < d.n; ++i)
          NV_Ith_S(atol, i) = settings.absolute_tolerances[i];
        const int flag = CVodeSVtolerances(d.cvode_mem,
                                           settings.relative_tolerance,
                                           atol); // CVODE copies atol
        N_VDestroy(atol);
        d.check(flag, "CVodeSVtolerances");
      }
    d.matrix = SUNDenseMatrix(n, n, d.context);
    if (d.matrix == nullptr)
      throw OdeError("CVODE: SUNDenseMatrix failed");
    d.linsol = SUNLinSol_Dense(d.y, d.matrix, d.context);
    if (d.linsol == nullptr)
      throw OdeError("CVODE: SUNLinSol_Dense failed");
    d.check(CVodeSetLinearSolver(d.cvode_mem, d.linsol, d.matrix),
            "CVodeSetLinearSolver");
    if (d.jacobian)
      d.check(CVodeSetJacFn(d.cvode_mem, &Impl::jacobian_callback),
              "CVodeSetJacFn");
    d.check(CVodeSetMaxOrd(d.cvode_mem, settings.max_order), "CVodeSetMaxOrd");
    d.check(CVodeSetMaxNumSteps(d.cvode_mem, settings.max_steps),
            "CVodeSetMaxNumSteps");
    if (settings.max_step > 0.)
      d.check(CVodeSetMaxStep(d.cvode_mem, settings.max_step),
              "CVodeSetMaxStep");
    if (settings.initial_step > 0.)
      d.check(CVodeSetInitStep(d.cvode_mem, settings.initial_step),
              "CVodeSetInitStep");
  }



  StiffOdeSolver::~StiffOdeSolver() = default;



  const std::vector<double> &
  StiffOdeSolver::advance(const double t_out)
  {
    Impl &d = *impl;
    d.check_output_time("advance", t_out);
    if (t_out == d.t_output)
      return d.output;
    d.step_to(t_out, false);
    return d.output;
  }



  bool
  StiffOdeSolver::advance_to_root(const double t_out)
  {
    Impl &d = *impl;
    d.check_output_time("advance_to_root", t_out);
    if (t_out == d.t_output)
      return false;
    if (d.t_internal > t_out)
      {
        // Already integrated past t_out (after a root return): interpolate.
        // A root in (t_output, t_out] would have been reported before.
        return d.step_to(t_out, true);
      }
    d.check(CVodeSetStopTime(d.cvode_mem, t_out), "CVodeSetStopTime");
    return d.step_to(t_out, true);
  }



  void
  StiffOdeSolver::set_root_functions(const unsigned int     n_roots,
                                     RootFunctions          g,
                                     const std::vector<int> directions)
  {
    Impl &d = *impl;
    if (n_roots > 0 && !g)
      throw std::invalid_argument(
        "StiffOdeSolver::set_root_functions: empty event functions");
    if (!directions.empty() && directions.size() != n_roots)
      throw std::invalid_argument(
        "StiffOdeSolver::set_root_functions: one direction per function");
    d.roots   = std::move(g);
    d.n_roots = n_roots;
    d.root_buffer.assign(n_roots, 0.);
    d.check(CVodeRootInit(d.cvode_mem,
                          static_cast<int>(n_roots),
                          n_roots > 0 ? &Impl::root_callback : nullptr),
            "CVodeRootInit");
    if (n_roots > 0)
      {
        std::vector<int> dirs = directions;
        if (dirs.empty())
          dirs.assign(n_roots, 0);
        d.check(CVodeSetRootDirection(d.cvode_mem, dirs.data()),
                "CVodeSetRootDirection");
        d.check(CVodeSetNoInactiveRootWarn(d.cvode_mem),
                "CVodeSetNoInactiveRootWarn");
      }
  }



  std::vector<int>
  StiffOdeSolver::roots_found() const
  {
    std::vector<int> info(impl->n_roots, 0);
    if (!info.empty())
      impl->check(CVodeGetRootInfo(impl->cvode_mem, info.data()),
                  "CVodeGetRootInfo");
    return info;
  }



  void
  StiffOdeSolver::set_step_observer(StepObserver observer)
  {
    impl->observer = std::move(observer);
  }



  void
  StiffOdeSolver::set_stop_time(const double t_stop)
  {
    impl->check(CVodeSetStopTime(impl->cvode_mem, t_stop), "CVodeSetStopTime");
  }



  void
  StiffOdeSolver::reinit(const double t0, const std::vector<double> &y0)
  {
    Impl &d = *impl;
    if (y0.size() != d.n)
      throw std::invalid_argument(
        "StiffOdeSolver::reinit: the state size cannot change");
    for (std::size_t i = 0; i < d.n; ++i)
      {
        if (!std::isfinite(y0[i]))
          throw std::invalid_argument(
            "StiffOdeSolver::reinit: non-finite state");
        NV_Ith_S(d.y, i) = y0[i];
      }
    d.check(CVodeReInit(d.cvode_mem, t0, d.y), "CVodeReInit");
    d.output      = y0;
    d.t_output    = t0;
    d.t_internal  = t0;
    d.n_nonfinite = 0;
    d.last_message.clear();
  }



  double
  StiffOdeSolver::time() const
  {
    return impl->t_output;
  }



  const std::vector<double> &
  StiffOdeSolver::state() const
  {
    return impl->output;
  }



  long
  StiffOdeSolver::n_steps() const
  {
    long steps = 0;
    impl->check(CVodeGetNumSteps(impl->cvode_mem, &steps), "CVodeGetNumSteps");
    return steps;
  }
} // namespace rockdda::analytical
