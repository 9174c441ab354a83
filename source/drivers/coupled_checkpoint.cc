// Checkpoint and restart of the coupled scene: the fluid mesh and solution
// (deal.II serialization), the DEM state, and a text file with the step,
// where the mesh was last adapted and the held-force history.

#include <softsand/drivers/coupled_scene.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace softsand
{
  namespace drivers
  {
    void
    CoupledScene::write_checkpoint()
    {
      TimerOutput::Scope t(timer, "checkpoint");
      const std::string  base = parameters.output.directory + "/checkpoint";
      // Write to temporary names, then rename: a run stopped while writing
      // leaves the previous checkpoint intact.
      fluid.solver().prepare_for_serialization();
      fluid.triangulation().save(base + ".fluid.tmp");
      {
        std::ostringstream dem_state;
        dem->save_state(dem_state);
        if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
          {
            std::ofstream out(base + ".dem.tmp", std::ios::binary);
            out << dem_state.str();
            std::ofstream info(base + ".info.tmp");
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
          namespace fs = std::filesystem;
          const fs::path dir(parameters.output.directory);
          // The info file last: it marks the checkpoint complete.
          for (const auto &entry : fs::directory_iterator(dir))
            {
              const std::string name = entry.path().filename().string();
              if (name.rfind("checkpoint.", 0) == 0 &&
                  name.find(".tmp") != std::string::npos &&
                  name != "checkpoint.info.tmp")
                {
                  std::string final_name = name;
                  final_name.erase(final_name.find(".tmp"), 4);
                  fs::rename(entry.path(), dir / final_name);
                }
            }
          fs::rename(dir / "checkpoint.info.tmp", dir / "checkpoint.info");
        }
      MPI_Barrier(mpi_communicator);
    }


    void
    CoupledScene::read_checkpoint()
    {
      TimerOutput::Scope t(timer, "checkpoint");
      const std::string  base = parameters.output.directory + "/checkpoint";
      std::ifstream      info(base + ".info");
      AssertThrow(info.good(),
                  ExcMessage("simulation control/restart = true, but there "
                             "is no checkpoint <" +
                             base +
                             ".info>: run with a checkpoint interval > 0 "
                             "first."));
      unsigned int fluid_steps = 0, n_centers = 0;
      info >> step >> time >> fluid_steps >> n_mesh_adaptations >> n_centers;
      std::vector<Point<3>> centers(n_centers);
      for (auto &c : centers)
        for (unsigned int d = 0; d < 3; ++d)
          info >> c[d];
      held_force->load(info, base + ".info");

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
