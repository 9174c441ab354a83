#ifndef softsand_core_mesh_parameters_h
#define softsand_core_mesh_parameters_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <string>
#include <vector>

namespace softsand
{
  namespace core
  {
    using namespace dealii;

    /**
     * The fluid domain and how the octree mesh is refined around grain
     * surfaces. The domain is the axis-aligned box between the corners
     * (faces with boundary ids 0..2 dim-1 in the order x min, x max, y min,
     * y max, z min, z max), or the circular cylinder inscribed in it: its
     * ends keep the ids of the box faces they lie on and its mantle has
     * id 2 dim (a no-slip wall). A mesh file (gmsh) gives any shape: its
     * boundary tags 0..2 dim-1 take the conditions of x min ... z max, every
     * other tag is a no-slip wall (id 2 dim); the box must contain it.
     */
    template <int dim>
    struct MeshParameters
    {
      enum class Geometry
      {
        box,
        cylinder,
        file
      };

      Point<dim> lower_corner;
      Point<dim> upper_corner;
      Geometry   geometry = Geometry::box;
      /// The cylinder's axis: the coordinate direction 0, 1 or 2.
      unsigned int cylinder_axis = dim - 1;
      /// geometry = file: the gmsh mesh (.msh) of the domain.
      std::string mesh_file;
      /// Half the edge of the box's square cross-section normal to the axis.
      double
      cylinder_radius() const;
      /// Coarse cells per direction; empty: cubes of the shortest edge.
      std::vector<unsigned int> coarse_cells;
      unsigned int              global_refinements = 0;
      /// Cells across the smallest grain diameter on grain surfaces (0: none).
      double                    cells_per_diameter = 8;
      /// Run although the finest cells are too coarse for the grains (fewer
      /// than 2 cells across the smallest).
      bool                      allow_unresolved_grains = false;
      /// Uniform: refine the whole mesh to the grain-surface cell size.
      bool                      uniform_refinement = false;
      unsigned int              max_refinement_level = 14;
      /// Kelly-estimator refinement cycles in the fluid after the first solve.
      unsigned int              kelly_cycles        = 0;
      double                    kelly_refine_fraction = 0.2;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };
  } // namespace core
} // namespace softsand

#endif
