// Pack generators and grain files: lattice counts and solid fractions, a
// random pack at a target fraction (non-overlapping, inside the region),
// the truncated normal size distribution, a grain file round trip and the
// messages for broken grain files.

#include <deal.II/base/exceptions.h>

#include <softsand/dem/grain_parameters.h>
#include <softsand/dem/pack_generators.h>
#include <softsand/io/grain_file.h>
#include <softsand/io/scene_grains.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <sstream>

#include "tests.h"

using namespace softsand;

template <int dim>
double
solid_fraction(const std::vector<dem::Grain<dim>> &grains, const double volume)
{
  double v = 0;
  for (const auto &g : grains)
    v += g.measure();
  return v / volume;
}


template <int dim>
double
min_gap(const std::vector<dem::Grain<dim>> &grains)
{
  double gap = std::numeric_limits<double>::max();
  for (unsigned int i = 0; i < grains.size(); ++i)
    for (unsigned int j = 0; j < i; ++j)
      gap = std::min(gap,
                     grains[i].center.distance(grains[j].center) -
                       grains[i].radius - grains[j].radius);
  return gap;
}


template <int dim>
bool
inside(const std::vector<dem::Grain<dim>> &grains, const double side)
{
  for (const auto &g : grains)
    for (unsigned int d = 0; d < dim; ++d)
      if (g.center[d] - g.radius < 0 || g.center[d] + g.radius > side)
        return false;
  return true;
}


/// The message of a deal.II exception without the file/line decoration.
std::string
message(const ExceptionBase &e)
{
  std::ostringstream s;
  e.print_info(s);
  std::string m = s.str();
  m.erase(0, m.find_first_not_of(" \n"));
  return m.substr(0, m.find('\n'));
}


void
try_reading(const std::string &name, const std::string &content)
{
  {
    std::ofstream f(name);
    f << content;
  }
  try
    {
      io::read_grain_file<3>(name);
      deallog << "no exception for " << name << std::endl;
    }
  catch (const ExceptionBase &e)
    {
      deallog << message(e) << std::endl;
    }
}


int
main()
{
  initlog();
  const double         side = 1e-3;
  const BoundingBox<3> cube(std::make_pair(Point<3>(), Point<3>(side, side, side)));
  const BoundingBox<2> square(std::make_pair(Point<2>(), Point<2>(side, side)));

  {
    const auto grains = dem::simple_cubic_array(cube, 1e-4, 2e-4);
    deallog << "simple cubic: " << grains.size() << " grains, solid fraction "
            << solid_fraction(grains, side * side * side) << std::endl;
    const auto grains_2d = dem::simple_cubic_array(square, 1e-4, 2e-4);
    deallog << "simple cubic 2D: " << grains_2d.size() << " grains"
            << std::endl;
  }

  {
    const auto grains = dem::bcc_array(cube, 1e-4, 2e-4);
    deallog << "bcc: " << grains.size() << " grains, min gap >= 0: "
            << (min_gap(grains) >= 0 ? "yes" : "no") << std::endl;
    dem::check_grains(grains, cube, "bcc");
  }

  {
    const auto grains = dem::random_pack(
      cube, dem::SizeDistribution::constant(1e-4), 0.3, 1, 100000);
    const double f = solid_fraction(grains, side * side * side);
    deallog << "random pack: " << grains.size() << " grains, solid fraction "
            << f << " (>= 0.3: " << (f >= 0.3 ? "yes" : "no")
            << "), min gap >= 0: " << (min_gap(grains) >= 0 ? "yes" : "no")
            << ", inside: " << (inside(grains, side) ? "yes" : "no")
            << std::endl;
    dem::check_grains(grains, cube, "random pack");

    const auto again = dem::random_pack(
      cube, dem::SizeDistribution::constant(1e-4), 0.3, 1, 100000);
    bool same = again.size() == grains.size();
    for (unsigned int i = 0; same && i < grains.size(); ++i)
      same = again[i].center == grains[i].center;
    deallog << "same seed, same pack: " << (same ? "yes" : "no") << std::endl;
  }

  {
    const auto grains = dem::random_pack(
      square,
      dem::SizeDistribution::uniform(0.5e-4, 1.5e-4),
      0.4,
      2,
      100000);
    const double f = solid_fraction(grains, side * side);
    deallog << "random pack 2D: solid fraction >= 0.4: "
            << (f >= 0.4 ? "yes" : "no")
            << ", min gap >= 0: " << (min_gap(grains) >= 0 ? "yes" : "no")
            << ", inside: " << (inside(grains, side) ? "yes" : "no")
            << std::endl;
  }

  try
    {
      dem::random_pack(
        cube, dem::SizeDistribution::constant(1e-4), 0.6, 1, 1000);
      deallog << "no exception for a jammed pack" << std::endl;
    }
  catch (const ExceptionBase &e)
    {
      deallog << message(e) << std::endl;
    }

  {
    const auto   d = dem::SizeDistribution::truncated_normal(1.35e-3,
                                                           0.3e-3,
                                                           0.9e-3,
                                                           1.8e-3);
    std::mt19937 rng(1);
    double       sum = 0, lo = 1, hi = 0;
    for (unsigned int i = 0; i < 10000; ++i)
      {
        const double x = d.draw(rng);
        sum += x;
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
    deallog << "truncated normal: mean * 1e3 = " << std::setprecision(3)
            << sum / 10000 * 1e3 << ", in range: "
            << (lo >= 0.9e-3 && hi <= 1.8e-3 ? "yes" : "no") << std::endl;
    deallog.precision(6);
  }

  try
    {
      dem::SizeDistribution::uniform(2e-4, 1e-4);
    }
  catch (const ExceptionBase &e)
    {
      deallog << message(e) << std::endl;
    }
  try
    {
      dem::simple_cubic_array(cube, 1e-4, 0.5e-4);
    }
  catch (const ExceptionBase &e)
    {
      deallog << message(e) << std::endl;
    }

  {
    std::vector<dem::Grain<3>> grains(3);
    for (unsigned int i = 0; i < 3; ++i)
      {
        grains[i].center = Point<3>(0.1 * i + 1. / 3, 0.2, 0.3 + i);
        grains[i].radius = 0.01 + i * 1e-17 + 1. / 7;
        grains[i].velocity[0]         = -1. / 3 * i;
        grains[i].angular_velocity[2] = 2. / 3 + i;
      }
    io::write_grain_file("grains.txt", grains);
    const auto read = io::read_grain_file<3>("grains.txt");
    bool       same = read.size() == grains.size();
    for (unsigned int i = 0; same && i < grains.size(); ++i)
      same = read[i].center == grains[i].center &&
             read[i].radius == grains[i].radius &&
             read[i].velocity == grains[i].velocity &&
             read[i].angular_velocity == grains[i].angular_velocity;
    deallog << "round trip of " << read.size()
            << " grains exact: " << (same ? "yes" : "no") << std::endl;
  }

  try_reading("bad_radius.txt", "# x y z r\n0 0 0 1e-4\n\n1 0 0 -1\n");
  try_reading("bad_columns.txt", "0 0 1e-4\n");
  try_reading("bad_number.txt", "0 0 0 1.5x  # radius typo\n");
  try_reading("bad_nan.txt", "0 nan 0 1\n");
  try_reading("empty.txt", "# no grains\n\n");
  try
    {
      io::read_grain_file<3>("missing.txt_does_not_exist");
    }
  catch (const ExceptionBase &e)
    {
      deallog << message(e) << std::endl;
    }

  try
    {
      std::vector<dem::Grain<3>> grains(1);
      grains[0].radius    = 1e-4;
      grains[0].center[2] = 2e-3;
      dem::check_grains(grains, cube, "grains/list");
    }
  catch (const ExceptionBase &e)
    {
      deallog << message(e) << std::endl;
    }
  try
    {
      std::vector<dem::Grain<2>> grains(2);
      grains[0].radius    = grains[1].radius = 1e-4;
      grains[1].center[0] = 1.5e-4;
      dem::check_grains(grains, square, "grains/list");
    }
  catch (const ExceptionBase &e)
    {
      deallog << message(e) << std::endl;
    }

  // The same generators through the "grains" parameters.
  for (const std::string source : {"random", "bcc", "file"})
    {
      ParameterHandler prm;
      dem::GrainParameters<3>::declare_parameters(prm);
      prm.enter_subsection("grains");
      prm.set("source", source);
      prm.set("file", "grains.txt");
      prm.set("size distribution", "truncated normal");
      prm.set("mean diameter", "1e-4");
      prm.set("diameter standard deviation", "2e-5");
      prm.set("min diameter", "5e-5");
      prm.set("max diameter", "1.5e-4");
      prm.set("velocity", "0, 0, -0.01");
      prm.leave_subsection();
      dem::GrainParameters<3> parameters;
      parameters.parse_parameters(prm);
      // The file's grains (written above) lie in (0,0,0)-(1,1,3) m; loaded
      // packs are checked against the domain.
      const BoundingBox<3> file_domain(
        std::make_pair(Point<3>(), Point<3>(1, 1, 3)));
      const auto grains = io::create_scene_grains(
        parameters, source == "file" ? file_domain : cube);
      deallog << "create_grains, source = " << source << ": " << grains.size()
              << " grains, first velocity " << grains[0].velocity
              << std::endl;
    }
}
