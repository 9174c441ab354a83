// Checkpoint and restart of the coupled scene: the fluid mesh and solution
// (deal.II serialization) and the DEM state in checkpoint-STEP.*, and
// checkpoint.info with the step, where the mesh was last adapted and the
// held-force history.

#include <softsand/drivers/coupled_scene.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace softsand
{
  namespace drivers
  {
    namespace
    {
      /// The files of the checkpoint of step @p step: checkpoint-STEP.*.
      std::string
      checkpoint_base(const std::string &directory, const unsigned int step)
      {
        return directory + "/checkpoint-" + std::to_string(step);
      }
    } // namespace


    void
    CoupledScene::write_checkpoint()
    {
      TimerOutput::Scope t(timer, "checkpoint");
      namespace fs          = std::filesystem;
      const std::string dir = parameters.output.directory;
      // The step's files under names of their own, then checkpoint.info
      // naming them (written aside and renamed, atomic), then the older
      // checkpoints removed: a run killed at any point leaves an info file
      // and the complete checkpoint it names.
      const std::string base = checkpoint_base(dir, step);
      fluid.solver().prepare_for_serialization();
      fluid.triangulation().save(base + ".fluid");
      {
        std::ostringstream dem_state;
        dem->save_state(dem_state);
        if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
          {
            {
              std::ofstream out(base + ".dem", std::ios::binary);
              out << dem_state.str();
            }
            std::ofstream info(dir + "/checkpoint.info.tmp");
            const auto   &centers = fluid.centers_at_adaptation();
            info << std::setprecision(17) << step << ' ' << time << ' '
                 << fluid.solver().n_steps_done() << ' ' << n_mesh_adaptations
                 << ' ' << centers.size() << '\n';
            // Where the mesh was last adapted: the restarted run must
            // re-adapt when the uninterrupted one would.
            for (const auto &c : centers)
              info << c << '\n';
            // The measured resistances: the restarted run must linearize
            // the held forces as the uninterrupted one.
            held_force->save(info);
          }
      }
      MPI_Barrier(mpi_communicator);
      if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
        {
          fs::rename(dir + "/checkpoint.info.tmp", dir + "/checkpoint.info");
          const std::string current = "checkpoint-" + std::to_string(step) + ".";
          for (const auto &entry : fs::directory_iterator(dir))
            {
              const std::string name = entry.path().filename().string();
              if (name.rfind("checkpoint-", 0) == 0 &&
                  name.rfind(current, 0) != 0)
                fs::remove(entry.path());
            }
        }
      MPI_Barrier(mpi_communicator);
    }


    void
    CoupledScene::read_checkpoint()
    {
      TimerOutput::Scope t(timer, "checkpoint");
      const std::string  info_name =
        parameters.output.directory + "/checkpoint.info";
      std::ifstream info(info_name);
      AssertThrow(info.good(),
                  ExcMessage("simulation control/restart = true, but there "
                             "is no checkpoint <" +
                             info_name +
                             ">: run with a checkpoint interval > 0 "
                             "first."));
      unsigned int fluid_steps = 0, n_centers = 0;
      info >> step >> time >> fluid_steps >> n_mesh_adaptations >> n_centers;
      const std::string base = checkpoint_base(parameters.output.directory, step);
      std::vector<Point<3>> centers(n_centers);
      for (auto &c : centers)
        for (unsigned int d = 0; d < 3; ++d)
          info >> c[d];
      held_force->load(info, info_name);

      // The coarse mesh as at the start, then the saved refinement.
      fluid.make_mesh(false, true);
      fluid.triangulation().load(base + ".fluid");
      fluid.solver().set_solid_field(nullptr);
      fluid.solver().deserialize(fluid_steps);
      fluid.solver().set_time(time);

      std::ifstream in(base + ".dem", std::ios::binary);
      AssertThrow(in.good(),
                  ExcMessage("The checkpoint <" + base +
                             ".dem> is missing or unreadable."));
      dem->load_state(in);
      update_grains_from_dem();
      fluid.set_centers_at_adaptation(centers);
    }
  } // namespace drivers
} // namespace softsand
