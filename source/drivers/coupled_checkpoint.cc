// Checkpoint and restart of the coupled scene: the fluid mesh and solution
// (deal.II serialization) and the DEM state in checkpoint-STEP.*, and
// checkpoint.info with the step, where the mesh was last adapted and the
// held-force history, the last step's length and the fracture's stall
// window (files and their order: checkpoint_files.h).

#include <softsand/drivers/checkpoint_files.h>
#include <softsand/drivers/coupled_scene.h>

#include <fstream>
#include <iomanip>
#include <sstream>

namespace softsand
{
  namespace drivers
  {
    namespace
    {
      const std::string stall_window_tag = "fracture_stall_window";
    }


    void
    CoupledScene::write_checkpoint()
    {
      TimerOutput::Scope t(timer, "checkpoint");
      const std::string dir  = parameters.output.directory;
      const std::string base = checkpoint_base(dir, step);
      fluid.solver().prepare_for_serialization();
      fluid.triangulation().save(base + ".fluid");
      std::ostringstream dem_state;
      dem->save_state(dem_state);
      std::ostringstream info;
      if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
        {
          {
            std::ofstream out(base + ".dem", std::ios::binary);
            out << dem_state.str();
          }
          const auto &centers = fluid.centers_at_adaptation();
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
          // The last step's length: BDF2 goes on only with equal steps.
          info << fluid.solver().last_transient_step() << '\n';
          // The fracture's stall window: the restarted run must stop where
          // the uninterrupted one would.
          if (fracture_development)
            {
              info << stall_window_tag << ' ';
              fracture_development->save(info);
            }
        }
      commit_checkpoint(dir,
                        step,
                        "coupled",
                        scene_fingerprint(parameters),
                        info.str(),
                        mpi_communicator);
    }


    void
    CoupledScene::read_checkpoint()
    {
      TimerOutput::Scope t(timer, "checkpoint");
      const std::string  dir  = parameters.output.directory;
      std::istringstream info = read_checkpoint_info(
        dir, "coupled", scene_fingerprint(parameters), mpi_communicator);
      unsigned int fluid_steps = 0, n_centers = 0;
      info >> step >> time >> fluid_steps >> n_mesh_adaptations >> n_centers;
      const std::string base = checkpoint_base(dir, step);
      std::vector<Point<3>> centers(n_centers);
      for (auto &c : centers)
        for (unsigned int d = 0; d < 3; ++d)
          info >> c[d];
      held_force->load(info, dir + "/checkpoint.info");
      double last_step = 0; // absent from older checkpoints
      if (!(info >> last_step))
        last_step = 0;
      // Absent from older checkpoints and from runs without the stall stop:
      // the window then starts anew.
      std::string tag;
      if (info >> tag && tag == stall_window_tag && fracture_development)
        fracture_development->load(info);
      else if (fracture_development &&
               parameters.fracture_area.stall_stop_set())
        console.pcout << "softsand coupled: the checkpoint holds no fracture "
                         "stall window; the stall stop's window starts anew."
                      << std::endl;

      // The coarse mesh as at the start, then the saved refinement.
      fluid.make_mesh(false, true);
      fluid.triangulation().load(base + ".fluid");
      fluid.solver().set_solid_field(nullptr);
      fluid.solver().deserialize(fluid_steps, last_step);
      fluid.solver().set_time(time);

      std::ifstream in = open_checkpoint_file(base + ".dem");
      dem->load_state(in);
      update_grains_from_dem();
      fluid.set_centers_at_adaptation(centers);
    }
  } // namespace drivers
} // namespace softsand
