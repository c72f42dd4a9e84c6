/**
 * @file
 * DDA snapshots in HDF5 with XDMF indices, for scenes too large for VTU:
 * binary arrays instead of base64 XML, and one index per series that
 * ParaView opens as one time series (XDMF reader).
 *
 * Each snapshot is one file `snapshot-NNNNN.h5` (written atomically) with
 * the groups `/blocks` and `/contacts`, each holding
 * - `points` (float64, P x 3, m; global coordinates, z = 0),
 * - `topology` (int64): blocks, XDMF mixed polygons, per cell the type 3,
 *   its number of points and their indices; contacts, C x 2 point indices,
 * - `offsets` (int64, one per cell: end of its points, as in VTU),
 * - one dataset per cell field of Snapshot (int32 or float64, N or N x k),
 * and the root attribute `time` (s). The XDMF indices `blocks.xdmf` and
 * `contacts.xdmf` list the snapshots as temporal collections; a 6-component
 * field (stress) is an XDMF "Matrix" attribute in the order XX YY ZZ XY YZ
 * XZ.
 *
 * Under MPI the snapshot is written collectively (MPI-IO, collective
 * transfers): each rank passes the cells it owns and writes them as
 * hyperslabs of the same datasets, after the cells of the lower ranks
 * (offsets from an exclusive scan of the counts), so the file has the same
 * layout as one written by one process; point indices in `topology` and
 * `offsets` are global. A serial write is the one-rank case.
 */
#ifndef ROCKDDA_DDA_HDF5_OUTPUT_H
#define ROCKDDA_DDA_HDF5_OUTPUT_H

#include <rockdda/dda/block_system.h>
#include <rockdda/dda/snapshot.h>
#include <rockdda/io/output.h>

#include <cstdint>
#include <mpi.h>
#include <string>
#include <utility>
#include <vector>

namespace rockdda::dda
{
  /// What one group of a snapshot file holds over all ranks: its numbers
  /// of cells and points, and which fields are integer (in field order).
  struct SnapshotLayout
  {
    std::uint64_t     cells = 0, points = 0;
    std::vector<bool> integer;
  };

  /**
   * Write @p blocks and @p contacts at @p time into the HDF5 file @p path,
   * atomically (a temporary file in the same folder, renamed by rank 0 once
   * every rank has closed it). Collective over @p comm: each rank passes
   * the cells it owns (possibly none; the same fields on every rank, else
   * every rank throws); the file holds the cells of rank 0, then rank 1,
   * ... Returns the layouts of /blocks and /contacts. Without MPI
   * initialised, @p comm must be MPI_COMM_SELF. Throws std::runtime_error
   * naming the file.
   */
  std::pair<SnapshotLayout, SnapshotLayout>
  write_snapshot_hdf5(const std::string &path,
                      const double       time,
                      const Snapshot    &blocks,
                      const Snapshot    &contacts,
                      const MPI_Comm     comm = MPI_COMM_SELF);

  /// Read group @p group ("blocks" or "contacts") of a snapshot file
  /// written by write_snapshot_hdf5() (description and default fields are
  /// not stored); throws std::runtime_error naming the file.
  Snapshot
  read_snapshot_hdf5(const std::string &path, const std::string &group);

  /// The time (s) stored in a snapshot file.
  double
  read_snapshot_time(const std::string &path);

  /**
   * One dataset of a serial HDF5 series file (write_series_hdf5()):
   * float64 values, row-major, of rows x @p components (1: a 1-D dataset
   * of rows), with its SI unit ("-" if none).
   */
  struct SeriesDataset
  {
    std::string         name, unit;
    std::size_t         components = 1;
    std::vector<double> values;
  };

  /**
   * Write @p datasets into a new HDF5 file @p path (serial), at its root in
   * the order given, each with the string attribute `unit`. Not atomic by
   * itself: call it through io::OutputDirectory::write_with(). Throws
   * std::runtime_error naming the file.
   */
  void
  write_series_hdf5(const std::string                &path,
                    const std::vector<SeriesDataset> &datasets);

  /// The datasets of a file written by write_series_hdf5(), in order;
  /// throws std::runtime_error naming the file.
  std::vector<SeriesDataset>
  read_series_hdf5(const std::string &path);

  /**
   * Write @p table atomically as the HDF5 file @p name of @p output
   * (statistics.h5 beside statistics.csv): one 1-D float64 dataset per
   * column, in the CSV's order, named by the column's name without its
   * unit (`time`, `kinetic_energy`, `mp1_uy`) and carrying the unit
   * attribute (`s`, `J/m`, `m`; the CSV header is name_unit).
   */
  void
  write_table_hdf5(const io::OutputDirectory &output,
                   const std::string         &name,
                   const io::Table           &table);

  /// The table of a file written by write_table_hdf5() (its csv() is
  /// the CSV of the table written); throws std::runtime_error naming the
  /// file.
  io::Table
  read_table_hdf5(const std::string &path);

  /**
   * The datasets of measurement_points.h5 (the time series of the
   * measurement points of a 2D run) from the rows of @p table (statistics
   * of a DDA run: column 0 the time, s; from column @p first_column five
   * columns per point: ux, uy in m, sigma_x, sigma_y, tau_xy in Pa) and
   * the measurement points of @p system: `time` (rows), `ux`, `uy`,
   * `sigma_x`, `sigma_y`, `tau_xy` (rows x points), `initial_position`
   * (points x 2, m, in the block file's coordinates: local + origin).
   */
  std::vector<SeriesDataset>
  measurement_point_series(const io::Table   &table,
                           const std::size_t  first_column,
                           const BlockSystem &system);

  /**
   * A series of HDF5 snapshots and its two XDMF indices in an output
   * folder. Each write() adds one file and rewrites both indices. With a
   * communicator of several ranks the snapshots are written collectively
   * (write_snapshot_hdf5()) and the indices by the ranks whose @p output is
   * enabled (rank 0); on one rank a disabled @p output writes nothing.
   */
  class Hdf5Series
  {
  public:
    explicit Hdf5Series(const io::OutputDirectory &output,
                        const MPI_Comm             comm = MPI_COMM_SELF);

    /// Write the next snapshot (collective over the series' communicator:
    /// each rank passes the cells it owns); returns its file name.
    std::string
    write(const double time, const Snapshot &blocks, const Snapshot &contacts);

    /// Continue a series written earlier (a resumed run): (time, file name)
    /// of each snapshot; the sizes are read from the files.
    void
    restore(const std::vector<std::pair<double, std::string>> &files);

    /// (time, file name) of each snapshot written.
    const std::vector<std::pair<double, std::string>> &
    files() const
    {
      return entries;
    }

  private:
    /// The XDMF <Grid> of each snapshot, for blocks and contacts.
    void
    add_grids(const double                                     time,
              const std::string                               &file,
              const Snapshot                                  &blocks,
              const Snapshot                                  &contacts,
              const std::pair<SnapshotLayout, SnapshotLayout> &layouts);
    void
    write_indices() const;

    const io::OutputDirectory                  &output;
    const MPI_Comm                              comm;
    std::vector<std::pair<double, std::string>> entries;
    std::vector<std::string>                    block_grids, contact_grids;
  };
} // namespace rockdda::dda

#endif
