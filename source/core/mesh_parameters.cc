#include <softsand/core/mesh_parameters.h>
#include <softsand/base/parameter_tools.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace softsand
{
  namespace core
  {
    template <int dim>
    void
    MeshParameters<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("mesh");
      base::declare_double_list(prm,
                          "lower corner",
                          dim == 2 ? "0, 0" : "0, 0, 0",
                          "Lower corner of the box domain (m).");
      base::declare_double_list(prm,
                          "upper corner",
                          dim == 2 ? "1e-3, 1e-3" : "1e-3, 1e-3, 1e-3",
                          "Upper corner of the box domain (m).");
      prm.declare_entry(
        "geometry",
        "box",
        Patterns::Selection("box|cylinder|file"),
        "box: the box between the corners; its faces are the boundary "
        "conditions' x min ... z max (boundary ids 0-5). cylinder (3D): the "
        "circular cylinder inscribed in that box along 'cylinder axis' (a "
        "permeameter): its ends are the box faces normal to the axis and "
        "keep their names and ids; its mantle, boundary id 6, is a no-slip "
        "wall, meshed as an inscribed 32-gon. The box's cross-section normal "
        "to the axis must be square: its half edge is the radius. file: the "
        "quadrilateral / hexahedral gmsh mesh of 'mesh file' as the coarse "
        "mesh, refined around grains like the others; its boundary faces' "
        "physical tags 0-5 take the conditions of x min ... z max (velocity, "
        "pressure, no slip, moving wall or function), every other tag is a "
        "no-slip wall; it must lie inside the box between the corners (the "
        "grains' and walls' frame).");
      prm.declare_entry("mesh file",
                        "",
                        Patterns::Anything(),
                        "geometry = file: path of the gmsh mesh (.msh, "
                        "format 2 or 4), relative to the working directory.");
      prm.declare_entry("cylinder axis",
                        "z",
                        Patterns::Selection("x|y|z"),
                        "geometry = cylinder: the direction of its axis.");
      prm.declare_entry("coarse cells",
                        "",
                        Patterns::List(Patterns::Integer(1), 0, dim),
                        "Number of coarse cells per direction; empty: cubic "
                        "coarse cells with the shortest box edge.");
      prm.declare_entry("global refinements",
                        "0",
                        Patterns::Integer(0, 12),
                        "Uniform refinements of the coarse mesh.");
      prm.declare_entry(
        "cells per diameter",
        "8",
        Patterns::Double(0, 256),
        "Cells across the smallest grain diameter on grain surfaces "
        "(the paper uses 6-16; 0 = no refinement around grains; values "
        "between 0 and 1 are refused).");
      prm.declare_entry(
        "allow unresolved grains",
        "false",
        Patterns::Bool(),
        "Run a fluid or coupled scene whose finest cells are too coarse for "
        "its grains (fewer than 2 cells across the smallest grain): its "
        "grains are then seen as a blur of solid fraction, not resolved. "
        "false stops such a scene with a message.");
      prm.declare_entry("refinement",
                        "adaptive",
                        Patterns::Selection("adaptive|uniform"),
                        "adaptive: refine only cells cut by grain surfaces "
                        "(p4est keeps 2:1 balance); uniform: the whole mesh "
                        "at that cell size (for comparisons).");
      prm.declare_entry("max refinement level",
                        "14",
                        Patterns::Integer(0, 30),
                        "Cap on the refinement level.");
      prm.declare_entry("kelly cycles",
                        "0",
                        Patterns::Integer(0, 20),
                        "Steady modes: further solve-estimate-refine cycles "
                        "with the Kelly estimator of the velocity.");
      prm.declare_entry("kelly refine fraction",
                        "0.2",
                        Patterns::Double(0, 1),
                        "Fraction of cells refined per Kelly cycle.");
      prm.leave_subsection();
    }


    template <int dim>
    void
    MeshParameters<dim>::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("mesh");
      lower_corner = base::get_point<dim>(prm, "lower corner");
      upper_corner = base::get_point<dim>(prm, "upper corner");
      for (unsigned int d = 0; d < dim; ++d)
        if (!(upper_corner[d] > lower_corner[d]))
          base::throw_invalid_parameter("mesh/upper corner",
                                  prm.get("upper corner"),
                                  "each coordinate must exceed the lower "
                                  "corner's (" +
                                    prm.get("lower corner") + ")");
      geometry      = prm.get("geometry") == "cylinder" ? Geometry::cylinder :
                      prm.get("geometry") == "file"     ? Geometry::file :
                                                          Geometry::box;
      mesh_file     = prm.get("mesh file");
      if (geometry == Geometry::file)
        {
          if (mesh_file.empty() || !std::ifstream(mesh_file))
            base::throw_invalid_parameter(
              "mesh/mesh file",
              mesh_file,
              "geometry = file needs a readable gmsh mesh (.msh); the path "
              "is relative to the working directory");
          if (!Utilities::trim(prm.get("coarse cells")).empty())
            base::throw_invalid_parameter(
              "mesh/coarse cells",
              prm.get("coarse cells"),
              "geometry = file takes its coarse cells from the mesh file: "
              "leave it empty");
        }
      cylinder_axis = prm.get("cylinder axis") == "x" ? 0 :
                      prm.get("cylinder axis") == "y" ? 1 :
                                                        2;
      if (geometry == Geometry::cylinder)
        {
          if (dim != 3)
            base::throw_invalid_parameter("mesh/geometry",
                                          "cylinder",
                                          "a cylinder is a 3D domain: set "
                                          "dimension = 3 or geometry = box");
          const unsigned int a = cylinder_axis;
          const double       w1 =
            upper_corner[(a + 1) % dim] - lower_corner[(a + 1) % dim];
          const double w2 =
            upper_corner[(a + 2) % dim] - lower_corner[(a + 2) % dim];
          if (std::abs(w1 - w2) > 1e-9 * std::max(w1, w2))
            base::throw_invalid_parameter(
              "mesh/upper corner",
              prm.get("upper corner"),
              "geometry = cylinder along " + prm.get("cylinder axis") +
                " needs a square cross-section: its two edges normal to the "
                "axis are " +
                Utilities::to_string(w1) + " and " + Utilities::to_string(w2) +
                " m (their half is the radius)");
          if (!Utilities::trim(prm.get("coarse cells")).empty())
            base::throw_invalid_parameter(
              "mesh/coarse cells",
              prm.get("coarse cells"),
              "geometry = cylinder makes its own coarse mesh (192 cells "
              "across, an inscribed 32-gon): leave it empty");
        }
      coarse_cells.clear();
      for (const auto &s :
           Utilities::split_string_list(prm.get("coarse cells"), ','))
        coarse_cells.push_back(Utilities::string_to_int(s));
      if (!coarse_cells.empty() && coarse_cells.size() != dim)
        base::throw_invalid_parameter("mesh/coarse cells",
                                prm.get("coarse cells"),
                                "give " + std::to_string(dim) +
                                  " numbers or leave it empty");
      global_refinements    = prm.get_integer("global refinements");
      cells_per_diameter    = prm.get_double("cells per diameter");
      // A grain narrower than a cell is not resolved: with 0.5 cells per
      // diameter a sphere in a stream took 0.22 of its Stokes drag.
      if (cells_per_diameter > 0 && cells_per_diameter < 1)
        base::throw_invalid_parameter("mesh/cells per diameter",
                                prm.get("cells per diameter"),
                                "a grain must span at least one cell: give "
                                "N >= 1 (the paper uses 6-16), or 0 for no "
                                "refinement around grains");
      allow_unresolved_grains = prm.get_bool("allow unresolved grains");
      uniform_refinement    = (prm.get("refinement") == "uniform");
      max_refinement_level  = prm.get_integer("max refinement level");
      kelly_cycles          = prm.get_integer("kelly cycles");
      kelly_refine_fraction = prm.get_double("kelly refine fraction");
      prm.leave_subsection();
    }

    template <int dim>
    double
    MeshParameters<dim>::cylinder_radius() const
    {
      const unsigned int across = (cylinder_axis + 1) % dim;
      return 0.5 * (upper_corner[across] - lower_corner[across]);
    }

    template struct MeshParameters<2>;
    template struct MeshParameters<3>;
  } // namespace core
} // namespace softsand
