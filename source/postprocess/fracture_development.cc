#include <softsand/base/parameter_tools.h>
#include <softsand/postprocess/fracture_development.h>

#include <sstream>

namespace softsand
{
  namespace postprocess
  {
    FractureDevelopment::FractureDevelopment(
      const FractureAreaParameters   &parameters,
      const fluid::PressureRegion<3> &inlet,
      const Point<3>                 &lower_corner,
      const Point<3>                 &upper_corner,
      const MPI_Comm                  comm)
      : parameters(parameters)
      , inlet(inlet)
      , lower_corner(lower_corner)
      , upper_corner(upper_corner)
      , mpi_communicator(comm)
    {
      if (parameters.stop_reach > 0 && !(parameters.stop_reach > inlet.radius))
        base::throw_invalid_parameter(
          "postprocessing/fracture area/stop at reach",
          Utilities::to_string(parameters.stop_reach),
          "above the inlet radius (boundary conditions/inlet region/radius = " +
            Utilities::to_string(inlet.radius) +
            " m): the open ring around the inlet already reaches it");
    }


    std::string
    FractureDevelopment::check(const std::vector<dem::Grain<3>> &grains)
    {
      if (!parameters.stops_set())
        return "";
      double values[3] = {0, 0, 0};
      if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
        {
          const FractureMap map = fracture_map_of_cell(
            grains, inlet, lower_corner, upper_corner, parameters);
          values[0] = map.fracture_area();
          values[1] = map.reach();
          values[2] = map.pixel_area();
        }
      // Every rank then keeps the same history and decides alike.
      MPI_Bcast(values, 3, MPI_DOUBLE, 0, mpi_communicator);
      const double area = values[0], reach = values[1], pixel_area = values[2];

      std::ostringstream why;
      if (parameters.stop_reach > 0 && reach >= parameters.stop_reach)
        why << "the fracture reaches " << reach << " m from the inlet axis "
            << "(postprocessing/fracture area/stop at reach = "
            << parameters.stop_reach << " m)";
      const unsigned int n = parameters.stop_stall_steps;
      if (n > 0)
        {
          areas.push_back(area);
          if (areas.size() > n + 1)
            areas.pop_front();
          if (why.str().empty() && areas.size() == n + 1 &&
              area - areas.front() < pixel_area)
            why << "the fracture area grew by " << area - areas.front()
                << " m^2, less than one pixel (" << pixel_area
                << " m^2), over " << n
                << " coupling steps (postprocessing/fracture area/stop when "
                   "stalled over = "
                << n << ")";
        }
      return why.str();
    }
  } // namespace postprocess
} // namespace softsand
