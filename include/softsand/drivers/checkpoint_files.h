#ifndef softsand_drivers_checkpoint_files_h
#define softsand_drivers_checkpoint_files_h

#include <deal.II/base/mpi.h>

#include <softsand/core/parameters.h>

#include <sstream>
#include <string>
#include <utility>
#include <vector>

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
     * step; its last line names the mode of the run that wrote it, after
     * the scene's fingerprint (lines "scene ENTRY = VALUE"): what a restart
     * must not change.
     */

    /// What identifies the scene of a checkpoint: (entry, value) pairs,
    /// the last one a hash of @p fixed_entries, which the checkpoint keeps
    /// in checkpoint-STEP.scene (to name the entries that differ).
    struct SceneFingerprint
    {
      std::vector<std::pair<std::string, std::string>> entries;
      std::string                                      fixed_entries;
    };

    /// The fingerprint of the scene of @p parameters: the mode, the
    /// dimension, the mesh entries that make the coarse mesh and its
    /// refinement (geometry, corners, coarse cells, cells per diameter, mesh
    /// file), the grain source, pack file, a hash of its content and the
    /// grain count, and a hash of every
    /// entry fixed over a restart (fixed_entries()). A restart whose
    /// fingerprint differs would read a mesh, fields or grains that are not
    /// its scene's: deal.II's SolutionTransfer then crashes rather than
    /// stops.
    template <int dim>
    SceneFingerprint
    scene_fingerprint(const core::Parameters<dim> &parameters);

    /// The entries of @p parameters that a restart must not change (those
    /// that make the mesh, the grains and the walls), as "path = value"
    /// lines with numbers written alike: what the fingerprint's hash is
    /// taken of.
    template <int dim>
    std::string
    fixed_entries(const core::Parameters<dim> &parameters);

    /// Prefix of the files of the checkpoint of step @p step.
    std::string
    checkpoint_base(const std::string &directory, const unsigned long step);

    /// Make the checkpoint of @p step current once every rank has written
    /// its files: @p info (rank 0's), the scene's @p fingerprint and the
    /// size of each file of the checkpoint become checkpoint.info.
    /// Collective.
    void
    commit_checkpoint(const std::string      &directory,
                      const unsigned long     step,
                      const std::string      &mode,
                      const SceneFingerprint &fingerprint,
                      const std::string      &info,
                      const MPI_Comm          comm);

    /// The contents of the directory's checkpoint.info, which a run of
    /// @p mode wrote, without its fingerprint: a missing file, another mode
    /// or another scene (a fingerprint that differs from @p fingerprint)
    /// stops the run with a message naming simulation control/restart and
    /// what differs; so does a file of the checkpoint that is missing or
    /// whose size differs from the one recorded when it was written (cut
    /// short). A checkpoint of an earlier version without a fingerprint is
    /// read after a warning.
    std::istringstream
    read_checkpoint_info(const std::string      &directory,
                         const std::string      &mode,
                         const SceneFingerprint &fingerprint,
                         const MPI_Comm          comm);

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
