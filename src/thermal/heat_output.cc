/**
 * @file
 * What either heat solver writes about itself (see heat_output.h): the VTU
 * piece of the field, instantiated for the serial and the Trilinos vector,
 * and the description of the time stepper.
 */
#include "heat_output.h"

#include <rockdda/io/output.h>

#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>

#include "heat_flux.h"
#include <ostream>
#include <sstream>

namespace rockdda::thermal::internal
{
  using namespace dealii;

  namespace
  {
    /// Write the VTU piece of @p field (see vtu_piece()) into @p out and,
    /// with @p piece_names, the PVTU record naming them into @p record.
    template <typename VectorType>
    void
    write_vtu(const HeatParameters           &prm,
              const DoFHandler<2>            &dof_handler,
              const VectorType               &field,
              const double                    t,
              const int                       rank,
              std::ostream                   &out,
              const std::vector<std::string> &piece_names = {},
              std::ostream                   *record      = nullptr)
    {
      const HeatFluxPostprocessor heat_flux(prm);
      DataOut<2>                  data_out;
      data_out.attach_dof_handler(dof_handler);
      data_out.add_data_vector(field, "temperature");
      data_out.add_data_vector(field, heat_flux);
      const auto   &tria = dof_handler.get_triangulation();
      Vector<float> block(tria.n_active_cells()),
        subdomain(tria.n_active_cells());
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            block[cell->active_cell_index()]     = cell->material_id();
            subdomain[cell->active_cell_index()] = rank;
          }
      data_out.add_data_vector(block, "block");
      if (rank >= 0)
        data_out.add_data_vector(subdomain, "rank");
      data_out.build_patches(dof_handler.get_fe().degree);
      // Binary, zlib-compressed when deal.II has zlib (write_vtu).
      DataOutBase::VtkFlags flags;
      flags.time              = t;
      flags.compression_level = DataOutBase::VtkFlags::best_speed;
      flags.physical_units    = {{"heat_flux", "W/m^2"}};
      data_out.set_flags(flags);
      data_out.write_vtu(out);
      if (record)
        data_out.write_pvtu_record(*record, piece_names);
    }
  } // namespace



  template <typename VectorType>
  std::string
  vtu_piece(const HeatParameters &prm,
            const DoFHandler<2>  &dof_handler,
            const VectorType     &field,
            const double          t,
            const int             rank)
  {
    std::ostringstream out;
    write_vtu(prm, dof_handler, field, t, rank, out);
    return out.str();
  }



  std::vector<std::pair<std::string, std::string>>
  pvtu_files(const HeatParameters                &prm,
             const DoFHandler<2>                 &dof_handler,
             const TrilinosWrappers::MPI::Vector &field,
             const double                         t,
             const std::string                   &name,
             const MPI_Comm                       comm)
  {
    const unsigned int       rank    = Utilities::MPI::this_mpi_process(comm);
    const unsigned int       n_ranks = Utilities::MPI::n_mpi_processes(comm);
    std::vector<std::string> names;
    for (unsigned int r = 0; r < n_ranks; ++r)
      names.push_back(name + "." + Utilities::int_to_string(r, 4) + ".vtu");
    std::ostringstream piece, record;
    write_vtu(prm,
              dof_handler,
              field,
              t,
              static_cast<int>(rank),
              piece,
              names,
              rank == 0 ? &record : nullptr);
    const std::vector<std::string> pieces
      = Utilities::MPI::gather(comm, piece.str(), 0);
    std::vector<std::pair<std::string, std::string>> files;
    if (rank == 0)
      {
        files.emplace_back(name + ".pvtu", record.str());
        for (unsigned int r = 0; r < pieces.size(); ++r)
          files.emplace_back(names[r], pieces[r]);
      }
    return files;
  }

  template std::string
  vtu_piece(const HeatParameters &,
            const DoFHandler<2> &,
            const Vector<double> &,
            const double,
            const int);
  template std::string
  vtu_piece(const HeatParameters &,
            const DoFHandler<2> &,
            const TrilinosWrappers::MPI::Vector &,
            const double,
            const int);



  std::string
  stepper_description(const HeatParameters &p)
  {
    std::string s;
    switch (p.stepper)
      {
        case TimeStepper::crank_nicolson:
          s = "Crank-Nicolson (theta = 1/2), dt = "
              + io::format_number(p.time_step, 6) + " s, "
              + std::to_string(p.rannacher_steps)
              + " backward-Euler start-up steps";
          break;
        case TimeStepper::backward_euler:
          s = "backward Euler (theta = 1), dt = "
              + io::format_number(p.time_step, 6) + " s";
          break;
        case TimeStepper::arkode:
          s = "SUNDIALS ARKODE (implicit DIRK, adaptive), rtol = "
              + io::format_number(p.arkode_relative_tolerance, 3) + ", atol = "
              + io::format_number(p.arkode_absolute_tolerance, 3) + " K";
          break;
      }
    return s + "; FE_Q(" + std::to_string(p.degree) + ")";
  }
} // namespace rockdda::thermal::internal
