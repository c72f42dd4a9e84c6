#include <rockdda/analytical/sliding3d.h>
#include <rockdda/io/error.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace rockdda::analytical
{
  namespace
  {
    constexpr double degree = M_PI / 180.;

    /// Gap (m) below which a plane is taken as touching the block.
    constexpr double gap_tolerance = 1e-12;
    /// Normal velocity (m/s) above which a touching plane is separating.
    constexpr double separation_tolerance = 1e-12;
    /// Guard against endless event loops inside one step.
    constexpr unsigned int max_substeps = 64;

    std::string
    to_text(const double x)
    {
      std::ostringstream s;
      s.precision(12);
      s << x;
      return s.str();
    }

    /**
     * Smallest tau in (0, h] with u0 + p tau + q tau^2 <= 0, or -1 if there
     * is none. u0 >= 0 is the speed along the sliding direction at tau = 0.
     */
    double
    first_zero(const double u0, const double p, const double q, const double h)
    {
      if (u0 <= 0.)
        {
          // Starting from rest: u = tau (p + q tau).
          if (p > 0. || (p == 0. && q > 0.))
            {
              if (q < 0.)
                {
                  const double tau = -p / q;
                  if (tau <= h)
                    return tau;
                }
              return -1.;
            }
          // Degenerate: no acceleration along the slip direction. Stop at
          // the end of the (sub)step.
          return h;
        }
      if (u0 + p * h + q * h * h > 0.
          && !(q > 0. && p < 0. && -p / (2. * q) < h
               && u0 - p * p / (4. * q) <= 0.))
        return -1.;
      // A root exists in (0, h].
      if (std::abs(q) * h <= 1e-14 * (std::abs(p) + u0 / h))
        return std::min(h, -u0 / p);
      const double disc = std::max(0., p * p - 4. * q * u0);
      const double sq   = std::sqrt(disc);
      // Stable pair of roots.
      const double w   = (p >= 0.) ? -p - sq : -p + sq;
      double       t1  = w / (2. * q);
      double       t2  = (w != 0.) ? 2. * u0 / w : t1;
      double       tau = std::numeric_limits<double>::infinity();
      for (const double t : {t1, t2})
        if (t > 0. && t <= h * (1. + 1e-12))
          tau = std::min(tau, t);
      if (!std::isfinite(tau))
        return h;
      return std::min(tau, h);
    }

    /// The integrator: state and the event-driven step.
    class Integrator
    {
    public:
      Integrator(const std::function<Eigen::Vector3d(double)> &load,
                 const Sliding3dOptions                       &input)
          : resultant_g(load)
          , options(input)
          , geometry(input)
      {}

      /// Advance from @p t_a to @p t_b; returns the mode at the end.
      SlidingMode
      advance(double t_a, const double t_b);

      Eigen::Vector3d D       = Eigen::Vector3d::Zero();
      Eigen::Vector3d V       = Eigen::Vector3d::Zero();
      bool            at_rest = true;

    private:
      Eigen::Vector3d
      r(const double t) const
      {
        return options.g * resultant_g(t);
      }

      const FrictionLaw &
      law(const unsigned int i) const
      {
        return i == 0 ? options.plane1.friction : options.plane2.friction;
      }

      std::array<bool, 2>
      touching() const;

      bool
      stuck_at(const double t, const std::array<bool, 2> &touch) const;

      /// Sliding acceleration (Eq. 4.11) in @p mode with friction opposing
      /// the unit direction @p e, friction evaluated at @p speed.
      Eigen::Vector3d
      acceleration(const Eigen::Vector3d &r_t,
                   const SlidingMode      mode,
                   const Eigen::Vector3d &e,
                   const double           speed) const;

      /// Friction capacity mu1 N1 + mu2 N2 at @p speed.
      double
      capacity(const ContactForces &f, const double speed) const
      {
        double c = 0.;
        for (unsigned int i = 0; i < geometry.n_planes(); ++i)
          c += law(i).coefficient(speed) * f.normal[i];
        return c;
      }

      /// Perfectly inelastic, frictionless impact on touching planes the
      /// block moves into.
      void
      apply_impacts(const std::array<bool, 2> &touch);

      /// Put the displacement exactly on the planes of @p mode (+ @p extra).
      void
      close_gaps(const SlidingMode mode, const int extra = -1);

      const std::function<Eigen::Vector3d(double)> &resultant_g;
      const Sliding3dOptions                       &options;
      const ContactGeometry                         geometry;
    };



    std::array<bool, 2>
    Integrator::touching() const
    {
      std::array<bool, 2> touch = {{false, false}};
      for (unsigned int i = 0; i < geometry.n_planes(); ++i)
        touch[i] = D.dot(geometry.normal(i)) <= gap_tolerance
                   && V.dot(geometry.normal(i)) <= separation_tolerance;
      return touch;
    }



    bool
    Integrator::stuck_at(const double t, const std::array<bool, 2> &touch) const
    {
      const Eigen::Vector3d r_t  = r(t);
      const SlidingMode     mode = geometry.select_mode(r_t, touch);
      return holds_at_rest(geometry.forces(r_t, mode),
                           law(0).static_coefficient(),
                           law(1).static_coefficient());
    }



    Eigen::Vector3d
    Integrator::acceleration(const Eigen::Vector3d &r_t,
                             const SlidingMode      mode,
                             const Eigen::Vector3d &e,
                             const double           speed) const
    {
      const ContactForces f = geometry.forces(r_t, mode);
      if (mode == SlidingMode::lifted_off)
        return f.driving;
      // Eq. 4.5 / 4.10 (V != 0) and Eq. 4.11.
      return f.driving - capacity(f, speed) * e;
    }



    void
    Integrator::apply_impacts(const std::array<bool, 2> &touch)
    {
      const unsigned int  n = geometry.n_planes();
      std::array<bool, 2> closing{{false, false}};
      unsigned int        n_closing = 0;
      for (unsigned int i = 0; i < n; ++i)
        if (touch[i] && V.dot(geometry.normal(i)) < 0.)
          {
            closing[i] = true;
            ++n_closing;
          }
      if (n_closing == 0)
        return;
      if (n_closing == 2)
        {
          // Impulses P_i n_i that cancel both normal velocities.
          const Eigen::Vector3d &n1 = geometry.normal(0),
                                &n2 = geometry.normal(1);
          const double k = n1.dot(n2), v1 = V.dot(n1), v2 = V.dot(n2);
          const double det = 1. - k * k;
          const double p1 = (-v1 + k * v2) / det, p2 = (-v2 + k * v1) / det;
          if (p1 >= 0. && p2 >= 0.)
            {
              V = geometry.tangential(V, SlidingMode::wedge);
              return;
            }
          closing[p1 < 0. ? 0 : 1] = false;
        }
      const unsigned int i = closing[0] ? 0 : 1;
      V -= V.dot(geometry.normal(i)) * geometry.normal(i);
      // The impulse on plane i may drive the block into the other plane.
      const unsigned int j = 1 - i;
      if (j < n && touch[j] && V.dot(geometry.normal(j)) < 0.)
        V = geometry.tangential(V, SlidingMode::wedge);
    }



    void
    Integrator::close_gaps(const SlidingMode mode, const int extra)
    {
      const bool on0 = ContactGeometry::is_active(mode, 0) || extra == 0;
      const bool on1 = ContactGeometry::is_active(mode, 1) || extra == 1;
      if (on0 && on1 && geometry.n_planes() == 2)
        D = geometry.tangential(D, SlidingMode::wedge);
      else if (on0)
        D -= D.dot(geometry.normal(0)) * geometry.normal(0);
      else if (on1 && geometry.n_planes() == 2)
        D -= D.dot(geometry.normal(1)) * geometry.normal(1);
    }



    SlidingMode
    Integrator::advance(double t_a, const double t_b)
    {
      SlidingMode last = at_rest ? SlidingMode::rest : SlidingMode::lifted_off;
      for (unsigned int substep = 0; t_a < t_b && substep < max_substeps;
           ++substep)
        {
          const double h     = t_b - t_a;
          const auto   touch = touching();
          apply_impacts(touch);
          const Eigen::Vector3d r_a  = r(t_a);
          const SlidingMode     mode = geometry.select_mode(r_a, touch);
          V                          = geometry.tangential(V, mode);

          Eigen::Vector3d e     = Eigen::Vector3d::Zero();
          double          speed = V.norm();
          // An impact can remove all the velocity: the block is then at rest.
          if (!at_rest && mode != SlidingMode::lifted_off && speed == 0.)
            at_rest = true;
          if (mode == SlidingMode::lifted_off)
            at_rest = false;
          else if (at_rest)
            {
              const ContactForces f = geometry.forces(r_a, mode);
              if (holds_at_rest(f,
                                law(0).static_coefficient(),
                                law(1).static_coefficient()))
                {
                  last = SlidingMode::rest;
                  if (stuck_at(t_b, touch))
                    {
                      t_a = t_b;
                      break;
                    }
                  // Slip starts inside the step: bisect for the onset.
                  double lo = t_a, hi = t_b;
                  for (unsigned int k = 0; k < 200; ++k)
                    {
                      const double mid = 0.5 * (lo + hi);
                      if (mid <= lo || mid >= hi)
                        break;
                      (stuck_at(mid, touch) ? lo : hi) = mid;
                    }
                  t_a = hi;
                  continue;
                }
              // Eq. 4.4: slip from rest along the driving force.
              at_rest = false;
              V.setZero();
              speed = 0.;
              e     = f.driving.normalized();
            }
          else
            e = V / speed;

          // Eqs. 4.11-4.14 over [t_a, t_b]. At t_a the friction opposes the
          // velocity at the start of the step (Eq. 4.5); its magnitude is
          // evaluated at the speed at each end (predicted at t_b).
          const Eigen::Vector3d s_a        = acceleration(r_a, mode, e, speed);
          const double          speed_b    = (V + s_a * h).norm();
          const Eigen::Vector3d r_b        = r(t_b);
          auto                  substep_to = [&](const double tau) {
            const Eigen::Vector3d s_tau
              = acceleration(r(t_a + tau), mode, e, (V + s_a * tau).norm());
            const Eigen::Vector3d S = 0.5 * (s_a + s_tau); // Eq. 4.12
            D += V * tau + 0.5 * S * tau * tau; // Eq. 4.14
            V += S * tau;                       // Eq. 4.13
          };

          Eigen::Vector3d s_b = acceleration(r_b, mode, e, speed_b);
          if (mode != SlidingMode::lifted_off)
            {
              // Does the velocity along its previous direction vanish?
              const double tau = first_zero(speed,
                                            s_a.dot(e),
                                            (s_b - s_a).dot(e) / (2. * h),
                                            h);
              if (tau >= 0.)
                {
                  substep_to(tau);
                  V.setZero();
                  at_rest = true;
                  close_gaps(mode);
                  last = mode;
                  t_a += tau;
                  continue;
                }
              // No stop: at t_b the friction opposes the velocity at t_b,
              // which is then parallel to W = V + h/2 (s_a + m_b). This keeps
              // the direction of sliding stable at small speeds (an explicit
              // direction amplifies transverse round-off when |V| < mu N h).
              const ContactForces   f_b = geometry.forces(r_b, mode);
              const double          cap = capacity(f_b, speed_b);
              const Eigen::Vector3d W   = V + 0.5 * h * (s_a + f_b.driving);
              if (W.norm() > 0.5 * h * cap)
                s_b = f_b.driving - cap * W.normalized();
            }

          // Does the block reach a plane it does not slide on?
          const Eigen::Vector3d S_full  = 0.5 * (s_a + s_b);
          const Eigen::Vector3d D_b     = D + V * h + 0.5 * S_full * h * h;
          double                tau_hit = 2. * h;
          int                   hit     = -1;
          for (unsigned int i = 0; i < geometry.n_planes(); ++i)
            {
              if (ContactGeometry::is_active(mode, i))
                continue;
              const Eigen::Vector3d &n = geometry.normal(i);
              if (D_b.dot(n) >= 0.)
                continue;
              const double g0 = D.dot(n), vn = V.dot(n), an = s_a.dot(n),
                           jn = (s_b - s_a).dot(n) / h;
              auto gap        = [&](const double t) {
                return g0 + vn * t + 0.5 * an * t * t + 0.25 * jn * t * t * t;
              };
              double lo = 0., hi = h;
              if (g0 > 0.)
                for (unsigned int k = 0; k < 200; ++k)
                  {
                    const double mid = 0.5 * (lo + hi);
                    if (mid <= lo || mid >= hi)
                      break;
                    (gap(mid) >= 0. ? lo : hi) = mid;
                  }
              else
                hi = 0.;
              if (hi < tau_hit)
                {
                  tau_hit = hi;
                  hit     = static_cast<int>(i);
                }
            }
          if (hit >= 0 && tau_hit < h)
            {
              if (tau_hit > 0.)
                substep_to(tau_hit);
              close_gaps(mode, hit);
              last = mode;
              t_a += tau_hit;
              continue;
            }

          // The full (sub)step.
          D = D_b;
          V += S_full * h;
          close_gaps(mode, hit);
          last = mode;
          t_a  = t_b;
        }
      return at_rest ? SlidingMode::rest : last;
    }
  } // namespace



  const char *
  to_string(const SlidingMode mode)
  {
    switch (mode)
      {
        case SlidingMode::rest:
          return "rest";
        case SlidingMode::plane1:
          return "plane1";
        case SlidingMode::plane2:
          return "plane2";
        case SlidingMode::wedge:
          return "wedge";
        case SlidingMode::lifted_off:
          return "lifted_off";
      }
    return "unknown";
  }



  Eigen::Vector3d
  plane_normal(const double dip_deg, const double dip_direction_deg)
  {
    const double a = dip_deg * degree, b = dip_direction_deg * degree;
    // Eq. 4.1.
    return Eigen::Vector3d(std::sin(a) * std::sin(b),
                           std::sin(a) * std::cos(b),
                           std::cos(a));
  }



  void
  validate(const SlidingPlane &plane, const char *name)
  {
    const std::string n(name);
    if (!(plane.dip_deg >= 0. && plane.dip_deg <= 90.))
      throw InputError(n + " dip = " + to_text(plane.dip_deg)
                       + " deg is outside the valid range [0, 90] deg");
    if (!(plane.dip_direction_deg >= 0. && plane.dip_direction_deg <= 360.))
      throw InputError(n
                       + " dip direction = " + to_text(plane.dip_direction_deg)
                       + " deg is outside the valid range [0, 360] deg");
    const FrictionLaw &f = plane.friction;
    if (!(std::isfinite(f.mu0) && f.mu0 >= 0.))
      throw InputError(n + " friction coefficient mu0 = " + to_text(f.mu0)
                       + " is invalid: the friction angle must be in [0, 90)"
                         " deg (mu0 finite and >= 0)");
    if (f.type == FrictionLaw::Type::steady_state)
      {
        if (!std::isfinite(f.a_minus_b))
          throw InputError(n + " friction A - B = " + to_text(f.a_minus_b)
                           + " must be finite");
        if (!(f.v0 > 0. && std::isfinite(f.v0)))
          throw InputError(n + " friction reference velocity V0 = "
                           + to_text(f.v0) + " m/s must be > 0");
        if (!(f.v_cutoff > 0. && std::isfinite(f.v_cutoff)))
          throw InputError(n + " friction cutoff velocity = "
                           + to_text(f.v_cutoff) + " m/s must be > 0");
      }
  }



  void
  validate(const Sliding3dOptions &options)
  {
    validate(options.plane1, "plane 1");
    if (options.wedge)
      {
        validate(options.plane2, "plane 2");
        const Eigen::Vector3d n1
          = plane_normal(options.plane1.dip_deg,
                         options.plane1.dip_direction_deg);
        const Eigen::Vector3d n2
          = plane_normal(options.plane2.dip_deg,
                         options.plane2.dip_direction_deg);
        const double s = n1.cross(n2).norm();
        if (s < 1e-6)
          throw InputError(
            "wedge planes 1 and 2 are parallel or nearly parallel: |n1 x n2| = "
            + to_text(s) + " must be >= 1e-6 (the planes must intersect)");
      }
    if (!(options.time_step > 0. && std::isfinite(options.time_step)))
      throw InputError("time step = " + to_text(options.time_step)
                       + " s must be > 0");
    if (!(options.duration > 0. && std::isfinite(options.duration)))
      throw InputError("duration = " + to_text(options.duration)
                       + " s must be > 0");
    if (!(options.output_interval >= 0.
          && std::isfinite(options.output_interval)))
      throw InputError("output interval = " + to_text(options.output_interval)
                       + " s must be >= 0 (0 = every step)");
    if (!(options.g > 0. && std::isfinite(options.g)))
      throw InputError("gravitational acceleration g = " + to_text(options.g)
                       + " m/s^2 must be > 0");
  }



  ContactGeometry::ContactGeometry(const Sliding3dOptions &options)
      : n_planes_(options.wedge ? 2 : 1)
  {
    validate(options);
    normals[0]
      = plane_normal(options.plane1.dip_deg, options.plane1.dip_direction_deg);
    normals[1]
      = plane_normal(options.plane2.dip_deg, options.plane2.dip_direction_deg);
    unit_intersection = Eigen::Vector3d::Zero();
    if (n_planes_ == 2)
      {
        // Eq. 4.6, normalised.
        const Eigen::Vector3d c = normals[0].cross(normals[1]);
        sin_normals             = c.norm();
        unit_intersection       = c / sin_normals;
      }
  }



  bool
  ContactGeometry::is_active(const SlidingMode mode, const unsigned int i)
  {
    return mode == SlidingMode::wedge || (i == 0 && mode == SlidingMode::plane1)
           || (i == 1 && mode == SlidingMode::plane2);
  }



  SlidingMode
  ContactGeometry::select_mode(const Eigen::Vector3d     &r,
                               const std::array<bool, 2> &touching) const
  {
    const bool   t1 = touching[0], t2 = n_planes_ == 2 && touching[1];
    const double rn1 = r.dot(normals[0]), rn2 = r.dot(normals[1]);
    if (t1 && t2)
      {
        // r = a n1 + b n2 + c I: (r x n2).I = a |n1 x n2|,
        // (r x n1).I = -b |n1 x n2|.
        const double a
          = r.cross(normals[1]).dot(unit_intersection) / sin_normals;
        const double b
          = -r.cross(normals[0]).dot(unit_intersection) / sin_normals;
        if (a <= 0. && b <= 0.)
          return SlidingMode::wedge;
        if (b > 0. && rn1 <= 0.)
          return SlidingMode::plane1;
        if (a > 0. && rn2 <= 0.)
          return SlidingMode::plane2;
        return SlidingMode::lifted_off;
      }
    if (t1)
      return rn1 <= 0. ? SlidingMode::plane1 : SlidingMode::lifted_off;
    if (t2)
      return rn2 <= 0. ? SlidingMode::plane2 : SlidingMode::lifted_off;
    return SlidingMode::lifted_off;
  }



  ContactForces
  ContactGeometry::forces(const Eigen::Vector3d &r,
                          const SlidingMode      mode) const
  {
    ContactForces f;
    f.mode = mode;
    switch (mode)
      {
        case SlidingMode::plane1:
        case SlidingMode::plane2:
          {
            const unsigned int     i = mode == SlidingMode::plane1 ? 0 : 1;
            const Eigen::Vector3d &n = normals[i];
            // Eq. 4.3 (magnitude) and Eq. 4.2: (n x r) x n = r - (r.n) n.
            f.normal[i] = std::max(0., -r.dot(n));
            f.driving   = r - r.dot(n) * n;
            break;
          }
        case SlidingMode::wedge:
          {
            // Eqs. 4.8-4.9 divided by |n1 x n2| (true reactions) and Eq. 4.7.
            const Eigen::Vector3d &I = unit_intersection;
            f.normal[0]
              = std::max(0., -r.cross(normals[1]).dot(I) / sin_normals);
            f.normal[1]
              = std::max(0., r.cross(normals[0]).dot(I) / sin_normals);
            f.driving = r.dot(I) * I;
            break;
          }
        default:
          f.mode    = SlidingMode::lifted_off;
          f.driving = r;
      }
    return f;
  }



  Eigen::Vector3d
  ContactGeometry::tangential(const Eigen::Vector3d &x,
                              const SlidingMode      mode) const
  {
    switch (mode)
      {
        case SlidingMode::plane1:
          return x - x.dot(normals[0]) * normals[0];
        case SlidingMode::plane2:
          return x - x.dot(normals[1]) * normals[1];
        case SlidingMode::wedge:
          return x.dot(unit_intersection) * unit_intersection;
        default:
          return x;
      }
  }



  bool
  holds_at_rest(const ContactForces &forces, const double mu1, const double mu2)
  {
    if (forces.mode == SlidingMode::lifted_off)
      return false;
    return forces.driving.norm()
           <= mu1 * forces.normal[0] + mu2 * forces.normal[1];
  }



  bool
  is_stuck(const Sliding3dOptions &options, const Eigen::Vector3d &resultant_g)
  {
    const ContactGeometry geometry(options);
    const SlidingMode     mode
      = geometry.select_mode(resultant_g, {{true, options.wedge}});
    return holds_at_rest(geometry.forces(resultant_g, mode),
                         options.plane1.friction.static_coefficient(),
                         options.wedge
                           ? options.plane2.friction.static_coefficient()
                           : 0.);
  }



  Sliding3dResult
  slide_3d(const std::function<Eigen::Vector3d(double)> &resultant_g,
           const Sliding3dOptions                       &options)
  {
    validate(options);
    Integrator      integrator(resultant_g, options);
    Sliding3dResult result;

    auto record = [&](const double t, const SlidingMode mode) {
      result.time.push_back(t);
      result.displacement.push_back(integrator.D);
      result.velocity.push_back(integrator.V);
      result.mode.push_back(mode);
    };
    record(0., SlidingMode::rest);

    const double dt = options.time_step;
    const auto   n_steps
      = static_cast<unsigned long>(std::ceil(options.duration / dt - 1e-9));
    double      next_output = options.output_interval;
    SlidingMode previous    = SlidingMode::rest;
    for (unsigned long i = 1; i <= n_steps; ++i)
      {
        const double      t_a  = (i - 1) * dt;
        const double      t_b  = (i == n_steps) ? options.duration : i * dt;
        const SlidingMode mode = integrator.advance(t_a, t_b);
        if (mode != previous)
          ++result.n_mode_changes;
        previous          = mode;
        result.max_speed  = std::max(result.max_speed, integrator.V.norm());
        result.final_mode = mode;
        if (options.output_interval <= 0. || i == n_steps
            || t_b >= next_output - 1e-9 * dt)
          {
            record(t_b, mode);
            while (options.output_interval > 0.
                   && next_output <= t_b + 1e-9 * dt)
              next_output += options.output_interval;
          }
      }
    result.final_displacement = integrator.D;
    result.n_steps            = n_steps;
    return result;
  }
} // namespace rockdda::analytical
