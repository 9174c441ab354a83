#include <deal.II/base/exceptions.h>

#include <softsand/io/column_units.h>
#include <softsand/io/statistics_file.h>

#include <algorithm>
#include <cctype>
#include <iomanip>
#include <sstream>

namespace softsand
{
  namespace io
  {
    using namespace dealii;

    StatisticsFile::StatisticsFile(const std::string &filename,
                                   const MPI_Comm     comm,
                                   const long         resume_after_step,
                                   const unsigned int dim)
      : is_writer(Utilities::MPI::this_mpi_process(comm) == 0)
      , filename(filename)
      , dim(dim)
    {
      if (resume_after_step >= 0)
        {
          // Every rank learns the columns (write_row checks them).
          std::ifstream in(filename);
          AssertThrow(in.good(),
                      ExcMessage("Cannot continue the statistics file <" +
                                 filename + ">: it does not exist."));
          // The header ('#' lines and the names line) is kept as it was.
          std::vector<std::string> header;
          std::string              text;
          while (in.peek() == '#' || std::isalpha(in.peek()))
            {
              std::string line;
              std::getline(in, line);
              header.push_back(line);
              text += line + '\n';
            }
          std::istringstream header_text(text);
          columns = read_column_names(header_text);
          const auto step_column =
            std::find(columns.begin(), columns.end(), "step") - columns.begin();
          AssertThrow(step_column < long(columns.size()),
                      ExcMessage("The statistics file <" + filename +
                                 "> has no step column to continue after."));
          std::vector<std::string> kept;
          for (std::string line; std::getline(in, line);)
            {
              std::istringstream values(line);
              double             value = 0;
              for (long k = 0; k <= step_column; ++k)
                values >> value;
              if (values && value <= resume_after_step)
                kept.push_back(line);
            }
          in.close();
          MPI_Barrier(comm);
          if (is_writer)
            {
              file.open(filename);
              for (const auto &line : header)
                file << line << '\n';
              for (const auto &line : kept)
                file << line << '\n';
              file.flush();
            }
          return;
        }
      if (is_writer)
        {
          file.open(filename);
          AssertThrow(file.good(),
                      ExcMessage("Cannot open the statistics file <" +
                                 filename + "> for writing."));
        }
    }


    std::vector<std::string>
    StatisticsFile::read_column_names(std::istream &in)
    {
      // The names line starts with a letter (a row with a digit or a sign).
      // Files of earlier versions name the columns in a '#' line.
      std::string last_comment, line;
      while (in.peek() == '#' && std::getline(in, line))
        last_comment = line;
      std::string names_line;
      if (std::isalpha(in.peek()))
        std::getline(in, names_line);
      else if (!last_comment.empty())
        names_line = last_comment.substr(1);
      std::vector<std::string> names;
      std::istringstream       words(names_line);
      for (std::string c; words >> c;)
        names.push_back(c);
      return names;
    }


    void
    StatisticsFile::add_value(const std::string &column, const double value)
    {
      for (auto &entry : row)
        if (entry.first == column)
          {
            entry.second = value;
            return;
          }
      row.emplace_back(column, value);
    }


    void
    StatisticsFile::write_row()
    {
      if (columns.empty())
        {
          // step, time and wall_time lead every table; the rest keep the
          // order the scene added them in.
          for (const std::string lead : {"step", "time", "wall_time"})
            for (const auto &entry : row)
              if (entry.first == lead)
                columns.push_back(lead);
          for (const auto &entry : row)
            if (std::find(columns.begin(), columns.end(), entry.first) ==
                columns.end())
              columns.push_back(entry.first);
          if (is_writer)
            {
              // The names line first (numpy's genfromtxt(names=True) takes
              // the first line, pandas and gnuplot the first non-comment
              // one), then one comment line per column with its unit.
              for (unsigned int i = 0; i < columns.size(); ++i)
                file << (i == 0 ? "" : " ") << columns[i];
              file << "\n# softsand statistics, " << columns.size()
                   << " columns (SI units of a " << dim << "D scene"
                   << (dim == 2 ? ", per metre of depth" : "")
                   << "; glossary: doc/statistics_columns.md):\n";
              for (unsigned int i = 0; i < columns.size(); ++i)
                file << "# " << i + 1 << ": " << columns[i] << " ("
                     << column_unit(columns[i], dim) << ")\n";
            }
        }
      // Columns fixed by the first row; a quantity that no longer exists
      // (say, the drag once every grain has left the domain) reads 0. A
      // column the first row did not have is an error.
      std::vector<std::pair<std::string, double>> ordered;
      for (const auto &c : columns)
        {
          double value = 0;
          for (const auto &entry : row)
            if (entry.first == c)
              value = entry.second;
          ordered.emplace_back(c, value);
        }
      for (const auto &entry : row)
        AssertThrow(std::find(columns.begin(), columns.end(), entry.first) !=
                      columns.end(),
                    ExcMessage("Internal error: statistics column <" +
                               entry.first +
                               "> appeared after the first row."));
      row = ordered;
      if (is_writer)
        {
          file << std::setprecision(10);
          for (unsigned int i = 0; i < row.size(); ++i)
            file << (i == 0 ? "" : " ") << row[i].second;
          file << std::endl; // flush every row
        }
      row.clear();
    }
  } // namespace io
} // namespace softsand
