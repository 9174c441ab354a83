#include <deal.II/base/exceptions.h>

#include <softsand/io/statistics_file.h>

#include <algorithm>
#include <iomanip>
#include <sstream>

namespace softsand
{
  namespace io
  {
    using namespace dealii;

    StatisticsFile::StatisticsFile(const std::string &filename,
                                   const MPI_Comm     comm,
                                   const long         resume_after_step)
      : is_writer(Utilities::MPI::this_mpi_process(comm) == 0)
      , filename(filename)
    {
      if (resume_after_step >= 0)
        {
          // Every rank learns the columns (write_row checks them).
          std::ifstream in(filename);
          AssertThrow(in.good(),
                      ExcMessage("Cannot continue the statistics file <" +
                                 filename + ">: it does not exist."));
          std::string header;
          std::getline(in, header);
          std::istringstream names(header.substr(header.find('#') + 1));
          for (std::string c; names >> c;)
            columns.push_back(c);
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
              file << header << '\n';
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
              file << '#';
              for (const auto &c : columns)
                file << ' ' << c;
              file << '\n';
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
