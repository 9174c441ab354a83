#include <softsand/base/parameter_tools.h>
#include <softsand/postprocess/fracture_development.h>

#include <istream>
#include <ostream>
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


    bool
    FractureDevelopment::spans_window(const std::size_t index) const
    {
      const unsigned int n        = parameters.stop_stall_steps;
      const double       duration = parameters.stop_stall_time;
      const double       now      = history.back().first;
      return history.size() - 1 - index >= n &&
             now - history[index].first >= duration * (1 - 1e-9);
    }


    std::string
    FractureDevelopment::check(const std::vector<dem::Grain<3>> &grains,
                               const double                      time)
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
      if (parameters.stall_stop_set())
        {
          history.emplace_back(time, area);
          // Only the newest check that still starts a full window is kept.
          while (history.size() >= 2 && spans_window(1))
            history.pop_front();
          if (why.str().empty() && spans_window(0) &&
              area - history.front().second < pixel_area)
            {
              why << "the fracture area grew by "
                  << area - history.front().second
                  << " m^2, less than one pixel (" << pixel_area
                  << " m^2), over " << history.size() - 1
                  << " coupling steps";
              if (parameters.stop_stall_time > 0)
                why << " and " << time - history.front().first << " s";
              why << " (postprocessing/fracture area/";
              if (parameters.stop_stall_steps > 0)
                why << "stop when stalled over = "
                    << parameters.stop_stall_steps
                    << (parameters.stop_stall_time > 0 ? ", " : "");
              if (parameters.stop_stall_time > 0)
                why << "stop when stalled for = " << parameters.stop_stall_time
                    << " s";
              why << ")";
            }
        }
      return why.str();
    }


    void
    FractureDevelopment::save(std::ostream &out) const
    {
      // Exact, so that a restarted run decides as the uninterrupted one.
      const auto precision = out.precision(17);
      out << history.size() << '\n';
      for (const auto &[time, area] : history)
        out << time << ' ' << area << '\n';
      out.precision(precision);
    }


    void
    FractureDevelopment::load(std::istream &in)
    {
      history.clear();
      std::size_t n = 0;
      AssertThrow(in >> n,
                  ExcMessage("The checkpoint's fracture stall window has no "
                             "length."));
      for (std::size_t k = 0; k < n; ++k)
        {
          double time = 0, area = 0;
          AssertThrow(in >> time >> area,
                      ExcMessage("The checkpoint's fracture stall window "
                                 "ends after " +
                                 std::to_string(k) + " of " +
                                 std::to_string(n) + " checks."));
          history.emplace_back(time, area);
        }
    }
  } // namespace postprocess
} // namespace softsand
