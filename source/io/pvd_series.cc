#include <deal.II/base/data_out_base.h>

#include <softsand/io/pvd_series.h>

#include <cstdio>
#include <fstream>
#include <regex>

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
      counter = 0;
      std::ifstream in(directory + "/" + base_name + ".pvd");
      // deal.II's records: <DataSet timestep="T" group="" part="0"
      // file="BASE_NNNN.pvtu"/>.
      const std::regex record(R"re(timestep="([^"]*)".*file="([^"]*)")re");
      const std::regex number(R"(_([0-9]+)\.[a-z]+$)");
      for (std::string line; std::getline(in, line);)
        {
          std::smatch m;
          if (!std::regex_search(line, m, record))
            continue;
          const double t = std::stod(m[1]);
          if (t > time * (1 + 1e-12) + 1e-300)
            continue;
          const std::string file = m[2];
          records.emplace_back(t, file);
          std::smatch n;
          if (std::regex_search(file, n, number))
            counter = std::max<unsigned int>(counter, std::stoul(n[1]) + 1);
          else
            counter = std::max<unsigned int>(counter, records.size());
        }
    }


    void
    PvdSeries::add(const double       time,
                   const std::string &file,
                   const MPI_Comm     comm)
    {
      records.emplace_back(time, file);
      ++counter;
      if (Utilities::MPI::this_mpi_process(comm) != 0)
        return;
      const std::string pvd = directory + "/" + base_name + ".pvd";
      {
        std::ofstream out(pvd + ".tmp");
        DataOutBase::write_pvd_record(out, records);
      }
      std::rename((pvd + ".tmp").c_str(), pvd.c_str());
    }
  } // namespace io
} // namespace softsand
