#include <softsand/base/parameter_tools.h>
#include <softsand/fluid/boundary_conditions.h>

#include <deal.II/base/function_parser.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/component_mask.h>
#include <deal.II/fe/fe_values_extractors.h>

#include <deal.II/numerics/vector_tools.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace softsand
{
  namespace fluid
  {
    template <int dim>
    std::string
    BoundaryConditions<dim>::face_name(const unsigned int boundary_id)
    {
      static const char *names[] = {
        "x min", "x max", "y min", "y max", "z min", "z max", "cylinder wall"};
      if (boundary_id == cylinder_wall_id)
        return names[6];
      return names[boundary_id];
    }


    template <int dim>
    void
    BoundaryConditions<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("boundary conditions");
      for (unsigned int b = 0; b < n_faces; ++b)
        {
          prm.enter_subsection(face_name(b));
          prm.declare_entry(
            "type",
            "no slip",
            Patterns::Selection("no slip|velocity|flow rate|function|"
                                "pressure|moving wall|symmetry"),
            "no slip: u = 0; velocity: u = the given vector; flow rate: a "
            "uniform inflow normal to the face carrying the given flow "
            "rate; function: u = the given expressions; pressure: "
            "do-nothing outlet/inlet with the given pressure; moving wall: "
            "the wall moves with the given velocity; symmetry: u.n = 0, no "
            "tangential stress.");
          base::declare_double_list(prm,
                                    "velocity",
                                    dim == 2 ? "0, 0" : "0, 0, 0",
                                    "velocity / moving wall: velocity (m/s).");
          prm.declare_entry("flow rate",
                            "0",
                            Patterns::Double(),
                            "flow rate: volumetric flow rate into the "
                            "domain (m^3/s; m^2/s in 2D).");
          prm.declare_entry("function",
                            dim == 2 ? "0; 0" : "0; 0; 0",
                            Patterns::Anything(),
                            "function: velocity components in x, y, z, t "
                            "separated by ';' (m/s).");
          prm.declare_entry("pressure",
                            "0",
                            Patterns::Double(),
                            "pressure: imposed pressure (Pa).");
          prm.leave_subsection();
        }
      PressureRegion<dim>::declare_parameters(
        prm, "inlet region", PressureRegion<dim>::Side::inside);
      PressureRegion<dim>::declare_parameters(
        prm, "perimeter region", PressureRegion<dim>::Side::outside);
      prm.leave_subsection();
    }


    template <int dim>
    void
    BoundaryConditions<dim>::parse_parameters(ParameterHandler       &prm,
                                              const BoundingBox<dim> &box,
                                              const unsigned int      axis,
                                              const bool              file_mesh)
    {
      domain        = box;
      cylinder_axis = axis;
      from_file     = file_mesh;
      prm.enter_subsection("boundary conditions");
      for (unsigned int b = 0; b < n_faces; ++b)
        {
          prm.enter_subsection(face_name(b));
          Face             &f = faces[b];
          const std::string t = prm.get("type");
          f.type = t == "no slip"     ? Type::no_slip :
                   t == "velocity"    ? Type::velocity :
                   t == "flow rate"   ? Type::flow_rate :
                   t == "function"    ? Type::function :
                   t == "pressure"    ? Type::pressure :
                   t == "moving wall" ? Type::moving_wall :
                                        Type::symmetry;
          f.velocity  = base::get_tensor<dim>(prm, "velocity");
          f.flow_rate = prm.get_double("flow rate");
          f.function  = prm.get("function");
          f.pressure  = prm.get_double("pressure");
          if (f.type == Type::function)
            {
              try
                {
                  FunctionParser<dim> test(dim);
                  test.initialize(dim == 2 ? "x,y,t" : "x,y,z,t",
                                  f.function,
                                  base::function_constants(),
                                  true);
                  // muparser compiles lazily: evaluate once to check.
                  Vector<double> value(dim);
                  test.vector_value(Point<dim>(), value);
                }
              catch (...)
                {
                  base::throw_invalid_parameter(
                    "boundary conditions/" + face_name(b) + "/function",
                    f.function,
                    std::to_string(dim) +
                      " expressions in x, y, z, t separated by ';'");
                }
            }
          if (cylinder_axis != numbers::invalid_unsigned_int &&
              b / 2 != cylinder_axis && f.type != Type::no_slip)
            base::throw_invalid_parameter(
              "boundary conditions/" + face_name(b) + "/type",
              prm.get("type"),
              "mesh/geometry = cylinder along its axis " +
                face_name(2 * cylinder_axis).substr(0, 1) +
                " has no such face: its ends are '" +
                face_name(2 * cylinder_axis) + "' and '" +
                face_name(2 * cylinder_axis + 1) +
                "', its mantle is a no-slip wall. Leave this face at no slip");
          if (from_file &&
              (f.type == Type::flow_rate || f.type == Type::symmetry))
            base::throw_invalid_parameter(
              "boundary conditions/" + face_name(b) + "/type",
              prm.get("type"),
              "mesh/geometry = file: the faces tagged " + std::to_string(b) +
                " need not be a plane of the box, which a flow rate (its "
                "area) and a symmetry condition (its normal) assume: use "
                "velocity, function, pressure, no slip or moving wall");
          if (f.type == Type::flow_rate)
            {
              // Uniform velocity into the domain through this face.
              const unsigned int axis = b / 2;
              const double       sign = (b % 2 == 0) ? 1. : -1.;
              f.velocity              = Tensor<1, dim>();
              f.velocity[axis]        = sign * f.flow_rate / face_area(b);
            }
          if (f.type == Type::moving_wall)
            {
              const unsigned int axis = b / 2;
              if (std::abs(f.velocity[axis]) > 0)
                base::throw_invalid_parameter(
                  "boundary conditions/" + face_name(b) + "/velocity",
                  prm.get("velocity"),
                  "a moving wall slides in its own plane: the normal "
                  "component must be 0 (use 'velocity' for inflow)");
            }
          prm.leave_subsection();
        }
      inlet.parse_parameters(prm,
                             "inlet region",
                             PressureRegion<dim>::Side::inside,
                             "boundary conditions/inlet region");
      perimeter.parse_parameters(prm,
                                 "perimeter region",
                                 PressureRegion<dim>::Side::outside,
                                 "boundary conditions/perimeter region");
      if (inlet.enabled() && perimeter.enabled() &&
          !(inlet.radius < perimeter.radius))
        base::throw_invalid_parameter(
          "boundary conditions/inlet region/radius",
          std::to_string(inlet.radius),
          "the inlet must be narrower than the perimeter region's cylinder "
          "(radius " + std::to_string(perimeter.radius) + " m)");
      prm.leave_subsection();
      check_flux_balance();
    }


    template <int dim>
    void
    BoundaryConditions<dim>::check_flux_balance() const
    {
      if (has_pressure_face() || from_file)
        return;
      // Flux into the domain through each face; the inward normal of face
      // b is +e_axis on a min face, -e_axis on a max face.
      std::vector<double> inflow(n_faces, 0.);
      double              total = 0;
      for (unsigned int b = 0; b < n_faces; ++b)
        {
          const Face        &f    = faces[b];
          const unsigned int axis = b / 2;
          const double       sign = (b % 2 == 0) ? 1. : -1.;
          if (f.type == Type::velocity || f.type == Type::flow_rate)
            inflow[b] = sign * f.velocity[axis] * face_area(b);
          else if (f.type == Type::function)
            {
              // A cylinder's circular ends would need their own rule.
              if (cylinder_axis != numbers::invalid_unsigned_int)
                return;
              FunctionParser<dim> u(dim);
              u.initialize(dim == 2 ? "x,y,t" : "x,y,z,t",
                           f.function,
                           base::function_constants(),
                           true);
              // Gauss points on the face rectangle: exact for polynomial
              // profiles (Poiseuille) of degree up to 19.
              const QGauss<dim - 1> rule(10);
              const auto [lo, hi] = domain.get_boundary_points();
              for (unsigned int q = 0; q < rule.size(); ++q)
                {
                  Point<dim> x;
                  double     weight = rule.weight(q);
                  for (unsigned int d = 0, e = 0; d < dim; ++d)
                    if (d == axis)
                      x[d] = (b % 2 == 0) ? lo[d] : hi[d];
                    else
                      {
                        x[d] = lo[d] + rule.point(q)[e++] * (hi[d] - lo[d]);
                        weight *= hi[d] - lo[d];
                      }
                  inflow[b] += sign * u.value(x, axis) * weight;
                }
            }
          total += std::abs(inflow[b]);
        }
      double net = 0;
      for (const double q : inflow)
        net += q;
      if (!(std::abs(net) > 1e-6 * total))
        return;
      const std::string  unit = dim == 3 ? " m^3/s" : " m^2/s";
      std::ostringstream in, out;
      double             sum_in = 0, sum_out = 0;
      for (unsigned int b = 0; b < n_faces; ++b)
        if (inflow[b] > 0)
          {
            in << (sum_in > 0 ? ", " : "") << inflow[b] << unit << " through '"
               << face_name(b) << "'";
            sum_in += inflow[b];
          }
        else if (inflow[b] < 0)
          {
            out << (sum_out > 0 ? ", " : "") << -inflow[b] << unit
                << " through '" << face_name(b) << "'";
            sum_out -= inflow[b];
          }
      std::ostringstream message;
      message << "boundary conditions: every face imposes the velocity (no "
                 "pressure face or region), but the imposed fluxes do not "
                 "balance: in "
              << sum_in << unit << " (" << (sum_in > 0 ? in.str() : "none")
              << "), out " << sum_out << unit << " ("
              << (sum_out > 0 ? out.str() : "none")
              << "). Incompressible flow carries out what comes in: make the "
                 "fluxes equal, or make one face an outlet (type = pressure).";
      AssertThrow(false, ExcMessage(message.str()));
    }


    template <int dim>
    double
    BoundaryConditions<dim>::face_area(const unsigned int b) const
    {
      if (from_file)
        return std::numeric_limits<double>::quiet_NaN();
      if (cylinder_axis != numbers::invalid_unsigned_int)
        {
          const double radius =
            0.5 * domain.side_length((cylinder_axis + 1) % dim);
          return b / 2 == cylinder_axis ? M_PI * radius * radius : 0.;
        }
      double area = 1;
      for (unsigned int d = 0; d < dim; ++d)
        if (d != b / 2)
          area *= domain.side_length(d);
      return area;
    }


    template <int dim>
    void
    BoundaryConditions<dim>::make_velocity_constraints(
      const DoFHandler<dim>     &dof_handler,
      AffineConstraints<double> &constraints,
      const double               time) const
    {
      const FiniteElement<dim> &fe = dof_handler.get_fe();
      const FEValuesExtractors::Vector velocities(0);
      const ComponentMask velocity_mask = fe.component_mask(velocities);

      for (unsigned int b = 0; b < n_boundary_ids(); ++b)
        {
          const Face &f = faces[b];
          switch (f.type)
            {
              case Type::pressure:
                break;
              case Type::symmetry:
                {
                  std::vector<bool> mask(dim + 1, false);
                  mask[b / 2] = true;
                  VectorTools::interpolate_boundary_values(
                    dof_handler,
                    b,
                    Functions::ZeroFunction<dim>(dim + 1),
                    constraints,
                    ComponentMask(mask));
                  break;
                }
              case Type::function:
                {
                  FunctionParser<dim> u(dim + 1);
                  u.initialize(dim == 2 ? "x,y,t" : "x,y,z,t",
                               f.function + "; 0",
                               base::function_constants(),
                               true);
                  u.set_time(time);
                  VectorTools::interpolate_boundary_values(
                    dof_handler, b, u, constraints, velocity_mask);
                  break;
                }
              default:
                {
                  Vector<double> value(dim + 1);
                  if (f.type != Type::no_slip)
                    for (unsigned int d = 0; d < dim; ++d)
                      value[d] = f.velocity[d];
                  VectorTools::interpolate_boundary_values(
                    dof_handler,
                    b,
                    Functions::ConstantFunction<dim>(value),
                    constraints,
                    velocity_mask);
                }
            }
        }
    }


    template <int dim>
    bool
    BoundaryConditions<dim>::has_pressure_face() const
    {
      for (const auto &f : faces)
        if (f.type == Type::pressure)
          return true;
      return has_pressure_regions();
    }


    template <int dim>
    Tensor<1, dim>
    BoundaryConditions<dim>::inflow_velocity() const
    {
      for (const auto &f : faces)
        if (f.type == Type::velocity || f.type == Type::flow_rate)
          return f.velocity;
      return {};
    }

    template class BoundaryConditions<2>;
    template class BoundaryConditions<3>;
  } // namespace fluid
} // namespace softsand
