/**
 * @file
 * Analysis types "sliding3d" (the thesis's 3D single-face and wedge sliding,
 * Chapter 4.2) and "yield" (pseudo-static yield acceleration and its
 * inversion), driven by the "Sliding 3d" and "Yield" sections.
 */
#include <rockdda/analytical/analyses.h>
#include <rockdda/analytical/sliding3d.h>
#include <rockdda/analytical/yield.h>
#include <rockdda/io/error.h>
#include <rockdda/io/parameters.h>
#include <rockdda/io/progress.h>
#include <rockdda/io/time_expression.h>
#include <rockdda/seismic/ground_motion.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>

namespace rockdda::analytical
{
  namespace
  {
    using dealii::Patterns::Double;

    /// Declare the "Sliding 3d" section shared by sliding3d and yield.
    void
    declare_geometry(dealii::ParameterHandler &prm)
    {
      declare_friction_parameters(prm);
      if (prm.subsection_path_exists({"Sliding 3d"}))
        return;
      prm.enter_subsection("Sliding 3d");
      io::declare(prm,
                  "Failure geometry",
                  "plane",
                  dealii::Patterns::Selection("plane|wedge"),
                  "-",
                  "'plane': a block on Plane 1; 'wedge': a block on Planes 1 "
                  "and 2. Either way the active mode (rest, single-face on "
                  "either plane, wedge, lifted off) is found every step, not "
                  "assumed.");
      for (const std::string plane : {"Plane 1", "Plane 2"})
        {
          prm.enter_subsection(plane);
          io::declare(prm,
                      "Dip",
                      plane == "Plane 1" ? "20" : "50",
                      Double(0., 90.),
                      "deg",
                      "Dip of the plane, 0 <= dip <= 90.");
          io::declare(prm,
                      "Dip direction",
                      plane == "Plane 1" ? "90" : "180",
                      Double(0., 360.),
                      "deg",
                      "Dip direction, clockwise from north, 0 to 360.");
          io::declare(prm,
                      "Friction angle",
                      "30",
                      io::DoubleInterval::right_open(0., 90.),
                      "deg",
                      "Friction angle of the plane, 0 <= phi < 90.");
          prm.leave_subsection();
        }
      io::declare(prm,
                  "Resultant source",
                  "expression",
                  dealii::Patterns::Selection("expression|ground motion"),
                  "-",
                  "'expression': r(t) from 'Resultant acceleration'; 'ground "
                  "motion': r = [a(t) sin(az), a(t) cos(az), -1] g with a(t) "
                  "from the Ground motion section and az = 'Ground motion "
                  "azimuth'.");
      io::declare(prm,
                  "Resultant acceleration",
                  "0.5*sin(10*t); 0; -1",
                  dealii::Patterns::Anything(),
                  "g",
                  "Resultant acceleration acting on the block, gravity "
                  "included: three expressions of t (s) for x (east), y "
                  "(north), z (up), separated by ';'. Example: thesis Fig. "
                  "4-2A is '0.5*sin(10*t); 0; -1'.");
      io::declare(prm,
                  "Ground motion azimuth",
                  "90",
                  Double(0., 360.),
                  "deg",
                  "Horizontal direction (clockwise from north) of the "
                  "inertial acceleration of the Ground motion record.");
      io::declare(prm,
                  "Time step",
                  "0.001",
                  io::DoubleInterval::positive(),
                  "s",
                  "Integration time step; > 0. The error is O(dt) at "
                  "stick-slip transitions (see benchmarks/sliding-block).");
      io::declare(prm,
                  "Duration",
                  "6.283185307179586",
                  io::DoubleInterval::positive(),
                  "s",
                  "End time of the analysis; > 0.");
      io::declare(prm,
                  "Output interval",
                  "0",
                  Double(0.),
                  "s",
                  "Spacing of rows in statistics.csv; 0 writes every step.");
      prm.leave_subsection();
    }

    /// Read the planes of the "Sliding 3d" section.
    void
    parse_geometry(dealii::ParameterHandler &prm,
                   const std::string        &prm_file,
                   Sliding3dOptions         &options)
    {
      prm.enter_subsection("Sliding 3d");
      options.wedge = prm.get("Failure geometry") == "wedge";
      std::array<double, 2> phi{};
      for (unsigned int k = 0; k < 2; ++k)
        {
          const std::string name = k == 0 ? "Plane 1" : "Plane 2";
          SlidingPlane     &p    = k == 0 ? options.plane1 : options.plane2;
          prm.enter_subsection(name);
          p.dip_deg           = prm.get_double("Dip");
          p.dip_direction_deg = prm.get_double("Dip direction");
          phi[k]              = prm.get_double("Friction angle");
          prm.leave_subsection();
          io::require(p.dip_deg >= 0. && p.dip_deg <= 90.,
                      prm_file,
                      "Sliding 3d/" + name + "/Dip",
                      p.dip_deg,
                      "0 <= dip <= 90 deg");
          io::require(p.dip_direction_deg >= 0. && p.dip_direction_deg <= 360.,
                      prm_file,
                      "Sliding 3d/" + name + "/Dip direction",
                      p.dip_direction_deg,
                      "0 <= dip direction <= 360 deg");
        }
      prm.leave_subsection();
      options.plane1.friction = parse_friction(
        prm, prm_file, phi[0], "Sliding 3d/Plane 1/Friction angle");
      options.plane2.friction = parse_friction(
        prm, prm_file, phi[1], "Sliding 3d/Plane 2/Friction angle");
    }

    /// The "sliding3d" analysis.
    class Sliding3dAnalysis : public io::Analysis
    {
    public:
      std::string
      name() const override
      {
        return "sliding3d";
      }

      std::string
      description() const override
      {
        return "3D rigid-block sliding on a plane or a wedge under a "
               "3-component acceleration (thesis Chapter 4)";
      }

      void
      declare_parameters(dealii::ParameterHandler &prm) const override
      {
        declare_geometry(prm);
      }

      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &prm_file) override
      {
        parse_geometry(prm, prm_file, options);
        prm.enter_subsection("Sliding 3d");
        options.time_step       = prm.get_double("Time step");
        options.duration        = prm.get_double("Duration");
        options.output_interval = prm.get_double("Output interval");
        const bool from_record = prm.get("Resultant source") == "ground motion";
        const double      azimuth = prm.get_double("Ground motion azimuth");
        const std::string expr    = prm.get("Resultant acceleration");
        prm.leave_subsection();
        io::with_parameter_file(prm_file, [&]() { validate(options); });

        if (from_record)
          {
            motion.parse_parameters(prm, prm_file);
            if (motion.polarity == seismic::GroundMotionInput::Polarity::both)
              throw InputError(prm_file
                               + ": key 'Ground motion/Polarity' = both is not "
                                 "supported by sliding3d; valid: normal or "
                                 "inverted");
            const double sign
              = motion.polarity
                    == seismic::GroundMotionInput::Polarity::inverted
                  ? -1.
                  : 1.;
            const double          sx = sign * std::sin(azimuth * M_PI / 180.);
            const double          sy = sign * std::cos(azimuth * M_PI / 180.);
            const seismic::Record record = motion.record;
            resultant                    = [record, sx, sy](const double t) {
              const double a = record.at(t);
              return Eigen::Vector3d(a * sx, a * sy, -1.);
            };
            input_text = motion.description + ", azimuth "
                         + std::to_string(azimuth) + " deg";
          }
        else
          {
            resultant
              = io::parse_time_expressions(expr,
                                           prm_file,
                                           "Sliding 3d/Resultant acceleration",
                                           "0.5*sin(10*t); 0; -1");
            input_text = "r(t) = [" + expr + "] g";
          }
      }

      void
      run(io::RunContext &context) override
      {
        context.log.line("resultant acceleration: " + input_text);
        io::ProgressBar       progress("sliding3d", options.duration);
        const Sliding3dResult r = slide_3d(resultant, options);
        progress.finish();

        io::Table table;
        table.add_column("time", "s");
        for (const char *c : {"x", "y", "z"})
          table.add_column(std::string("displacement_") + c, "m");
        for (const char *c : {"x", "y", "z"})
          table.add_column(std::string("velocity_") + c, "m/s");
        table.add_column("mode", "-");
        for (std::size_t i = 0; i < r.time.size(); ++i)
          table.add_row({r.time[i],
                         r.displacement[i][0],
                         r.displacement[i][1],
                         r.displacement[i][2],
                         r.velocity[i][0],
                         r.velocity[i][1],
                         r.velocity[i][2],
                         static_cast<double>(r.mode[i])});
        context.output.write("statistics.csv", table.csv());

        const Eigen::Vector3d d = r.final_displacement;
        context.summary.add("final_displacement", d.norm(), "m");
        context.summary.add("final_displacement_x", d[0], "m");
        context.summary.add("final_displacement_y", d[1], "m");
        context.summary.add("final_displacement_z", d[2], "m");
        const double trend
          = std::fmod(std::atan2(d[0], d[1]) * 180. / M_PI + 360., 360.);
        const double plunge
          = d.norm() > 0. ? -std::asin(d[2] / d.norm()) * 180. / M_PI : 0.;
        context.summary.add("displacement_trend", trend, "deg");
        context.summary.add("displacement_plunge", plunge, "deg");
        context.summary.add("max_speed", r.max_speed, "m/s");
        context.summary.add("mode_changes", r.n_mode_changes, "-");
        context.summary.add_text("final_mode", to_string(r.final_mode));
        context.summary.add("steps", r.n_steps, "-");
        context.log.line("mode column of statistics.csv: 0 rest, 1 plane 1, "
                         "2 plane 2, 3 wedge, 4 lifted off");
      }

    private:
      Sliding3dOptions                             options;
      seismic::GroundMotionInput                   motion;
      std::function<Eigen::Vector3d(const double)> resultant;
      std::string                                  input_text;
    };



    /// The "yield" analysis.
    class YieldAnalysis : public io::Analysis
    {
    public:
      std::string
      name() const override
      {
        return "yield";
      }

      std::string
      description() const override
      {
        return "pseudo-static yield acceleration of a plane or wedge block, "
               "and the friction angle that makes a given acceleration "
               "critical";
      }

      void
      declare_parameters(dealii::ParameterHandler &prm) const override
      {
        declare_geometry(prm);
        prm.enter_subsection("Yield");
        io::declare(prm,
                    "Cohesion",
                    "0",
                    Double(0.),
                    "Pa",
                    "Cohesion of Plane 1 (plane geometry only).");
        io::declare(prm,
                    "Contact area",
                    "1",
                    Double(0.),
                    "m^2",
                    "Contact area of the block on Plane 1 (with cohesion).");
        io::declare(prm,
                    "Block weight",
                    "1",
                    io::DoubleInterval::positive(),
                    "N",
                    "Weight of the block (with cohesion). Must be > 0.");
        io::declare(prm,
                    "Load azimuth",
                    "-1",
                    Double(-1., 360.),
                    "deg",
                    "Horizontal direction of the inertial load (wedge), "
                    "clockwise from north; -1 takes the trend of the "
                    "intersection line (plane: always the dip direction).");
        io::declare(prm,
                    "Critical acceleration",
                    "0",
                    Double(0.),
                    "g",
                    "If > 0, also find the friction angle that makes this "
                    "horizontal acceleration critical (back-analysis).");
        prm.leave_subsection();
      }

      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &prm_file) override
      {
        parse_geometry(prm, prm_file, options);
        prm.enter_subsection("Yield");
        cohesion = prm.get_double("Cohesion");
        area     = prm.get_double("Contact area");
        weight   = prm.get_double("Block weight");
        azimuth  = prm.get_double("Load azimuth");
        critical = prm.get_double("Critical acceleration");
        prm.leave_subsection();
        io::require(
          weight > 0., prm_file, "Yield/Block weight", weight, "weight > 0 N");
        options.time_step = options.duration = 1.;
        io::with_parameter_file(prm_file, [&]() { validate(options); });
        if (options.wedge && azimuth < 0.)
          {
            const Eigen::Vector3d i
              = plane_normal(options.plane1.dip_deg,
                             options.plane1.dip_direction_deg)
                  .cross(plane_normal(options.plane2.dip_deg,
                                      options.plane2.dip_direction_deg));
            azimuth
              = std::fmod(std::atan2(i[0], i[1]) * 180. / M_PI + 360., 360.);
            // The downward-plunging sense of the intersection line.
            if (i[2] > 0.)
              azimuth = std::fmod(azimuth + 180., 360.);
          }
      }

      void
      run(io::RunContext &context) override
      {
        const double phi1
          = std::atan(options.plane1.friction.mu0) * 180. / M_PI;
        double ky = 0., phi_critical = 0.;
        if (!options.wedge)
          {
            ky = plane_yield_acceleration(
              options.plane1.dip_deg, phi1, cohesion, area, weight);
            if (critical > 0.)
              phi_critical = critical_friction_angle_plane(
                options.plane1.dip_deg, critical, cohesion, area, weight);
          }
        else
          {
            ky = wedge_yield_acceleration(options.plane1,
                                          options.plane2,
                                          azimuth);
            if (critical > 0.)
              phi_critical = critical_friction_angle_wedge(
                options.plane1.dip_deg,
                options.plane1.dip_direction_deg,
                options.plane2.dip_deg,
                options.plane2.dip_direction_deg,
                azimuth,
                critical);
            context.summary.add("load_azimuth", azimuth, "deg");
          }
        context.summary.add("yield_acceleration", ky, "g");
        io::Table table;
        table.add_column("yield_acceleration", "g");
        if (critical > 0.)
          {
            context.summary.add("critical_friction_angle", phi_critical, "deg");
            table.add_column("critical_acceleration", "g");
            table.add_column("critical_friction_angle", "deg");
            table.add_row({ky, critical, phi_critical});
          }
        else
          table.add_row({ky});
        context.output.write("statistics.csv", table.csv());
      }

    private:
      Sliding3dOptions options;
      double           cohesion = 0., area = 1., weight = 1., azimuth = -1.,
             critical = 0.;
    };
  } // namespace



  std::unique_ptr<io::Analysis>
  internal::make_sliding3d_analysis()
  {
    return std::make_unique<Sliding3dAnalysis>();
  }



  std::unique_ptr<io::Analysis>
  internal::make_yield_analysis()
  {
    return std::make_unique<YieldAnalysis>();
  }
} // namespace rockdda::analytical
