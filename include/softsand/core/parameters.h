#ifndef softsand_core_parameters_h
#define softsand_core_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <softsand/core/convergence_study_parameters.h>
#include <softsand/core/mesh_parameters.h>
#include <softsand/core/simulation_control.h>
#include <softsand/coupling/coupling_parameters.h>
#include <softsand/coupling/grain_solid_field.h>
#include <softsand/dem/dem_parameters.h>
#include <softsand/dem/grain_parameters.h>
#include <softsand/fluid/boundary_conditions.h>
#include <softsand/fluid/fluid_parameters.h>
#include <softsand/io/output_parameters.h>
#include <softsand/postprocess/flow_diagnostics.h>
#include <softsand/postprocess/fracture_area.h>
#include <softsand/postprocess/radial_flow.h>

#include <map>
#include <string>

namespace softsand
{
  namespace core
  {
    /**
     * All parameters of a scene, one struct per subsection of the .prm file.
     */
    template <int dim>
    struct Parameters
    {
      SimulationControl                    simulation_control;
      MeshParameters<dim>                  mesh;
      dem::GrainParameters<dim>            grains;
      dem::DEMParameters                   dem;
      coupling::VoidFractionParameters     void_fraction;
      coupling::HybridModelParameters      hybrid_model;
      coupling::CouplingParameters         coupling;
      fluid::FluidParameters               fluid;
      fluid::SolverParameters              fluid_solver;
      fluid::BoundaryConditions<dim>       boundary_conditions;
      io::OutputParameters                 output;
      postprocess::PostprocessingParameters postprocessing;
      ConvergenceStudyParameters           convergence_study;
      postprocess::RadialFlowParameters     radial_flow;
      postprocess::FractureAreaParameters   fracture_area;
      /// Every entry as read ("subsection/.../entry" -> value, defaults
      /// included): what a checkpoint's fingerprint is taken of.
      std::map<std::string, std::string> entries;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /// Every entry of @p prm with its value ("subsection/entry" -> value).
    std::map<std::string, std::string>
    all_entries(const ParameterHandler &prm);

    /// The space dimension named by 'set dimension = 2|3' in a parameter
    /// file (3 if absent); stops with a clear message for a missing file.
    unsigned int
    read_dimension(const std::string &filename);

    /// Stops with a message naming the chain of files when the 'include'
    /// statements of parameter file @p filename form a cycle (a file that
    /// includes itself, directly or through others), which deal.II would
    /// follow until the stack overflows. Paths are taken as deal.II takes
    /// them: relative to the working directory, not to the including file.
    void
    check_include_cycles(const std::string &filename);

    /// The entries of parameter file @p filename set more than once (the
    /// last one wins in ParameterHandler), each as a sentence naming the
    /// entry and both lines.
    std::vector<std::string>
    duplicated_entries(const std::string &filename);
  } // namespace core
} // namespace softsand

#endif
