#include <deal.II/base/data_out_base.h>

#include <softsand/io/pvd_series.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <regex>
#include <string>

namespace softsand
{
  namespace io
  {
    using namespace dealii;

    PvdSeries::PvdSeries(const std::string &directory,
                         const std::string &base_name)
      : directory(directory)
      , base_name(base_name)
    {}


    void
    PvdSeries::resume(const double time)
    {
      records.clear();
      std::ifstream in(directory + "/" + base_name + ".pvd");
      // deal.II's records: <DataSet timestep="T" group="" part="0"
      // file="BASE_NNNN.pvtu"/>.
      const std::regex record(R"re(timestep="([^"]*)".*file="([^"]*)")re");
      for (std::string line; std::getline(in, line);)
        {
          std::smatch m;
          if (!std::regex_search(line, m, record))
            continue;
          const double t = std::stod(m[1]);
          if (t > time * (1 + 1e-12) + 1e-300)
            continue;
          records.emplace_back(t, m[2]);
        }
    }


    void
    PvdSeries::add(const double       time,
                   const std::string &file,
                   const MPI_Comm     comm)
    {
      if (!records.empty() && records.back().second == file)
        records.back().first = time;
      else
        records.emplace_back(time, file);
      if (Utilities::MPI::this_mpi_process(comm) != 0)
        return;
      const std::string pvd = directory + "/" + base_name + ".pvd";
      {
        std::ofstream out(pvd + ".tmp");
        DataOutBase::write_pvd_record(out, records);
      }
      std::rename((pvd + ".tmp").c_str(), pvd.c_str());
    }


    unsigned int
    PvdSeries::n_digits(const unsigned long step)
    {
      return std::max<std::size_t>(5, std::to_string(step).size());
    }


    std::string
    PvdSeries::file_number(const unsigned long step)
    {
      const std::string digits = std::to_string(step);
      return std::string(n_digits(step) - digits.size(), '0') + digits;
    }
  } // namespace io
} // namespace softsand
