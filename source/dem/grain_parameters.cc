#include <softsand/base/parameter_tools.h>
#include <softsand/dem/grain_parameters.h>

#include <deal.II/base/utilities.h>

namespace softsand
{
  namespace dem
  {
    template <int dim>
    void
    GrainParameters<dim>::declare_parameters(ParameterHandler &prm)
    {
      const std::string zero = (dim == 2 ? "0, 0" : "0, 0, 0");
      prm.enter_subsection("grains");
      prm.declare_entry("source",
                        "none",
                        Patterns::Selection(
                          "none|list|file|simple cubic|bcc|random"),
                        "Where the grains come from.");
      prm.declare_entry("list",
                        "",
                        Patterns::Anything(),
                        "source = list: grains separated by ';', each "
                        "'x, y, [z,] radius' (m).");
      prm.declare_entry("file",
                        "",
                        Patterns::Anything(),
                        "source = file: pack file, one grain per line "
                        "'x y [z] radius [vx vy [vz] [wx wy] wz]' (SI); "
                        "relative paths are taken from the working "
                        "directory.");
      prm.declare_entry("file velocities",
                        "read",
                        Patterns::Selection("read|zero"),
                        "source = file: read: the grains start with the "
                        "file's velocities; zero: at rest (a settled pack "
                        "written by the DEM still carries small rattler "
                        "velocities, up to 1e-4 m/s in the Fig. 5 packs, "
                        "which a static pack's steady solve would impose on "
                        "the fluid).");
      prm.declare_entry("diameter",
                        "1e-4",
                        Patterns::Double(0),
                        "Grain diameter of lattices and of the constant "
                        "size distribution (m).");
      prm.declare_entry("lattice spacing",
                        "2e-4",
                        Patterns::Double(0),
                        "Simple cubic: centre distance; bcc: cube edge (m).");
      base::declare_double_list(prm,
                                "region lower corner",
                                "",
                                "Lower corner of the region filled by "
                                "lattices and random packs (m); empty: the "
                                "domain.");
      base::declare_double_list(prm,
                                "region upper corner",
                                "",
                                "Upper corner of that region (m).");
      prm.declare_entry("solid fraction",
                        "0.3",
                        Patterns::Double(0, 0.74),
                        "source = random: target solid volume fraction.");
      prm.declare_entry("count",
                        "0",
                        Patterns::Integer(0),
                        "source = random: number of grains to insert (0: "
                        "fill to the solid fraction).");
      prm.declare_entry("max overlap ratio",
                        "0.3",
                        Patterns::Double(0),
                        "Largest overlap delta / R* accepted between two "
                        "grains of a file or list, and between a grain and "
                        "a wall at the start of a DEM or coupled scene "
                        "(there R* = R): settled DEM packs touch with "
                        "overlaps of a few % of R* (soft grains under load "
                        "up to about 25%).");
      prm.declare_entry("seed",
                        "1",
                        Patterns::Integer(0),
                        "Random seed of the random pack.");
      prm.declare_entry("size distribution",
                        "constant",
                        Patterns::Selection(
                          "constant|uniform|truncated normal|lognormal|discrete"),
                        "Diameter distribution of the random pack.");
      prm.declare_entry("min diameter", "0", Patterns::Double(0), "(m)");
      prm.declare_entry("discrete diameters", "", Patterns::Anything(),
                        "size distribution = discrete: the diameters (m), "
                        "comma-separated.");
      prm.declare_entry("discrete fractions", "", Patterns::Anything(),
                        "Mass fractions of those diameters (normalized).");
      prm.declare_entry("max diameter", "0", Patterns::Double(0), "(m)");
      prm.declare_entry("mean diameter", "0", Patterns::Double(0), "(m)");
      prm.declare_entry("diameter standard deviation",
                        "0",
                        Patterns::Double(0),
                        "(m)");
      base::declare_double_list(prm,
                                "velocity",
                                zero,
                                "Translational velocity given to every grain "
                                "not read from a file with velocities (m/s).");
      base::declare_double_list(prm,
                                "angular velocity",
                                "0, 0, 0",
                                "Angular velocity given to every grain "
                                "(rad/s; 2D uses the z component).");
      prm.leave_subsection();
    }


    template <int dim>
    void
    GrainParameters<dim>::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("grains");
      const std::string s = prm.get("source");
      source = s == "none"         ? Source::none :
               s == "list"         ? Source::list :
               s == "file"         ? Source::file :
               s == "simple cubic" ? Source::simple_cubic :
               s == "bcc"          ? Source::bcc :
                                     Source::random;
      list            = prm.get("list");
      file            = prm.get("file");
      diameter        = prm.get_double("diameter");
      lattice_spacing = prm.get_double("lattice spacing");
      region_is_domain =
        Utilities::trim(prm.get("region lower corner")).empty();
      if (!region_is_domain)
        {
          region_lower = base::get_point<dim>(prm, "region lower corner");
          region_upper = base::get_point<dim>(prm, "region upper corner");
          for (unsigned int d = 0; d < dim; ++d)
            if (!(region_upper[d] > region_lower[d]))
              base::throw_invalid_parameter(
                "grains/region upper corner",
                prm.get("region upper corner"),
                "each coordinate must exceed the lower corner's");
        }
      solid_fraction    = prm.get_double("solid fraction");
      count             = prm.get_integer("count");
      max_overlap_ratio = prm.get_double("max overlap ratio");
      {
        const auto list = [&](const std::string &entry) {
          std::vector<double> values;
          for (const auto &v :
               Utilities::split_string_list(prm.get(entry), ','))
            {
              try
                {
                  values.push_back(std::stod(v));
                }
              catch (...)
                {
                  base::throw_invalid_parameter("grains/" + entry, prm.get(entry),
                                                "a comma-separated list of "
                                                "numbers");
                }
            }
          return values;
        };
        discrete_diameters = list("discrete diameters");
        discrete_fractions = list("discrete fractions");
      }
      seed              = prm.get_integer("seed");
      size_distribution = prm.get("size distribution");
      min_diameter      = prm.get_double("min diameter");
      max_diameter      = prm.get_double("max diameter");
      mean_diameter     = prm.get_double("mean diameter");
      diameter_sd       = prm.get_double("diameter standard deviation");
      zero_file_velocities = prm.get("file velocities") == "zero";
      velocity          = base::get_tensor<dim>(prm, "velocity");
      angular_velocity  = base::get_tensor<3>(prm, "angular velocity");

      if ((source == Source::simple_cubic || source == Source::bcc ||
           (source == Source::random && size_distribution == "constant")) &&
          !(diameter > 0))
        base::throw_invalid_parameter("grains/diameter",
                                      prm.get("diameter"),
                                      "the grain diameter must be > 0 m");
      if (source == Source::file && Utilities::trim(file).empty())
        base::throw_invalid_parameter("grains/file",
                                      file,
                                      "source = file needs a pack file name");
      if (source == Source::list && Utilities::trim(list).empty())
        base::throw_invalid_parameter("grains/list",
                                      list,
                                      "source = list needs at least one "
                                      "grain 'x, y, [z,] radius'");
      prm.leave_subsection();
    }


    template struct GrainParameters<2>;
    template struct GrainParameters<3>;
  } // namespace dem
} // namespace softsand
