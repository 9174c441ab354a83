#include <deal.II/base/parameter_handler.h>

#include <softsand/base/warnings.h>
#include <softsand/drivers/convergence_study.h>
#include <softsand/drivers/run_parameter_file.h>
#include <softsand/drivers/run_scene.h>
#include <softsand/drivers/scene_setup.h>

#include <filesystem>
#include <fstream>

#include <type_traits>

namespace softsand
{
  namespace drivers
  {
    namespace
    {
      /// The input beside the results: original.prm as given and
      /// parameters.prm with every entry's value as read (defaults
      /// expanded), so that a run can be repeated from its output alone.
      void
      keep_input(const std::string      &filename,
                 const ParameterHandler &prm,
                 const std::string      &directory,
                 const MPI_Comm          comm)
      {
        make_output_directory(directory, comm);
        if (Utilities::MPI::this_mpi_process(comm) != 0)
          return;
        const std::string original = directory + "/original.prm";
        // A rerun of a run's own copy keeps it.
        if (!std::filesystem::exists(original) ||
            !std::filesystem::equivalent(filename, original))
          std::filesystem::copy_file(
            filename,
            original,
            std::filesystem::copy_options::overwrite_existing);
        std::ofstream out(directory + "/parameters.prm");
        prm.print_parameters(out, ParameterHandler::OutputStyle::ShortPRM);
      }
    } // namespace


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
        for (const auto &duplicate : core::duplicated_entries(filename))
          base::warn(duplicate, comm);
        keep_input(filename, prm, parameters.output.directory, comm);
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
