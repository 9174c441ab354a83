#include <softsand/base/parameter_tools.h>
#include <softsand/core/parameters.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

namespace softsand
{
  namespace core
  {
    std::map<std::string, std::string>
    all_entries(const ParameterHandler &prm)
    {
      std::ostringstream text;
      prm.print_parameters(text, ParameterHandler::OutputStyle::ShortPRM);
      std::istringstream       in(text.str());
      const std::regex         subsection(R"(^\s*subsection\s+(.*?)\s*$)");
      const std::regex         end(R"(^\s*end\s*$)");
      const std::regex         set(R"(^\s*set\s+(.*?)\s*=\s?(.*?)\s*$)");
      std::vector<std::string> path;
      std::map<std::string, std::string> entries;
      for (std::string line; std::getline(in, line);)
        {
          std::smatch m;
          if (std::regex_match(line, m, subsection))
            path.push_back(m[1]);
          else if (std::regex_match(line, end))
            {
              if (!path.empty())
                path.pop_back();
            }
          else if (std::regex_match(line, m, set))
            {
              std::string entry;
              for (const auto &s : path)
                entry += s + "/";
              entries[entry + std::string(m[1])] = m[2];
            }
        }
      return entries;
    }


    template <int dim>
    void
    Parameters<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("dimension",
                        "3",
                        Patterns::Integer(2, 3),
                        "Space dimension of the scene (2 or 3).");
      SimulationControl::declare_parameters(prm);
      MeshParameters<dim>::declare_parameters(prm);
      dem::GrainParameters<dim>::declare_parameters(prm);
      dem::DEMParameters::declare_parameters(prm);
      coupling::VoidFractionParameters::declare_parameters(prm);
      coupling::HybridModelParameters::declare_parameters(prm);
      coupling::CouplingParameters::declare_parameters(prm);
      fluid::FluidParameters::declare_parameters(prm);
      fluid::SolverParameters::declare_parameters(prm);
      fluid::BoundaryConditions<dim>::declare_parameters(prm);
      io::OutputParameters::declare_parameters(prm);
      postprocess::PostprocessingParameters::declare_parameters(prm);
      ConvergenceStudyParameters::declare_parameters(prm);
      postprocess::RadialFlowParameters::declare_parameters(prm);
      postprocess::FractureAreaParameters::declare_parameters(prm);
    }


    template <int dim>
    void
    Parameters<dim>::parse_parameters(ParameterHandler &prm)
    {
      entries = all_entries(prm);
      simulation_control.parse_parameters(prm);
      mesh.parse_parameters(prm);
      grains.parse_parameters(prm);
      dem.parse_parameters(prm);
      void_fraction.parse_parameters(prm);
      hybrid_model.parse_parameters(prm);
      coupling.parse_parameters(prm);
      fluid.parse_parameters(prm);
      fluid_solver.parse_parameters(prm);
      boundary_conditions.parse_parameters(
        prm,
        BoundingBox<dim>(std::make_pair(mesh.lower_corner, mesh.upper_corner)),
        mesh.geometry == MeshParameters<dim>::Geometry::cylinder ?
          mesh.cylinder_axis :
          numbers::invalid_unsigned_int,
        mesh.geometry == MeshParameters<dim>::Geometry::file);
      output.parse_parameters(prm);
      postprocessing.parse_parameters(prm);
      convergence_study.parse_parameters(prm);
      if (postprocessing.flow_axis >= dim)
        base::throw_invalid_parameter("postprocessing/flow axis",
                                "z",
                                "a 2D scene flows along x or y");
      // Radial cells: rings and fracture maps are centred on the inlet.
      radial_flow.parse_parameters(prm);
      fracture_area.parse_parameters(prm);
      const auto &inlet = boundary_conditions.inlet_region();
      if (hybrid_model.enabled && hybrid_model.resolved_radius > 0 &&
          !inlet.enabled())
        base::throw_invalid_parameter(
          "coupling/hybrid model/resolved radius",
          prm.get({"coupling", "hybrid model"}, "resolved radius"),
          "the resolved zone is a cylinder around the inlet region's axis: "
          "set boundary conditions/inlet region/type = cylinder, or the "
          "radius to none (every grain resolved) or 0 (none resolved)");
      if (!radial_flow.radii.empty() && !inlet.enabled())
        base::throw_invalid_parameter("postprocessing/radial flow/radii",
                                prm.get({"postprocessing", "radial flow"}, "radii"),
                                "pressure rings are centred on the inlet: set "
                                "boundary conditions/inlet region/type = "
                                "cylinder");
      if (fracture_area.enabled)
        {
          if (dim != 3 || !inlet.enabled() ||
              std::abs(std::abs(inlet.axis[dim - 1]) - 1) > 1e-12)
            base::throw_invalid_parameter(
              "postprocessing/fracture area/enabled",
              "true",
              "the fracture map is a 3D cell between plates normal to z "
              "around an inlet region (boundary conditions/inlet region/type "
              "= cylinder) with axis 0, 0, 1");
        }
    }


    unsigned int
    read_dimension(const std::string &filename)
    {
      std::ifstream in(filename);
      AssertThrow(in.good(),
                  ExcMessage("Cannot open the parameter file <" + filename +
                             ">: it does not exist or is not readable."));
      const std::regex pattern(
        R"(^\s*set\s+dimension\s*=\s*([^\s#]+)\s*(#.*)?$)");
      std::string line;
      unsigned int dim = 3;
      while (std::getline(in, line))
        {
          std::smatch m;
          if (std::regex_match(line, m, pattern))
            {
              const std::string v = m[1];
              if (v == "2" || v == "3")
                dim = std::stoi(v);
              else
                base::throw_invalid_parameter("dimension", v, "2 or 3");
            }
        }
      return dim;
    }

    namespace
    {
      /// The file named by each 'include' statement of @p filename, read
      /// as ParameterHandler::parse_input() reads them: comments (from an
      /// unescaped '#') removed, lines ending in '\\' joined, and the
      /// statement "include NAME" or "INCLUDE NAME" at the start of a
      /// trimmed line.
      std::vector<std::string>
      included_files(std::istream &in)
      {
        std::vector<std::string> files;
        std::string              joined;
        for (std::string line; std::getline(in, line);)
          {
            for (std::size_t k = line.find('#'); k != std::string::npos;
                 k             = line.find('#', k + 1))
              if (k == 0 || line[k - 1] != '\\')
                {
                              line.erase(k);
                              break;
                }
            line = Utilities::trim(line);
            if (!line.empty() && line.back() == '\\')
              {
                joined += line.substr(0, line.size() - 1);
                continue;
              }
            line = Utilities::trim(joined + line);
            joined.clear();
            if (line.rfind("include ", 0) == 0 ||
                line.rfind("INCLUDE ", 0) == 0)
              {
                const std::string name = Utilities::trim(line.substr(8));
                if (!name.empty())
                  files.push_back(name);
              }
          }
        return files;
      }

      void
      follow_includes(const std::string                  &filename,
                      std::vector<std::filesystem::path> &stack,
                      std::vector<std::string>           &names)
      {
        std::error_code       error;
        std::filesystem::path path =
          std::filesystem::weakly_canonical(filename, error);
        if (error)
          path = std::filesystem::absolute(filename).lexically_normal();
        const auto seen = std::find(stack.begin(), stack.end(), path);
        if (seen != stack.end())
          {
            std::string chain;
            for (auto k = seen - stack.begin(); k < long(names.size()); ++k)
              chain += "<" + names[k] + "> includes ";
            chain += "<" + filename + ">";
            AssertThrow(false,
                        ExcMessage(
                          "The parameter files include each other in a "
                          "cycle: " +
                          chain +
                          ". Remove the 'include' statement that closes "
                          "the cycle (relative paths in an 'include' are "
                          "taken from the working directory, as deal.II "
                          "reads them)."));
          }
        // A missing file: deal.II names it when it reads the statement.
        std::ifstream in(filename);
        if (!in)
          return;
        stack.push_back(path);
        names.push_back(filename);
        for (const auto &included : included_files(in))
          follow_includes(included, stack, names);
        stack.pop_back();
        names.pop_back();
      }
    } // namespace


    void
    check_include_cycles(const std::string &filename)
    {
      std::vector<std::filesystem::path> stack;
      std::vector<std::string>           names;
      follow_includes(filename, stack, names);
    }


    std::vector<std::string>
    duplicated_entries(const std::string &filename)
    {
      std::ifstream in(filename);
      const std::regex subsection(R"(^\s*subsection\s+(.*?)\s*(#.*)?$)");
      const std::regex end(R"(^\s*end\s*(#.*)?$)");
      const std::regex set(R"(^\s*set\s+(.*?)\s*=.*$)");
      std::vector<std::string>                     path;
      std::map<std::string, unsigned int>          first_line;
      std::vector<std::string>                     duplicates;
      std::string                                  line;
      for (unsigned int number = 1; std::getline(in, line); ++number)
        {
          std::smatch m;
          if (std::regex_match(line, m, subsection))
            path.push_back(m[1]);
          else if (std::regex_match(line, end))
            {
              if (!path.empty())
                path.pop_back();
            }
          else if (std::regex_match(line, m, set))
            {
              std::string entry;
              for (const auto &s : path)
                entry += s + "/";
              entry += std::regex_replace(std::string(m[1]),
                                          std::regex(R"(\s+)"),
                                          " ");
              const auto [it, inserted] = first_line.emplace(entry, number);
              if (!inserted)
                duplicates.push_back(
                  "the entry <" + entry + "> is set twice in <" + filename +
                  ">, on lines " + std::to_string(it->second) + " and " +
                  std::to_string(number) + ": the last value is used");
            }
        }
      return duplicates;
    }

    template struct Parameters<2>;
    template struct Parameters<3>;
  } // namespace core
} // namespace softsand
