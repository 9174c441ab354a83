#ifndef softsand_tests_test_scenes_h
#define softsand_tests_test_scenes_h

// Run a scene given as .prm text and return its last statistics row.

#include <deal.II/base/parameter_handler.h>

#include <softsand/core/parameters.h>
#include <softsand/core/simulator.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>

/// The scene parameters/NAME.prm of the repository with its output sent to
/// ./results, without VTU files and quiet; later entries may override it.
inline std::string
scene_text(const std::string &name)
{
  std::ifstream     in(std::string(SOURCE_DIR) + "/../parameters/" + name +
                   ".prm");
  std::stringstream text;
  text << in.rdbuf()
       << "subsection output\n set directory = results\n"
          " set write vtu = false\n set verbosity = quiet\nend\n";
  return text.str();
}

template <int dim>
std::map<std::string, double>
run_scene(const std::string &prm_text, const MPI_Comm comm = MPI_COMM_WORLD)
{
  using namespace softsand;
  dealii::ParameterHandler prm;
  core::Parameters<dim>::declare_parameters(prm);
  prm.parse_input_from_string(prm_text);
  core::Parameters<dim> parameters;
  parameters.parse_parameters(prm);
  core::Simulator<dim> simulator(parameters, comm);
  simulator.run();
  return simulator.results();
}

#endif
