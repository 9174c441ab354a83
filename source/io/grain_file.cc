#include <deal.II/base/exceptions.h>

#include <softsand/io/grain_file.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace softsand
{
  namespace io
  {
    using namespace dealii;

    namespace
    {
      template <int dim>
      std::string
      column_names()
      {
        return dim == 2 ? "x y radius [vx vy w]" :
                          "x y z radius [vx vy vz wx wy wz]";
      }
    } // namespace


    template <int dim>
    std::vector<dem::Grain<dim>>
    read_grain_file(const std::string &filename)
    {
      std::ifstream in(filename);
      AssertThrow(in.good(),
                  ExcMessage("Cannot open the grain file <" + filename +
                             ">; check the name of grains/file (relative "
                             "paths start in the working directory)."));

      const unsigned int n_position = dim + 1;               // x, radius
      const unsigned int n_full     = n_position + dim + 3; // + v, omega
      std::vector<dem::Grain<dim>> grains;
      std::string                  line;
      unsigned int                 line_number = 0;
      while (std::getline(in, line))
        {
          ++line_number;
          const auto here = [&]() {
            return "Grain file <" + filename + ">, line " +
                   std::to_string(line_number) + ": ";
          };

          std::istringstream  words(line.substr(0, line.find('#')));
          std::vector<std::string> tokens;
          std::vector<double>      values;
          std::string              word;
          while (words >> word)
            {
              // strtod rather than >>: it tells apart "1.5x" from "1.5".
              char        *end   = nullptr;
              const double value = std::strtod(word.c_str(), &end);
              AssertThrow(end != word.c_str() && *end == '\0',
                          ExcMessage(here() + "<" + word +
                                     "> is not a number."));
              AssertThrow(std::isfinite(value),
                          ExcMessage(here() + "<" + word +
                                     "> is not a finite number."));
              tokens.push_back(word);
              values.push_back(value);
            }
          if (values.empty())
            continue;
          AssertThrow(values.size() == n_position || values.size() == n_full,
                      ExcMessage(here() + "expected " +
                                 std::to_string(n_position) + " or " +
                                 std::to_string(n_full) + " columns (" +
                                 column_names<dim>() + "), found " +
                                 std::to_string(values.size()) + "."));

          dem::Grain<dim> g;
          for (unsigned int d = 0; d < dim; ++d)
            g.center[d] = values[d];
          g.radius = values[dim];
          AssertThrow(g.radius > 0,
                      ExcMessage(here() + "the radius must be > 0 m, got " +
                                 tokens[dim] + "."));
          if (values.size() == n_full)
            {
              for (unsigned int d = 0; d < dim; ++d)
                g.velocity[d] = values[n_position + d];
              if constexpr (dim == 2)
                g.angular_velocity[2] = values[n_position + dim];
              else
                for (unsigned int d = 0; d < 3; ++d)
                  g.angular_velocity[d] = values[n_position + dim + d];
            }
          grains.push_back(g);
        }
      AssertThrow(!in.bad(),
                  ExcMessage("Reading the grain file <" + filename +
                             "> failed after line " +
                             std::to_string(line_number) + "."));
      AssertThrow(!grains.empty(),
                  ExcMessage("The grain file <" + filename +
                             "> holds no grains (expected lines '" +
                             column_names<dim>() +
                             "'); use grains/source = none for a run "
                             "without grains."));
      return grains;
    }


    template <int dim>
    void
    write_grain_file(const std::string                  &filename,
                     const std::vector<dem::Grain<dim>> &grains,
                     const std::string                  &note)
    {
      const std::string tmp = filename + ".tmp";
      {
        std::ofstream out(tmp);
        AssertThrow(out.good(),
                    ExcMessage("Cannot open <" + tmp +
                               "> for writing the grain file."));
        out << "# softsand grains (SI units), " << grains.size()
            << " grains\n# "
            << (dim == 2 ? "x y radius vx vy w" :
                           "x y z radius vx vy vz wx wy wz")
            << '\n';
        if (!note.empty())
          out << "# " << note << '\n';
        out << std::setprecision(17);
        // "+ 0." writes -0 as 0.
        for (const auto &g : grains)
          {
            for (unsigned int d = 0; d < dim; ++d)
              out << g.center[d] + 0. << ' ';
            out << g.radius + 0.;
            for (unsigned int d = 0; d < dim; ++d)
              out << ' ' << g.velocity[d] + 0.;
            if constexpr (dim == 2)
              out << ' ' << g.angular_velocity[2] + 0.;
            else
              for (unsigned int d = 0; d < 3; ++d)
                out << ' ' << g.angular_velocity[d] + 0.;
            out << '\n';
          }
        out.close();
        AssertThrow(!out.fail(),
                    ExcMessage("Writing the grain file <" + tmp +
                               "> failed (disk full?)."));
      }
      if (std::rename(tmp.c_str(), filename.c_str()) != 0)
        {
          const std::string reason = std::strerror(errno);
          std::remove(tmp.c_str());
          AssertThrow(false,
                      ExcMessage("Cannot rename <" + tmp + "> to <" +
                                 filename + ">: " + reason + "."));
        }
    }


    template std::vector<dem::Grain<2>>
    read_grain_file<2>(const std::string &);
    template std::vector<dem::Grain<3>>
    read_grain_file<3>(const std::string &);
    template void
    write_grain_file<2>(const std::string &,
                        const std::vector<dem::Grain<2>> &,
                        const std::string &);
    template void
    write_grain_file<3>(const std::string &,
                        const std::vector<dem::Grain<3>> &,
                        const std::string &);
  } // namespace io
} // namespace softsand
