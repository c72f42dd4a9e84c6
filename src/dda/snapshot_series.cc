/**
 * @file
 * The snapshots of a DDA run (snapshot_series.h).
 */
#include <rockdda/dda/snapshot_series.h>
#include <rockdda/dda/vtu_output.h>

#include <cstdio>

namespace rockdda::dda
{
  SnapshotSeries::SnapshotSeries(const io::OutputDirectory &output,
                                 const bool                 hdf5,
                                 RunProgress               &progress)
      : output(output)
      , hdf5(hdf5)
      , progress(progress)
      , series(output)
  {}



  void
  SnapshotSeries::write(const double                        time,
                        const std::function<Snapshot()>    &blocks_cells,
                        const std::function<Snapshot()>    &contacts_cells,
                        const std::function<std::string()> &blocks_vtu,
                        const std::function<std::string()> &contacts_vtu)
  {
    auto &blocks   = progress.block_files;
    auto &contacts = progress.contact_files;
    if (hdf5)
      {
        // One file holds the blocks and the contacts.
        const std::string f
          = series.write(time, blocks_cells(), contacts_cells());
        blocks.emplace_back(time, f);
        contacts.emplace_back(time, f);
        return;
      }
    char name[64];
    std::snprintf(name, sizeof(name), "%05zu", blocks.size());
    const std::string b = std::string("blocks-") + name + ".vtu";
    const std::string c = std::string("contacts-") + name + ".vtu";
    output.write(b, blocks_vtu());
    output.write(c, contacts_vtu());
    blocks.emplace_back(time, b);
    contacts.emplace_back(time, c);
    output.write("blocks.pvd", pvd(blocks));
    output.write("contacts.pvd", pvd(contacts));
  }



  void
  SnapshotSeries::resume()
  {
    if (hdf5)
      series.restore(progress.block_files);
  }
} // namespace rockdda::dda
