#include <softsand/postprocess/columns/grain_columns.h>

namespace softsand
{
  namespace postprocess
  {
    namespace
    {
      constexpr char axis_names[3] = {'x', 'y', 'z'};
    }

    GrainColumns::GrainColumns(const BoundingBox<3> &probe)
      : probe(probe)
    {}


    dem::GranularStatistics
    GrainColumns::add_columns(const dem::GranularDynamics &dem,
                              io::StatisticsFile          &statistics,
                              const MPI_Comm               comm) const
    {
      const dem::GranularStatistics s = dem.statistics(probe);
      statistics.add_value("kinetic_energy", s.kinetic_energy);
      statistics.add_value("mean_speed", s.mean_speed);
      statistics.add_value("max_speed", s.max_speed);
      statistics.add_value("max_overlap_ratio", s.max_overlap);
      statistics.add_value("mean_overlap_ratio", s.mean_overlap);
      statistics.add_value("max_wall_overlap_ratio", s.max_wall_overlap);
      statistics.add_value("coordination", s.coordination);
      const auto [omega_dt, damping_dt] = dem.stability_rates();
      statistics.add_value("omega_dt", omega_dt);
      statistics.add_value("damping_dt", damping_dt);
      statistics.add_value("packing_fraction", s.packing_fraction);
      for (unsigned int d = 0; d < 3; ++d)
        statistics.add_value(std::string("contact_stress_") + axis_names[d] +
                               axis_names[d],
                             s.contact_stress[d][d]);
      statistics.add_value("grains", s.n_grains);
      statistics.add_value("lost_grains",
                           Utilities::MPI::sum(dem.n_lost_grains(), comm));
      statistics.add_value("neighbor_list_builds", dem.n_neighbor_list_builds());
      for (const auto &wall : dem.get_walls())
        {
          const bool plane = (wall.shape == dem::Wall::Shape::plane);
          // A cylinder's force vector cancels around the axis: its load is
          // the sum of the normal contact forces.
          statistics.add_value(wall.name + "_force_normal",
                               plane ? -(wall.force * wall.normal) :
                                       wall.normal_force);
          statistics.add_value(wall.name + "_pressure", wall.pressure());
          if (plane)
            statistics.add_value(wall.name + "_position",
                                 wall.point * wall.normal);
        }
      return s;
    }


    void
    add_first_grain_columns(const std::vector<dem::Grain<3>> &grains,
                            io::StatisticsFile               &statistics)
    {
      const dem::Grain<3> first = grains.empty() ? dem::Grain<3>() : grains[0];
      for (unsigned int d = 0; d < 3; ++d)
        {
          statistics.add_value(std::string("grain0_") + axis_names[d],
                               first.center[d]);
          statistics.add_value(std::string("grain0_v") + axis_names[d],
                               first.velocity[d]);
          statistics.add_value(std::string("grain0_w") + axis_names[d],
                               first.angular_velocity[d]);
        }
    }
  } // namespace postprocess
} // namespace softsand
