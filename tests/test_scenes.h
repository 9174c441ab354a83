#ifndef softsand_tests_test_scenes_h
#define softsand_tests_test_scenes_h

// Run a scene given as .prm text and return its last statistics row.

#include <deal.II/base/parameter_handler.h>

#include <softsand/base/warnings.h>
#include <softsand/core/parameters.h>
#include <softsand/drivers/granular_scene.h>
#include <softsand/drivers/run_scene.h>

#include <deal.II/base/logstream.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <string>
#include <vector>

/// Whether a warning containing @p text was given in this process.
inline bool
warned(const std::string &text)
{
  for (const auto &w : softsand::base::warnings_given())
    if (w.find(text) != std::string::npos)
      return true;
  return false;
}

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

/// The columns of a statistics file by name, one value per row.
inline std::map<std::string, std::vector<double>>
read_statistics(const std::string &file)
{
  std::ifstream                              in(file);
  std::vector<std::string>                   names;
  std::map<std::string, std::vector<double>> columns;
  for (std::string line; std::getline(in, line);)
    {
      std::istringstream words(line);
      // The names line; '#' lines (a column and its unit each).
      if (line.empty() || line[0] == '#')
        continue;
      if (std::isalpha(line[0]))
        {
          for (std::string name; words >> name;)
            names.push_back(name);
          continue;
        }
      double value;
      for (unsigned int i = 0; i < names.size() && (words >> value); ++i)
        columns[names[i]].push_back(value);
    }
  return columns;
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
  return drivers::run_scene(parameters, comm);
}

/// Run a granular (DEM-only) scene given as .prm text; its final results.
inline std::map<std::string, double>
run_granular_scene(const std::string &prm_text,
                   const MPI_Comm     comm = MPI_COMM_WORLD)
{
  using namespace softsand;
  dealii::ParameterHandler prm;
  core::Parameters<3>::declare_parameters(prm);
  prm.parse_input_from_string(prm_text);
  core::Parameters<3> parameters;
  parameters.parse_parameters(prm);
  drivers::GranularScene simulator(parameters, comm);
  simulator.run();
  return simulator.results();
}

/// One row of an order-of-accuracy table in deallog: cells, velocity and
/// pressure L2 errors and, from the second row on (@p old_u > 0), the
/// observed orders log2(e_old / e). Updates @p old_u and @p old_p.
inline void
log_error_row(const unsigned int                   refinement,
              const std::map<std::string, double> &results,
              double                              &old_u,
              double                              &old_p)
{
  using dealii::deallog;
  const double eu = results.at("velocity_l2_error");
  const double ep = results.at("pressure_l2_error");
  deallog << "refinement " << refinement << " cells "
          << static_cast<unsigned int>(results.at("cells")) << " velocity L2 "
          << std::scientific << std::setprecision(3) << eu << " pressure L2 "
          << ep << std::fixed;
  if (old_u > 0)
    deallog << " orders " << std::setprecision(1) << std::log2(old_u / eu)
            << ' ' << std::log2(old_p / ep);
  deallog << std::setprecision(6) << std::endl;
  old_u = eu;
  old_p = ep;
}

#endif
