#include <deal.II/base/exceptions.h>

#include <softsand/io/statistics_file.h>

#include <iomanip>

namespace softsand
{
  namespace io
  {
    using namespace dealii;

    StatisticsFile::StatisticsFile(const std::string &filename,
                                   const MPI_Comm     comm)
      : is_writer(Utilities::MPI::this_mpi_process(comm) == 0)
      , filename(filename)
    {
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
          for (const auto &entry : row)
            columns.push_back(entry.first);
          if (is_writer)
            {
              file << '#';
              for (const auto &c : columns)
                file << ' ' << c;
              file << '\n';
            }
        }
      AssertThrow(row.size() == columns.size(),
                  ExcMessage("Internal error: statistics row with a "
                             "different set of columns."));
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
