#include <softsand/base/parameter_tools.h>
#include <softsand/core/parameters.h>

#include <fstream>
#include <map>
#include <regex>

namespace softsand
{
  namespace core
  {
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
      simulation_control.parse_parameters(prm);
      mesh.parse_parameters(prm);
      grains.parse_parameters(prm);
      dem.parse_parameters(prm);
      void_fraction.parse_parameters(prm);
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
