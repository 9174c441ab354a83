#include <softsand/core/parameter_tools.h>
#include <softsand/dem/grain_parameters.h>
#include <softsand/dem/pack_generators.h>
#include <softsand/io/grain_file.h>

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
      core::declare_double_list(prm,
                                "region lower corner",
                                "",
                                "Lower corner of the region filled by "
                                "lattices and random packs (m); empty: the "
                                "domain.");
      core::declare_double_list(prm,
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
                        "grains of a file or list: settled DEM packs touch "
                        "with overlaps of a few % of R* (soft grains under "
                        "load up to about 25%).");
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
      core::declare_double_list(prm,
                                "velocity",
                                zero,
                                "Translational velocity given to every grain "
                                "not read from a file with velocities (m/s).");
      core::declare_double_list(prm,
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
          region_lower = core::get_point<dim>(prm, "region lower corner");
          region_upper = core::get_point<dim>(prm, "region upper corner");
          for (unsigned int d = 0; d < dim; ++d)
            if (!(region_upper[d] > region_lower[d]))
              core::throw_invalid_parameter(
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
                  core::throw_invalid_parameter("grains/" + entry, prm.get(entry),
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
      velocity          = core::get_tensor<dim>(prm, "velocity");
      angular_velocity  = core::get_tensor<3>(prm, "angular velocity");

      if ((source == Source::simple_cubic || source == Source::bcc ||
           (source == Source::random && size_distribution == "constant")) &&
          !(diameter > 0))
        core::throw_invalid_parameter("grains/diameter",
                                      prm.get("diameter"),
                                      "the grain diameter must be > 0 m");
      if (source == Source::file && Utilities::trim(file).empty())
        core::throw_invalid_parameter("grains/file",
                                      file,
                                      "source = file needs a pack file name");
      if (source == Source::list && Utilities::trim(list).empty())
        core::throw_invalid_parameter("grains/list",
                                      list,
                                      "source = list needs at least one "
                                      "grain 'x, y, [z,] radius'");
      prm.leave_subsection();
    }


    namespace
    {
      template <int dim>
      std::vector<Grain<dim>>
      parse_grain_list(const std::string &text)
      {
        std::vector<Grain<dim>> grains;
        for (const std::string &item :
             Utilities::split_string_list(text, ';'))
          {
            std::vector<double> v;
            try
              {
                for (const auto &x : Utilities::split_string_list(item, ','))
                  v.push_back(Utilities::string_to_double(x));
              }
            catch (...)
              {
                v.clear();
              }
            if (v.size() != dim + 1)
              core::throw_invalid_parameter(
                "grains/list",
                item,
                "each grain is 'x, y, " + std::string(dim == 3 ? "z, " : "") +
                  "radius' with numbers");
            Grain<dim> g;
            for (unsigned int d = 0; d < dim; ++d)
              g.center[d] = v[d];
            g.radius = v[dim];
            if (!(g.radius > 0))
              core::throw_invalid_parameter("grains/list",
                                            item,
                                            "the radius must be > 0 m");
            grains.push_back(g);
          }
        return grains;
      }
    } // namespace


    template <int dim>
    std::vector<Grain<dim>>
    create_grains(const GrainParameters<dim> &p,
                  const BoundingBox<dim>     &domain)
    {
      using S = typename GrainParameters<dim>::Source;
      const BoundingBox<dim> region =
        p.region_is_domain ?
          domain :
          BoundingBox<dim>(std::make_pair(p.region_lower, p.region_upper));

      std::vector<Grain<dim>> grains;
      bool                    velocities_from_file = false;
      if (p.source == S::list)
        grains = parse_grain_list<dim>(p.list);
      switch (p.source)
        {
          case S::none:
          case S::list: // parsed above
            break;
          case S::file:
            grains               = io::read_grain_file<dim>(p.file);
            velocities_from_file = !p.zero_file_velocities;
            break;
          case S::simple_cubic:
            grains = simple_cubic_array(region, p.diameter, p.lattice_spacing);
            break;
          case S::bcc:
            grains = bcc_array(region, p.diameter, p.lattice_spacing);
            break;
          case S::random:
            {
              SizeDistribution dist = make_size_distribution(p);
              grains =
                random_pack(region,
                            dist,
                            p.solid_fraction,
                            p.seed,
                            100000,
                            p.count);
              break;
            }
        }
      // Loaded or listed packs come from users: refuse overlaps and grains
      // outside the domain before anything is built on them.
      if (p.source == S::file)
        check_grains(grains, domain, "grains/file = " + p.file,
                     p.max_overlap_ratio);
      else if (p.source == S::list)
        check_grains(grains, domain, "grains/list", p.max_overlap_ratio);
      if (!velocities_from_file)
        for (auto &g : grains)
          {
            g.velocity         = p.velocity;
            g.angular_velocity = p.angular_velocity;
          }
      return grains;
    }

    template struct GrainParameters<2>;
    template struct GrainParameters<3>;
    template std::vector<Grain<2>>
    create_grains(const GrainParameters<2> &, const BoundingBox<2> &);
    template std::vector<Grain<3>>
    create_grains(const GrainParameters<3> &, const BoundingBox<3> &);
  } // namespace dem
} // namespace softsand
