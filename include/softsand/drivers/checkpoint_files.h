#ifndef softsand_drivers_checkpoint_files_h
#define softsand_drivers_checkpoint_files_h

#include <deal.II/base/mpi.h>

#include <sstream>
#include <string>

namespace softsand
{
  namespace drivers
  {
    /**
     * The files of a checkpoint in the output directory, shared by the
     * scenes with a time loop (granular, transient fluid, coupled):
     * checkpoint-STEP.* written by the scene, then checkpoint.info naming
     * the step, written aside and renamed (atomic), then the older
     * checkpoints removed. A run killed at any point leaves an info file and
     * the complete checkpoint it names. The info file's first word is the
     * step; its last line names the mode of the run that wrote it.
     */

    /// Prefix of the files of the checkpoint of step @p step.
    std::string
    checkpoint_base(const std::string &directory, const unsigned long step);

    /// Make the checkpoint of @p step current once every rank has written
    /// its files: @p info (rank 0's) becomes checkpoint.info. Collective.
    void
    commit_checkpoint(const std::string &directory,
                      const unsigned long step,
                      const std::string &mode,
                      const std::string &info,
                      const MPI_Comm     comm);

    /// The contents of the directory's checkpoint.info, which a run of
    /// @p mode wrote: a missing file or another mode stops the run with a
    /// message naming simulation control/restart.
    std::istringstream
    read_checkpoint_info(const std::string &directory, const std::string &mode);

    /// Stop the run if reading the fields of the directory's checkpoint.info
    /// from @p info failed (a truncated or corrupt file).
    void
    check_checkpoint_info(const std::istream &info, const std::string &directory);

    /// Open a file of the checkpoint for reading (binary), or stop the run
    /// with a message naming it.
    std::ifstream
    open_checkpoint_file(const std::string &name);
  } // namespace drivers
} // namespace softsand

#endif
