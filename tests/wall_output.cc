// Walls as geometry for ParaView (dem::plane_wall_face, io::WallOutput):
// an octagon of pistons (inradius R = 0.8 mm) between the plates z- and z+
// of a 2 x 2 x 0.12 mm box, and a cylinder along (1, 1, 0)/sqrt(2).
// Each piston is drawn as the rectangle side x height with side
// 2 R tan(pi/8); each plate as the octagon, of area 8 R^2 tan(pi/8); moving
// a piston in by d lengthens it by 2 d / tan(pi/4) (its ends slide along the
// neighbours, 45 degrees away) and shortens each neighbour by d / sin(pi/4).
// The cylinder spans the box's extent
// along its axis. The VTU written has those cells and the cell data
// ParaView needs.

#include <softsand/dem/walls.h>
#include <softsand/io/wall_output.h>

#include "tests.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace softsand;

namespace
{
  double
  polygon_area(const std::vector<Point<3>> &p)
  {
    Tensor<1, 3> twice;
    for (unsigned int a = 1; a + 1 < p.size(); ++a)
      twice += cross_product_3d(p[a] - p[0], p[a + 1] - p[0]);
    return 0.5 * twice.norm();
  }

  /// Largest edge length in the xy plane (the side of a piston's face).
  double
  side(const std::vector<Point<3>> &p)
  {
    double longest = 0;
    for (unsigned int a = 0; a < p.size(); ++a)
      {
        const Tensor<1, 3> e = p[(a + 1) % p.size()] - p[a];
        longest              = std::max(longest, std::hypot(e[0], e[1]));
      }
    return longest;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  const double         R = 0.8e-3, h = 0.12e-3, L = 1e-3;
  const BoundingBox<3> domain(
    std::make_pair(Point<3>(-L, -L, 0), Point<3>(L, L, h)));
  dem::WallParameters p;
  p.box_faces                  = "z-, z+";
  p.octagon                    = {0, 0, R};
  p.list                       = "cylinder 0 0 0 1 1 0 2e-4";
  std::vector<dem::Wall> walls = dem::create_walls(p, domain);

  const double side_0       = 2 * R * std::tan(M_PI / 8);
  double       worst_piston = 0, worst_plate = 0;
  unsigned int piston_vertices = 0, plate_vertices = 0;
  for (unsigned int k = 0; k < walls.size(); ++k)
    {
      if (walls[k].shape != dem::Wall::Shape::plane)
        continue;
      const auto face = dem::plane_wall_face(walls, k, domain);
      if (walls[k].name.find("piston") == 0)
        {
          piston_vertices =
            std::max<unsigned int>(piston_vertices, face.size());
          worst_piston =
            std::max(worst_piston,
                     std::abs(polygon_area(face) / (side_0 * h) - 1) +
                       std::abs(side(face) / side_0 - 1));
        }
      else
        {
          plate_vertices = std::max<unsigned int>(plate_vertices, face.size());
          worst_plate    = std::max(worst_plate,
                                 std::abs(polygon_area(face) /
                                            (8 * R * R * std::tan(M_PI / 8)) -
                                          1));
        }
    }
  deallog << "pistons: " << piston_vertices
          << " vertices, side x height within 1e-12: "
          << (worst_piston < 1e-12 ? "yes" : "NO") << std::endl;
  deallog << "plates: " << plate_vertices
          << " vertices, octagon area within 1e-12: "
          << (worst_plate < 1e-12 ? "yes" : "NO") << std::endl;

  // Piston 0 (walls[2]) moves in by d.
  {
    const double d = 0.1 * R;
    walls[2].point += d * walls[2].normal;
    const double expected_0 = side_0 + 2 * d / std::tan(M_PI / 4);
    const double expected_1 = side_0 - d / std::sin(M_PI / 4);
    double       worst      = 0;
    for (unsigned int k = 0; k < 8; ++k)
      {
        const double expected = (k == 0             ? expected_0 :
                                 (k == 1 || k == 7) ? expected_1 :
                                                      side_0);
        worst =
          std::max(worst,
                   std::abs(side(dem::plane_wall_face(walls, 2 + k, domain)) /
                              expected -
                            1));
      }
    deallog << "piston 0 moved in by R/10: the 8 sides within 1e-12: "
            << (worst < 1e-12 ? "yes" : "NO") << std::endl;
    walls[2].point -= d * walls[2].normal;
  }

  const dem::Wall &cylinder = walls.back();
  const auto [s_min, s_max] = dem::cylinder_axis_range(cylinder, domain);
  // Box corners projected on (1, 1, 0)/sqrt(2): +-2 L / sqrt(2).
  deallog << "cylinder: axis range / (2 sqrt(2) L) = " << std::setprecision(9)
          << (s_max - s_min) / (2 * std::sqrt(2.) * L)
          << ", area / (2 pi r range) = "
          << cylinder.area / (2 * M_PI * 2e-4 * (s_max - s_min))
          << std::setprecision(6) << std::endl;

  // Written file: one polygon per plane, the cylinder's quadrilaterals.
  walls[2].force        = Tensor<1, 3>({0.5, 0, 0});
  walls[2].normal_force = 0.5;
  std::filesystem::create_directories("results");
  io::WallOutput output("results", "walls", domain);
  // Files by step: step 0, step 1 (written twice, as a run's last output
  // step is: one record), and a DEM step past five digits.
  output.write(walls, 0, 0, MPI_COMM_WORLD);
  output.write(walls, 1e-3, 1, MPI_COMM_WORLD);
  output.write(walls, 1e-3, 1, MPI_COMM_WORLD);
  output.write(walls, 2e-3, 123456, MPI_COMM_WORLD);
  std::ifstream     in("results/walls_00001.vtu");
  std::stringstream text;
  text << in.rdbuf();
  const std::string vtu       = text.str();
  const auto        attribute = [&](const std::string &name) {
    const auto at = vtu.find(name + "=\"");
    return vtu.substr(at + name.size() + 2,
                      vtu.find('"', at + name.size() + 2) - at - name.size() -
                        2);
  };
  deallog << "VTU: points " << attribute("NumberOfPoints") << ", cells "
          << attribute("NumberOfCells") << " (8 x 4 + 2 x 8 + 2 x "
          << io::WallOutput::cylinder_segments << " points, 10 + "
          << io::WallOutput::cylinder_segments << " cells)" << std::endl;
  for (const std::string field : {"wall_index",
                                  "pressure",
                                  "normal_force",
                                  "target_pressure",
                                  "force",
                                  "velocity"})
    deallog << "VTU cell data " << field << ": "
            << (vtu.find("Name=\"" + field + "\"") != std::string::npos ?
                  "yes" :
                  "NO")
            << std::endl;
  std::ifstream     pvd_in("results/walls.pvd");
  std::stringstream pvd;
  pvd << pvd_in.rdbuf();
  std::size_t n_records = 0;
  for (auto at = pvd.str().find("<DataSet"); at != std::string::npos;
       at      = pvd.str().find("<DataSet", at + 1))
    ++n_records;
  deallog << "PVD lists walls_00000.vtu, walls_00001.vtu, walls_123456.vtu: "
          << (pvd.str().find("walls_00000.vtu") != std::string::npos &&
                  pvd.str().find("walls_00001.vtu") != std::string::npos &&
                  pvd.str().find("walls_123456.vtu") != std::string::npos ?
                "yes" :
                "NO")
          << ", records: " << n_records << std::endl;
}
