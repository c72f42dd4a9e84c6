/**
 * @file
 * The snapshots of a DDA run, written once for both engines: an HDF5
 * series (one file per snapshot holding blocks and contacts, with XDMF
 * indices) or VTU files of blocks and of contacts with their PVD indices.
 */
#ifndef ROCKDDA_DDA_SNAPSHOT_SERIES_H
#define ROCKDDA_DDA_SNAPSHOT_SERIES_H

#include <rockdda/dda/hdf5_output.h>
#include <rockdda/dda/run_loop.h>
#include <rockdda/dda/snapshot.h>

#include <functional>
#include <string>

namespace rockdda::dda
{
  /**
   * Writes a run's snapshots in its format and lists them in the run's
   * progress (RunProgress::block_files and contact_files, which the
   * checkpoint keeps). An HDF5 series continues after a resume
   * (resume()).
   */
  class SnapshotSeries
  {
  public:
    /// Snapshots in @p output, HDF5 if @p hdf5 (else VTU), listed in
    /// @p progress.
    SnapshotSeries(const io::OutputDirectory &output,
                   const bool                 hdf5,
                   RunProgress               &progress);

    /// The snapshot at @p time: the blocks and contacts as HDF5 cells or
    /// as VTU documents (only the pair of the series' format is called).
    void
    write(const double                        time,
          const std::function<Snapshot()>    &blocks_cells,
          const std::function<Snapshot()>    &contacts_cells,
          const std::function<std::string()> &blocks_vtu,
          const std::function<std::string()> &contacts_vtu);

    /// After a resume: continue the HDF5 series listed in the progress.
    void
    resume();

  private:
    const io::OutputDirectory &output;
    const bool                 hdf5;
    RunProgress               &progress;
    Hdf5Series                 series;
  };
} // namespace rockdda::dda

#endif
