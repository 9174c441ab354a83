#ifndef softsand_base_parameter_tools_h
#define softsand_base_parameter_tools_h

#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace softsand
{
  namespace base
  {
    using namespace dealii;

    /**
     * Small helpers shared by the parameter structs: reading vectors of a
     * given length and producing error messages that name the entry, the
     * value and what is allowed.
     */

    /// Parse a comma-separated list of @p n numbers from entry @p entry of the
    /// current subsection of @p prm; stops with a clear message otherwise.
    std::vector<double>
    get_double_list(const ParameterHandler &prm,
                    const std::string      &entry,
                    const unsigned int      n);

    /// Same as get_double_list(), returned as a Point.
    template <int dim>
    Point<dim>
    get_point(const ParameterHandler &prm, const std::string &entry);

    /// Same as get_double_list(), returned as a Tensor.
    template <int dim>
    Tensor<1, dim>
    get_tensor(const ParameterHandler &prm, const std::string &entry);

    /// Throw a message of the form
    /// "Parameter <entry> = <value> is invalid: <allowed>."
    [[noreturn]] void
    throw_invalid_parameter(const std::string &entry,
                            const std::string &value,
                            const std::string &allowed);

    /// Constants available in function expressions of parameter files.
    inline std::map<std::string, double>
    function_constants()
    {
      return {{"pi", M_PI}};
    }

    /// The user-facing part of an exception's text: deal.II's exceptions
    /// carry file, line and stack noise around the message.
    std::string
    error_message(const std::exception &e);

    /// Declare an entry holding a comma-separated list of numbers.
    void
    declare_double_list(ParameterHandler  &prm,
                        const std::string &entry,
                        const std::string &default_value,
                        const std::string &documentation);
  } // namespace base
} // namespace softsand

#endif
