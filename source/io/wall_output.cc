#include <deal.II/base/data_out_base.h>

#include <softsand/io/wall_output.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>

namespace softsand
{
  namespace io
  {
    WallOutput::WallOutput(const std::string    &directory,
                           const std::string    &base_name,
                           const BoundingBox<3> &domain)
        : directory(directory)
        , base_name(base_name)
        , domain(domain)
        , series(directory, base_name)
    {}


    void
    WallOutput::write(const std::vector<dem::Wall> &walls,
                      const double                  time,
                      const unsigned long           step,
                      const MPI_Comm                comm)
    {
      const std::string vtu =
        base_name + "_" + PvdSeries::file_number(step) + ".vtu";
      if (Utilities::MPI::this_mpi_process(comm) != 0)
        {
          series.add(time, vtu, comm);
          return;
        }

      // Polygons (planes) and quadrilaterals (cylinders), each cell
      // remembering its wall.
      std::vector<Point<3>>                  points;
      std::vector<std::vector<unsigned int>> cells;
      std::vector<unsigned int>              cell_wall;
      for (unsigned int k = 0; k < walls.size(); ++k)
        if (walls[k].shape == dem::Wall::Shape::plane)
          {
            const auto face = dem::plane_wall_face(walls, k, domain);
            if (face.empty())
              continue;
            std::vector<unsigned int> cell;
            for (const auto &p : face)
              {
                cell.push_back(points.size());
                points.push_back(p);
              }
            cells.push_back(cell);
            cell_wall.push_back(k);
          }
        else
          {
            const dem::Wall    &c    = walls[k];
            const Tensor<1, 3> &axis = c.normal;
            Tensor<1, 3>        e1;
            e1[std::abs(axis[0]) < 0.9 ? 0 : 1] = 1;
            e1 -= (e1 * axis) * axis;
            e1 /= e1.norm();
            const Tensor<1, 3> e2     = cross_product_3d(axis, e1);
            const auto [s_min, s_max] = dem::cylinder_axis_range(c, domain);
            const unsigned int first  = points.size();
            for (unsigned int a = 0; a < cylinder_segments; ++a)
              {
                const double       phi = 2 * M_PI * a / cylinder_segments;
                const Tensor<1, 3> radial =
                  c.radius * (std::cos(phi) * e1 + std::sin(phi) * e2);
                points.push_back(c.point + s_min * axis + radial);
                points.push_back(c.point + s_max * axis + radial);
              }
            for (unsigned int a = 0; a < cylinder_segments; ++a)
              {
                const unsigned int b = (a + 1) % cylinder_segments;
                cells.push_back({first + 2 * a,
                                 first + 2 * b,
                                 first + 2 * b + 1,
                                 first + 2 * a + 1});
                cell_wall.push_back(k);
              }
          }

      // VTK XML, ASCII: small, and read by any ParaView.
      const std::string name = directory + "/" + vtu;
      {
        std::ofstream out(name);
        out << std::setprecision(12);
        out << "<?xml version=\"1.0\"?>\n"
               "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
               "byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n"
               "<FieldData>\n<DataArray type=\"Float64\" Name=\"TIME\" "
               "NumberOfTuples=\"1\" format=\"ascii\">"
            << time << "</DataArray>\n</FieldData>\n"
            << "<Piece NumberOfPoints=\"" << points.size()
            << "\" NumberOfCells=\"" << cells.size() << "\">\n"
            << "<Points>\n<DataArray type=\"Float64\" "
               "NumberOfComponents=\"3\" format=\"ascii\">\n";
        for (const auto &p : points)
          out << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
        out << "</DataArray>\n</Points>\n<Cells>\n"
               "<DataArray type=\"Int64\" Name=\"connectivity\" "
               "format=\"ascii\">\n";
        for (const auto &cell : cells)
          {
            for (const auto v : cell)
              out << v << ' ';
            out << '\n';
          }
        out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" "
               "format=\"ascii\">\n";
        std::size_t offset = 0;
        for (const auto &cell : cells)
          out << (offset += cell.size()) << '\n';
        // VTK_POLYGON = 7, VTK_QUAD = 9.
        out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" "
               "format=\"ascii\">\n";
        for (const auto &cell : cells)
          out << (cell.size() == 4 ? 9 : 7) << '\n';
        out << "</DataArray>\n</Cells>\n"
               "<CellData Scalars=\"pressure\" Vectors=\"force\">\n";
        const auto scalar = [&](const std::string &field,
                                const std::string &type,
                                const auto        &value) {
          out << "<DataArray type=\"" << type << "\" Name=\"" << field
              << "\" format=\"ascii\">\n";
          for (const auto k : cell_wall)
            out << value(walls[k], k) << '\n';
          out << "</DataArray>\n";
        };
        const auto vector = [&](const std::string &field, const auto &value) {
          out << "<DataArray type=\"Float64\" Name=\"" << field
              << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
          for (const auto k : cell_wall)
            {
              const Tensor<1, 3> t = value(walls[k]);
              out << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
            }
          out << "</DataArray>\n";
        };
        scalar("wall_index", "Int32", [](const dem::Wall &, unsigned int k) {
          return k;
        });
        scalar("pressure", "Float64", [](const dem::Wall &w, unsigned int) {
          return w.pressure() + 0.;
        });
        scalar("normal_force", "Float64", [](const dem::Wall &w, unsigned int) {
          // + 0.: no -0 in the file.
          return (w.shape == dem::Wall::Shape::plane ? -(w.force * w.normal) :
                                                       w.normal_force) +
                 0.;
        });
        scalar("target_pressure",
               "Float64",
               [](const dem::Wall &w, unsigned int) {
                 return w.motion == dem::Wall::Motion::servo ?
                          w.target_pressure :
                          0.;
               });
        vector("force", [](const dem::Wall &w) { return w.force; });
        vector("velocity", [](const dem::Wall &w) { return w.velocity; });
        out << "</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
      }

      // The series names the file once it is complete.
      series.add(time, vtu, comm);
    }
  } // namespace io
} // namespace softsand
