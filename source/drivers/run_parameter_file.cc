#include <deal.II/base/parameter_handler.h>

#include <softsand/base/parameter_tools.h>
#include <softsand/base/version.h>
#include <softsand/base/warnings.h>
#include <softsand/drivers/convergence_study.h>
#include <softsand/drivers/run_parameter_file.h>
#include <softsand/drivers/run_scene.h>
#include <softsand/drivers/scene_setup.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <type_traits>

namespace softsand
{
  namespace drivers
  {
    namespace
    {
      /// A --set option split into its path (subsections and entry) and
      /// value, or a message naming the option when it is not
      /// "subsection/entry=value".
      std::pair<std::vector<std::string>, std::string>
      split_setting(const std::string &setting)
      {
        const auto               equals = setting.find('=');
        std::vector<std::string> path;
        if (equals != std::string::npos)
          for (const auto &part :
               Utilities::split_string_list(setting.substr(0, equals), '/'))
            path.push_back(part);
        AssertThrow(equals != std::string::npos && !path.empty() &&
                      std::none_of(path.begin(),
                                   path.end(),
                                   [](const std::string &p) {
                                     return p.empty();
                                   }),
                    ExcMessage("The option --set <" + setting +
                               "> is not of the form "
                               "\"subsection/entry=value\" (e.g. --set "
                               "\"fluid/viscosity=1e-3\")."));
        return {path, Utilities::trim(setting.substr(equals + 1))};
      }


      /// Apply the --set options to @p prm as if their lines closed the
      /// parameter file: the same checks, and a message naming the option.
      void
      apply_settings(ParameterHandler               &prm,
                     const std::vector<std::string> &settings)
      {
        for (const auto &setting : settings)
          {
            const auto [path, value] = split_setting(setting);
            std::string text;
            for (unsigned int k = 0; k + 1 < path.size(); ++k)
              text += "subsection " + path[k] + "\n";
            text += "set " + path.back() + " = " + value + "\n";
            for (unsigned int k = 0; k + 1 < path.size(); ++k)
              text += "end\n";
            try
              {
                prm.parse_input_from_string(text);
              }
            catch (const std::exception &e)
              {
                // deal.II's message names the line of a string we made:
                // name the option instead.
                const std::string message = std::regex_replace(
                  base::error_message(e),
                  std::regex(R"(^Line <\d+> of file <input string>?:\s*)"),
                  "");
                AssertThrow(false,
                            ExcMessage("The option --set <" + setting +
                                       ">: " + message));
              }
          }
      }


      /// The dimension of the scene: the file's, or that of a --set
      /// "dimension=...".
      unsigned int
      scene_dimension(const std::string              &filename,
                      const std::vector<std::string> &settings)
      {
        unsigned int dim = core::read_dimension(filename);
        for (const auto &setting : settings)
          {
            const auto [path, value] = split_setting(setting);
            if (path.size() == 1 && Utilities::trim(path[0]) == "dimension")
              {
                if (value != "2" && value != "3")
                  base::throw_invalid_parameter("dimension", value, "2 or 3");
                dim = std::stoi(value);
              }
          }
        return dim;
      }


      /// A fresh run's output directory must not hold another run's
      /// results: its statistics, log and checkpoints would be overwritten
      /// or, worse, mixed with this run's. A restart (from the checkpoint
      /// there) continues that run and may.
      void
      check_output_directory_is_free(const std::string &directory,
                                     const bool         restart,
                                     const MPI_Comm     comm)
      {
        if (restart)
          return;
        std::string found;
        if (Utilities::MPI::this_mpi_process(comm) == 0)
          for (const std::string name :
               {"statistics.txt", "checkpoint.info", "run-0"})
            if (found.empty() &&
                std::filesystem::exists(directory + "/" + name))
              found = name;
        found = Utilities::MPI::broadcast(comm, found, 0);
        if (!found.empty())
          base::throw_invalid_parameter(
            "output/directory",
            directory,
            "it holds an earlier run's results (" + found +
              ") and a new run would overwrite them: give another "
              "directory (or --set \"output/directory=NEW\"), delete this "
              "one, or continue that run from its checkpoint with "
              "simulation control/restart = true");
      }


      /// The input beside the results: original.prm as given and
      /// parameters.prm with every entry's value as read (defaults
      /// expanded, --set options applied), so that a run can be repeated
      /// from its output alone.
      void
      keep_input(const std::string              &filename,
                 const std::vector<std::string> &settings,
                 const ParameterHandler         &prm,
                 const std::string              &directory,
                 const MPI_Comm                  comm)
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
        out << "# " << base::version_line() << '\n'
            << "# read from " << filename << '\n';
        for (const auto &setting : settings)
          out << "# --set \"" << setting << "\"\n";
        prm.print_parameters(out, ParameterHandler::OutputStyle::ShortPRM);
      }
    } // namespace


    void
    run_parameter_file(const std::string              &filename,
                       const MPI_Comm                  comm,
                       const std::vector<std::string> &settings)
    {
      const auto run = [&](auto dim_tag) {
        constexpr int    dim = decltype(dim_tag)::value;
        ParameterHandler prm;
        core::Parameters<dim>::declare_parameters(prm);
        prm.parse_input(filename);
        apply_settings(prm, settings);
        core::Parameters<dim> parameters;
        parameters.parse_parameters(prm);
        for (const auto &duplicate : core::duplicated_entries(filename))
          base::warn(duplicate, comm);
        check_output_directory_is_free(parameters.output.directory,
                                       parameters.simulation_control.restart,
                                       comm);
        keep_input(filename, settings, prm, parameters.output.directory, comm);
        if (parameters.convergence_study.knob !=
            core::ConvergenceStudyParameters::Knob::none)
          ConvergenceStudy<dim>(parameters, comm).run();
        else
          run_scene(parameters, comm);
      };
      // Before deal.II follows them: a cycle would recurse until the stack
      // overflows.
      core::check_include_cycles(filename);
      if (scene_dimension(filename, settings) == 2)
        run(std::integral_constant<int, 2>());
      else
        run(std::integral_constant<int, 3>());
    }
  } // namespace drivers
} // namespace softsand
