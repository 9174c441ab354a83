#include <deal.II/base/parameter_handler.h>

#include <softsand/drivers/convergence_study.h>
#include <softsand/drivers/run_parameter_file.h>
#include <softsand/drivers/run_scene.h>

#include <type_traits>

namespace softsand
{
  namespace drivers
  {
    void
    run_parameter_file(const std::string &filename, const MPI_Comm comm)
    {
      const auto run = [&](auto dim_tag) {
        constexpr int    dim = decltype(dim_tag)::value;
        ParameterHandler prm;
        core::Parameters<dim>::declare_parameters(prm);
        prm.parse_input(filename);
        core::Parameters<dim> parameters;
        parameters.parse_parameters(prm);
        if (parameters.convergence_study.knob !=
            core::ConvergenceStudyParameters::Knob::none)
          ConvergenceStudy<dim>(parameters, comm).run();
        else
          run_scene(parameters, comm);
      };
      if (core::read_dimension(filename) == 2)
        run(std::integral_constant<int, 2>());
      else
        run(std::integral_constant<int, 3>());
    }
  } // namespace drivers
} // namespace softsand
