// Runs outside their model's validity or on doubtful input go on with a
// warning (once): an entry set twice in a .prm (both lines named), a pack
// saved unsettled (and its file's header says so), fluid/theta = 0 with the
// penalization, a coupling step above the grains' response time, a
// creeping-flow model at pore Reynolds numbers above 1, a fluid solve
// retried with a stronger velocity preconditioner, freed contact cells
// that hand most of a pack to the fluid, grains overlapping beyond what
// the contact law (and a grain file) accepts, the paper's penalization on
// a pack at a penalty coupling number the coupled step is unstable at. Settings
// a scene would ignore (restart, checkpoints outside coupled scenes) stop
// it instead.

#include <deal.II/base/mpi.h>

#include <softsand/base/parameter_tools.h>
#include <softsand/base/warnings.h>
#include <softsand/core/parameters.h>

#include <cmath>
#include <fstream>

#include "test_scenes.h"
#include "tests.h"

namespace
{
  /// The message of the error @p text stops with, or "accepted".
  std::string
  stops(const std::string &text)
  {
    try
      {
        run_granular_scene(text);
      }
    catch (const std::exception &e)
      {
        return softsand::base::error_message(e);
      }
    return "accepted (wrong)";
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  using namespace softsand;

  // 1. An entry set twice.
  {
    std::ofstream("twice.prm")
      << "subsection mesh\n  set cells per diameter = 4\nend\n"
         "subsection fluid\n  set theta = 1e6\nend\n"
         "subsection mesh\n  # again\n  set cells per diameter  = 8\nend\n";
    for (const auto &d : core::duplicated_entries("twice.prm"))
      deallog << d << std::endl;
  }

  // 2. A pour stopped before it settled: saved with a note and a warning.
  {
    const auto r = run_granular_scene(
      scene_text("pour") +
      "subsection simulation control\n set end time = 0.01\nend\n");
    std::ifstream in("results/pack.txt");
    std::string   line, note;
    while (std::getline(in, line) && line[0] == '#')
      if (line.find("unsettled") != std::string::npos)
        note = line.substr(0, line.find(" saved"));
    deallog << "pour to 10 ms: settled " << r.at("settled")
            << ", pack header: '" << note << "', warned: "
            << (warned("the pack is unsettled") ? "yes" : "no") << std::endl;
  }

  // 3. The penalization without penalty.
  {
    run_scene<3>(scene_text("drag_sphere") +
                 "subsection fluid\n set theta = 0\n"
                 " set solid model = penalization\nend\n"
                 "subsection mesh\n set cells per diameter = 2\nend\n");
    deallog << "theta = 0 with penalization warned: "
            << (warned("fluid/theta = 0") ? "yes" : "no") << std::endl;
  }

  // 4. A coupled step of 5.7 response times of the free sphere.
  {
    run_scene<3>(scene_text("free_sphere") +
                 "subsection simulation control\n set time step = 0.1\n"
                 " set end time = 0.1\nend\n"
                 "subsection mesh\n set cells per diameter = 2\nend\n");
    std::string ratio;
    for (const auto &w : base::warnings_given())
      if (const auto k = w.find(" s is "); k != std::string::npos)
        ratio = w.substr(k + 6, w.find(" times") - k - 6);
    deallog << "coupled time step 0.1 s: warned, " << ratio
            << " times the response time" << std::endl;
  }

  // 5. Steady Stokes past the sphere (d = 1 mm, U = 1e-4 m/s): Re_p 0.1 at
  // mu = 1e-3, no warning; at mu = 1e-5 the same velocity field has 100x the
  // pore Reynolds number, above 1: warned, naming the entry.
  for (const double mu : {1e-3, 1e-5})
    {
      const auto r = run_scene<3>(
        scene_text("drag_sphere") + "subsection fluid\n set viscosity = " +
        std::to_string(mu) +
        "\nend\nsubsection mesh\n set cells per diameter = 2\nend\n");
      deallog << "steady Stokes, mu = " << mu << ": pore Reynolds max "
              << r.at("pore_reynolds_max") << ", 95 % below "
              << r.at("pore_reynolds_p95") << ", warned: "
              << (warned("simulation control/mode = steady stokes neglects") ?
                    "yes" :
                    "no")
              << std::endl;
    }

  // 6. A fluid solve that does not converge (at most 1 FGMRES iteration to
  // 1e-12): retried with twice, then four times the velocity AMG sweeps,
  // each with a warning; then it stops, naming where the residual is
  // largest.
  {
    std::string error = "no error (wrong)";
    try
      {
        run_scene<3>(scene_text("drag_sphere") +
                     "subsection mesh\n set cells per diameter = 2\nend\n"
                     "subsection fluid solver\n"
                     " set max linear iterations = 1\n"
                     " set linear tolerance = 1e-12\nend\n");
      }
    catch (const std::exception &e)
      {
        error = softsand::base::error_message(e);
      }
    deallog << "failed solve: retried with 8 sweeps: "
            << (warned("with 8 velocity AMG sweeps instead of 4") ? "yes" :
                                                                     "no")
            << ", with 16: "
            << (warned("with 16 velocity AMG sweeps instead of 8") ? "yes" :
                                                                      "no")
            << ", then stopped: "
            << error.substr(0, error.find(" iterations")) << ", "
            << (error.find("Largest residual: momentum rows") !=
                    std::string::npos ?
                  "largest residual located" :
                  "largest residual not located")
            << std::endl;
  }

  // 7. Freed contact cells on a coarse mesh: the small Hele-Shaw pack at 2
  // cells per mean diameter, one coupling step. The transient model frees
  // them (automatic) and they hold nearly all of the grains' volume: warned.
  // The quasi-steady model keeps them: nothing freed, no warning.
  for (const std::string model : {"quasi-steady", "transient"})
    {
      const auto r = run_scene<3>(
        scene_text("hele_shaw_small") +
        "subsection simulation control\n set max time steps = 1\n"
        " set time step = 1e-4\nend\n"
        "subsection coupling\n set fluid model = " + model + "\nend\n"
        "subsection fluid\n set free contact cells = automatic\nend\n"
        "subsection grains\n set file = " + std::string(SOURCE_DIR) +
        "/../parameters/packs/hele_shaw_small.txt\nend\n");
      deallog << "small Hele-Shaw, " << model << ": freed solid fraction "
              << std::round(1000 * r.at("freed_solid_fraction")) / 1000
              << ", warned: "
              << (warned("the freed contact cells") ? "yes" : "no")
              << std::endl;
    }

  // 7b. The paper's penalization on the same pack and step: grains that
  // share a cell are held together by the penalty. The penalty coupling
  // number Theta (rho_f / rho_s) h^3 / V (smallest grain, finest cell) is
  // 0.3 Theta here: warned at Theta = 1e6, not at 1e2.
  for (const double theta : {1e2, 1e6})
    {
      run_scene<3>(
        scene_text("hele_shaw_small") +
        "subsection simulation control\n set max time steps = 1\n"
        " set time step = 1e-4\nend\n"
        "subsection coupling\n set fluid model = transient\n"
        " set void fraction model = cell average\nend\n"
        "subsection fluid\n set solid model = penalization\n"
        " set theta = " + std::to_string(theta) + "\nend\n"
        "subsection grains\n set file = " + std::string(SOURCE_DIR) +
        "/../parameters/packs/hele_shaw_small.txt\nend\n");
      std::string number = "none";
      for (const auto &w : base::warnings_given())
        if (const auto k = w.find("h^3 / V = "); k != std::string::npos)
          number = w.substr(k + 10, w.find(" (finest") - k - 10);
      deallog << "small Hele-Shaw, penalization, theta = " << theta
              << ": penalty coupling number warned: " << number << std::endl;
    }

  // 8. Settings a steady scene would ignore (it has no time loop to
  // checkpoint); a granular scene restarts, and says so where there is no
  // checkpoint yet.
  const std::string scene =
    "subsection simulation control\n set mode = %m\n"
    " set end time = 1e-4\n set %s\nend\n"
    "subsection mesh\n set lower corner = 0, 0, 0\n"
    " set upper corner = 1e-3, 1e-3, 1e-3\nend\n"
    "subsection output\n set directory = results\n set write vtu = false\n"
    " set verbosity = quiet\nend\n";
  for (const std::string mode : {"steady stokes", "granular"})
    for (const std::string entry :
         {"restart = true", "checkpoint interval = 5"})
      {
        if (mode == "granular" && entry != "restart = true")
          continue;
        std::string text = scene;
        text.replace(text.find("%m"), 2, mode);
        text.replace(text.find("%s"), 2, entry);
        deallog << mode << " with " << entry << ": " << stops(text)
                << std::endl;
      }
  // 9. Two grains at rest, touching, pulled together by the simplified JKR
  // cohesion until Hertz balances it (test dem_contact_laws checks the
  // balance against its closed form): with the paper's soft grains (E = 5
  // MPa) at 0.034 R* for c = 1e5 J/m^3, at 1.9 R* for 1e6, beyond
  // grains/max overlap ratio = 0.3: there the run warns that the contact
  // law is outside its validity.
  for (const double c : {1e5, 1e6})
    {
      const auto r = run_granular_scene(
        "subsection simulation control\n set mode = granular\n"
        " set end time = 2e-3\nend\n"
        "subsection mesh\n set lower corner = -5e-4, -5e-4, -5e-4\n"
        " set upper corner = 5e-4, 5e-4, 5e-4\nend\n"
        "subsection grains\n set source = list\n"
        " set list = -0.995e-4, 0, 0, 1e-4; 0.995e-4, 0, 0, 1e-4\nend\n"
        "subsection dem\n set gravity = 0, 0, 0\n subsection material\n"
        "  set density = 2650\n  set youngs modulus = 5e6\n"
        "  set poisson ratio = 0.15\n  set restitution = 0.3\n"
        "  set cohesion energy density = " + std::to_string(c) +
        "\n end\nend\n"
        "subsection output\n set directory = results\n"
        " set write vtu = false\n set verbosity = quiet\nend\n");
      deallog << "cohesive pair, c = " << c << ": overlap "
              << r.at("max_overlap_ratio") << " R*, warned: "
              << (warned("grains/max overlap ratio = 0.3: the contact law") ?
                    "yes" :
                    "no")
              << std::endl;
    }
}
