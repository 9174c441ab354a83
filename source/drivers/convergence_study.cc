// Convergence studies (issue 6): one scene run for several values of one
// discretization knob, tabulated with deal.II's ConvergenceTable.

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>

#include <softsand/drivers/convergence_study.h>
#include <softsand/io/statistics_file.h>
#include <softsand/base/parameter_tools.h>
#include <softsand/drivers/run_scene.h>
#include <softsand/drivers/scene_setup.h>

#include <malloc.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>

namespace softsand
{
  namespace drivers
  {
    namespace
    {
      constexpr double not_defined = std::numeric_limits<double>::quiet_NaN();

      /// Size of the knob for the orders: 1/N, 2^-r, 1/Theta, dt.
      double
      knob_size(const core::ConvergenceStudyParameters::Knob knob, const double v)
      {
        using Knob = core::ConvergenceStudyParameters::Knob;
        switch (knob)
          {
            case Knob::cells_per_diameter:
            case Knob::theta:
              return 1. / v;
            case Knob::global_refinements:
              return std::pow(2., -v);
            default:
              return v;
          }
      }

      /// The short column name of the knob in the table.
      std::string
      knob_column(const core::ConvergenceStudyParameters::Knob knob)
      {
        using Knob = core::ConvergenceStudyParameters::Knob;
        switch (knob)
          {
            case Knob::cells_per_diameter:
              return "N";
            case Knob::global_refinements:
              return "refinements";
            case Knob::theta:
              return "theta";
            default:
              return "dt";
          }
      }

      /// Peak resident memory is a per-process high-water mark: reset it
      /// (Linux >= 4.0, /proc/self/clear_refs) after giving freed memory
      /// back, so that each run of the study measures its own peak. Returns
      /// false where the reset is not possible (the peak is then the
      /// largest over this and the earlier runs).
      bool
      reset_peak_memory()
      {
        malloc_trim(0);
        std::ofstream clear("/proc/self/clear_refs");
        if (!clear)
          return false;
        clear << "5" << std::flush;
        return clear.good();
      }

      /// CPU time (user + system) of this process so far (s).
      double
      process_cpu_time()
      {
        rusage usage;
        getrusage(RUSAGE_SELF, &usage);
        return usage.ru_utime.tv_sec + 1e-6 * usage.ru_utime.tv_usec +
               usage.ru_stime.tv_sec + 1e-6 * usage.ru_stime.tv_usec;
      }

      /// Sum of a column over the rows of a statistics table (rank 0 reads).
      double
      sum_statistics_column(const std::string &filename,
                            const std::string &column)
      {
        std::ifstream  in(filename);
        const auto     names = io::StatisticsFile::read_column_names(in);
        const auto     found = std::find(names.begin(), names.end(), column);
        if (found == names.end())
          return 0;
        const int   index = found - names.begin();
        std::string line;
        double      sum = 0;
        while (std::getline(in, line))
          {
            std::istringstream row(line);
            double             value = 0;
            for (int k = 0; k <= index && row >> value; ++k)
              ;
            if (row)
              sum += value;
          }
        return sum;
      }
    } // namespace


    double
    observed_order(const double h_coarse,
                   const double h_medium,
                   const double h_fine,
                   const double q_coarse,
                   const double q_medium,
                   const double q_fine)
    {
      // Celik et al., J. Fluids Eng. 130 (2008) 078001: with e21 = q2 - q1,
      // e32 = q3 - q2 (1 fine, 3 coarse) and ratios r21, r32, solve
      // p = |ln|e32/e21| + ln((r21^p - s)/(r32^p - s))| / ln r21.
      const double e21 = q_medium - q_fine;
      const double e32 = q_coarse - q_medium;
      const double r21 = h_medium / h_fine;
      const double r32 = h_coarse / h_medium;
      if (e21 == 0 || e32 == 0 || !(r21 > 1) || !(r32 > 1) ||
          (e21 > 0) != (e32 > 0))
        return not_defined;
      double p = std::abs(std::log(std::abs(e32 / e21))) / std::log(r21);
      for (unsigned int it = 0; it < 200; ++it)
        {
          const double q =
            std::log((std::pow(r21, p) - 1) / (std::pow(r32, p) - 1));
          const double next =
            std::abs(std::log(std::abs(e32 / e21)) + q) / std::log(r21);
          if (!std::isfinite(next))
            return not_defined;
          if (std::abs(next - p) < 1e-12 * std::max(1., p))
            return next;
          p = next;
        }
      return p;
    }


    template <int dim>
    ConvergenceStudy<dim>::ConvergenceStudy(const core::Parameters<dim> &parameters,
                                            const MPI_Comm         comm)
        : parameters(parameters)
        , mpi_communicator(comm)
        , pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
    {}


    template <int dim>
    void
    ConvergenceStudy<dim>::check_scene() const
    {
      using Knob     = core::ConvergenceStudyParameters::Knob;
      const auto &cs = parameters.convergence_study;
      AssertThrow(cs.knob != Knob::none, ExcInternalError());
      if (parameters.simulation_control.mode ==
          core::SimulationControl::Mode::granular)
        base::throw_invalid_parameter("convergence study/knob",
                                      cs.knob_name(),
                                      "convergence studies run fluid scenes; "
                                      "simulation control/mode = granular has "
                                      "no fluid (set knob = none)");
      if (cs.knob == Knob::cells_per_diameter &&
          parameters.grains.source == dem::GrainParameters<dim>::Source::none)
        base::throw_invalid_parameter("convergence study/knob",
                                      cs.knob_name(),
                                      "the scene has no grains to resolve; use "
                                      "global refinements");
    }


    template <int dim>
    core::Parameters<dim>
    ConvergenceStudy<dim>::parameters_of_run(const unsigned int k,
                                             const double       v) const
    {
      using Knob                           = core::ConvergenceStudyParameters::Knob;
      core::Parameters<dim> run_parameters = parameters;
      switch (parameters.convergence_study.knob)
        {
          case Knob::cells_per_diameter:
            run_parameters.mesh.cells_per_diameter = v;
            break;
          case Knob::global_refinements:
            run_parameters.mesh.global_refinements = static_cast<unsigned int>(v);
            break;
          case Knob::theta:
            run_parameters.fluid.theta = v;
            break;
          case Knob::time_step:
            run_parameters.simulation_control.time_step = v;
            break;
          default:
            break;
        }
      run_parameters.output.directory =
        parameters.output.directory + "/run-" + std::to_string(k);
      return run_parameters;
    }


    template <int dim>
    typename ConvergenceStudy<dim>::Run
    ConvergenceStudy<dim>::measure_run(const core::Parameters<dim> &run_parameters,
                                       const double                 v)
    {
      const auto  &cs        = parameters.convergence_study;
      const double cpu_start = process_cpu_time();
      Timer        clock(mpi_communicator, true);
      std::map<std::string, double> results =
        run_scene(run_parameters, mpi_communicator);
      clock.stop();
      const double wall_time =
        Utilities::MPI::max(clock.wall_time(), mpi_communicator);
      // CPU time is what a run costs on a shared machine, where the wall
      // time also counts the other jobs' share of the cores.
      const double cpu_time =
        Utilities::MPI::sum(process_cpu_time() - cpu_start, mpi_communicator);

      Run r;
      r.value      = v;
      r.h          = knob_size(cs.knob, v);
      const auto q = results.find(cs.quantity);
      if (q == results.end())
        {
          std::string names;
          for (const auto &[name, value] : results)
            names += (names.empty() ? "" : ", ") + name;
          base::throw_invalid_parameter("convergence study/quantity",
                                        cs.quantity,
                                        "not a statistics column of this "
                                        "scene; its columns are: " +
                                          names);
        }
      r.quantity        = q->second;
      r.cells           = static_cast<unsigned int>(results["cells"]);
      r.dofs            = static_cast<unsigned int>(results["dofs"]);
      r.wall_time       = wall_time;
      r.cpu_time        = cpu_time;
      double iterations = 0;
      if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
        iterations = sum_statistics_column(run_parameters.output.directory +
                                             "/statistics.txt",
                                           "total_linear_iterations");
      r.fgmres_iterations = static_cast<unsigned int>(
        std::round(Utilities::MPI::broadcast(mpi_communicator, iterations, 0)));
      Utilities::System::MemoryStats memory;
      Utilities::System::get_memory_stats(memory);
      r.peak_memory = Utilities::MPI::sum(memory.VmHWM / 1024., mpi_communicator);
      return r;
    }


    template <int dim>
    void
    ConvergenceStudy<dim>::run()
    {
      check_scene();
      const auto &cs = parameters.convergence_study;
      // Coarse to fine.
      std::vector<double> values = cs.values;
      std::sort(values.begin(), values.end(), [&](double a, double b) {
        return knob_size(cs.knob, a) > knob_size(cs.knob, b);
      });
      make_output_directory(parameters.output.directory, mpi_communicator);

      study_runs.clear();
      bool memory_per_run = true;
      for (unsigned int k = 0; k < values.size(); ++k)
        {
          const double v = values[k];
          pcout << "Convergence study: run " << k + 1 << " of " << values.size()
                << ", " << cs.knob_name() << " = " << v << std::endl;
          memory_per_run = Utilities::MPI::min(reset_peak_memory() ? 1 : 0,
                                               mpi_communicator) == 1 &&
                           memory_per_run;
          MPI_Barrier(mpi_communicator);
          const Run r = measure_run(parameters_of_run(k, v), v);
          study_runs.push_back(r);
          // The tables so far: a long study that stops (time limit, memory)
          // keeps its finished runs.
          if (study_runs.size() >= 2 && k + 1 < values.size())
            {
              evaluate();
              fill_table();
              write_tables(false);
            }
          pcout << "Convergence study: " << cs.knob_name() << " = " << v << ": "
                << cs.quantity << " = " << std::setprecision(10) << r.quantity
                << std::setprecision(6) << ", " << r.cells << " cells, "
                << r.dofs << " DoFs, " << r.fgmres_iterations
                << " FGMRES iterations, " << r.wall_time << " s wall, "
                << r.cpu_time << " s CPU, " << r.peak_memory << " MB"
                << std::endl;
        }
      if (!memory_per_run)
        pcout << "Convergence study: the peak memory could not be reset "
                 "between runs (/proc/self/clear_refs): each value is the "
                 "largest so far."
              << std::endl;

      evaluate();
      fill_table();
      write_tables(true);
    }


    template <int dim>
    void
    ConvergenceStudy<dim>::evaluate()
    {
      const auto  &cs     = parameters.convergence_study;
      auto        &r      = study_runs;
      const double finest = r.back().quantity;
      for (unsigned int i = 0; i < r.size(); ++i)
        {
          r[i].change_against_finest =
            finest != 0 ? (r[i].quantity - finest) / std::abs(finest) :
                          r[i].quantity - finest;
          r[i].observed_order      = not_defined;
          r[i].richardson_estimate = not_defined;
          r[i].richardson_error    = not_defined;
          if (i >= 2)
            r[i].observed_order = observed_order(r[i - 2].h,
                                                 r[i - 1].h,
                                                 r[i].h,
                                                 r[i - 2].quantity,
                                                 r[i - 1].quantity,
                                                 r[i].quantity);
          const double p =
            cs.richardson_order > 0 ? cs.richardson_order : r[i].observed_order;
          if (i >= 1 && std::isfinite(p) && p > 0)
            {
              // Q_exact ~ Q_i + (Q_i - Q_{i-1}) / (r^p - 1), r = h_{i-1}/h_i.
              const double ratio = std::pow(r[i - 1].h / r[i].h, p);
              r[i].richardson_estimate =
                r[i].quantity +
                (r[i].quantity - r[i - 1].quantity) / (ratio - 1);
              r[i].richardson_error =
                r[i].richardson_estimate != 0 ?
                  std::abs(r[i].quantity - r[i].richardson_estimate) /
                    std::abs(r[i].richardson_estimate) :
                  not_defined;
            }
        }
    }


    template <int dim>
    bool
    ConvergenceStudy<dim>::monotone() const
    {
      for (unsigned int i = 1; i + 1 < study_runs.size(); ++i)
        if (!(std::abs(study_runs[i].change_against_finest) <
              std::abs(study_runs[i - 1].change_against_finest)))
          return false;
      return true;
    }


    template <int dim>
    void
    ConvergenceStudy<dim>::fill_table()
    {
      const auto       &cs   = parameters.convergence_study;
      const std::string knob = knob_column(cs.knob);
      const std::string q    = cs.quantity;
      convergence_table      = ConvergenceTable();
      const auto add_or_dash = [&](const std::string &key, const double v) {
        if (std::isfinite(v))
          convergence_table.add_value(key, v);
        else
          convergence_table.add_value(key, std::string("-"));
      };
      for (const auto &r : study_runs)
        {
          if (cs.knob == core::ConvergenceStudyParameters::Knob::global_refinements)
            convergence_table.add_value(knob,
                                        static_cast<unsigned int>(r.value));
          else
            convergence_table.add_value(knob, r.value);
          convergence_table.add_value("cells", r.cells);
          convergence_table.add_value("dofs", r.dofs);
          convergence_table.add_value(q, r.quantity);
          convergence_table.add_value("change", r.change_against_finest);
          add_or_dash("order", r.observed_order);
          add_or_dash("richardson", r.richardson_estimate);
          add_or_dash("richardson_error", r.richardson_error);
          if (cs.has_reference)
            {
              // Relative error (absolute if the reference is 0) and its
              // order in an effective mesh size h = DoFs^(-1/dim):
              // dim ln(e_{i-1} / e_i) / ln(n_i / n_{i-1}).
              const auto error = [&](const Run &run) {
                return cs.reference_value != 0 ?
                         std::abs(run.quantity - cs.reference_value) /
                           std::abs(cs.reference_value) :
                         std::abs(run.quantity);
              };
              convergence_table.add_value("error", error(r));
              const std::size_t i             = &r - study_runs.data();
              double            order_in_dofs = not_defined;
              if (i > 0 && r.dofs != study_runs[i - 1].dofs && error(r) > 0 &&
                  error(study_runs[i - 1]) > 0)
                order_in_dofs =
                  dim * std::log(error(study_runs[i - 1]) / error(r)) /
                  std::log(double(r.dofs) / study_runs[i - 1].dofs);
              add_or_dash("order_dofs", order_in_dofs);
            }
          convergence_table.add_value("fgmres", r.fgmres_iterations);
          convergence_table.add_value("wall_s", r.wall_time);
          convergence_table.add_value("cpu_s", r.cpu_time);
          convergence_table.add_value("memory_MB", r.peak_memory);
        }
      convergence_table.set_scientific(
        knob, cs.knob != core::ConvergenceStudyParameters::Knob::cells_per_diameter);
      convergence_table.set_precision(knob, 3);
      convergence_table.set_scientific(q, true);
      convergence_table.set_precision(q, 8);
      for (const char *key : {"change", "richardson_error"})
        {
          convergence_table.set_scientific(key, true);
          convergence_table.set_precision(key, 3);
        }
      convergence_table.set_scientific("richardson", true);
      convergence_table.set_precision("richardson", 8);
      convergence_table.set_precision("order", 2);
      convergence_table.set_precision("wall_s", 1);
      convergence_table.set_precision("cpu_s", 1);
      convergence_table.set_precision("memory_MB", 0);
      convergence_table.set_tex_caption(knob, cs.knob_name());
      convergence_table.set_tex_caption("change", "change vs finest");
      convergence_table.set_tex_caption("richardson_error",
                                        "distance to Richardson");
      convergence_table.set_tex_caption("wall_s", "wall time [s]");
      convergence_table.set_tex_caption("cpu_s", "CPU time [s]");
      convergence_table.set_tex_caption("memory_MB", "peak memory [MB]");
      convergence_table.set_tex_caption("fgmres", "FGMRES iterations");
      if (cs.has_reference)
        {
          convergence_table.set_scientific("error", true);
          convergence_table.set_precision("error", 3);
          convergence_table.set_precision("order_dofs", 2);
          convergence_table.set_tex_caption("error", "error vs reference");
          convergence_table.set_tex_caption("order_dofs", "order in DoFs");
        }
      // LaTeX needs the underscores of statistics names escaped.
      std::string tex_quantity;
      for (const char c : q)
        tex_quantity += (c == '_') ? std::string("\\_") : std::string(1, c);
      convergence_table.set_tex_caption(q, tex_quantity);
    }


    template <int dim>
    void
    ConvergenceStudy<dim>::write_tables(const bool final) const
    {
      const auto        &cs = parameters.convergence_study;
      std::ostringstream text, org, tex;
      convergence_table.write_text(text, TableHandler::table_with_headers);
      convergence_table.write_text(org, TableHandler::org_mode_table);
      convergence_table.write_tex(tex);

      // Markdown: org mode's table plus the separator under the header.
      std::istringstream org_lines(org.str());
      std::ostringstream markdown;
      std::string        line;
      bool               header = true;
      while (std::getline(org_lines, line))
        {
          markdown << line << '\n';
          if (header)
            {
              const auto n = std::count(line.begin(), line.end(), '|');
              for (long c = 0; c + 1 < n; ++c)
                markdown << "|---";
              markdown << "|\n";
              header = false;
            }
        }

      std::ostringstream summary;
      const auto        &last = study_runs.back();
      summary << "Knob: " << cs.knob_name() << ", quantity: " << cs.quantity
              << ", " << study_runs.size() << " runs. Change against the "
              << "finest run decreases monotonically: "
              << (monotone() ? "yes" : "no") << ".";
      if (std::isfinite(last.observed_order))
        summary << " Observed order of the finest three runs: "
                << std::setprecision(3) << last.observed_order << ".";
      if (std::isfinite(last.richardson_estimate))
        summary << " Richardson estimate: " << std::setprecision(8)
                << last.richardson_estimate << "; the finest run is within "
                << std::setprecision(3) << last.richardson_error << " of it.";
      summary << '\n';

      if (final)
        pcout << "\nConvergence table (" << cs.knob_name() << "):\n"
              << text.str() << summary.str() << std::endl;
      if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
        {
          const std::string base =
            parameters.output.directory + "/" + cs.table_name;
          std::ofstream(base + ".txt") << text.str();
          std::ofstream(base + ".md") << markdown.str() << '\n'
                                      << summary.str();
          std::ofstream(base + ".tex") << tex.str();
        }
    }

    template class ConvergenceStudy<2>;
    template class ConvergenceStudy<3>;
  } // namespace drivers
} // namespace softsand
