#include <softsand/base/parameter_tools.h>

#include <deal.II/base/utilities.h>

#include <cmath>

namespace softsand
{
  namespace base
  {
    void
    throw_invalid_parameter(const std::string &entry,
                            const std::string &value,
                            const std::string &allowed)
    {
      AssertThrow(false,
                  ExcMessage("Parameter <" + entry + "> = <" + value +
                             "> is invalid: " + allowed + "."));
      std::abort(); // not reached
    }


    std::string
    error_message(const std::exception &e)
    {
      std::string text = e.what();
      const std::string marker = "Additional information:";
      const auto        pos    = text.find(marker);
      if (pos != std::string::npos)
        {
          text = text.substr(pos + marker.size());
          const auto stack = text.find("Stacktrace:");
          if (stack != std::string::npos)
            text = text.substr(0, stack);
        }
      // Collapse the indentation deal.II puts in front of wrapped lines.
      std::string out;
      bool        space = false;
      for (const char c : text)
        {
          if (c == '\n' || c == ' ' || c == '\t')
            space = !out.empty();
          else
            {
              if (space)
                out += ' ';
              out += c;
              space = false;
            }
        }
      while (!out.empty() && (out.back() == '-' || out.back() == ' '))
        out.pop_back();
      return out;
    }


    std::vector<double>
    get_double_list(const ParameterHandler &prm,
                    const std::string      &entry,
                    const unsigned int      n)
    {
      const std::string text = prm.get(entry);
      std::vector<double> values;
      for (const std::string &item :
           Utilities::split_string_list(text, ','))
        {
          try
            {
              values.push_back(Utilities::string_to_double(item));
            }
          catch (...)
            {
              throw_invalid_parameter(entry,
                                      text,
                                      "expected " + std::to_string(n) +
                                        " comma-separated numbers");
            }
          if (!std::isfinite(values.back()))
            throw_invalid_parameter(entry, text, "values must be finite");
        }
      if (values.size() != n)
        throw_invalid_parameter(entry,
                                text,
                                "expected " + std::to_string(n) +
                                  " comma-separated numbers, got " +
                                  std::to_string(values.size()));
      return values;
    }


    template <int dim>
    Point<dim>
    get_point(const ParameterHandler &prm, const std::string &entry)
    {
      const std::vector<double> v = get_double_list(prm, entry, dim);
      Point<dim>                p;
      for (unsigned int d = 0; d < dim; ++d)
        p[d] = v[d];
      return p;
    }


    template <int dim>
    Tensor<1, dim>
    get_tensor(const ParameterHandler &prm, const std::string &entry)
    {
      return get_point<dim>(prm, entry);
    }


    void
    declare_double_list(ParameterHandler  &prm,
                        const std::string &entry,
                        const std::string &default_value,
                        const std::string &documentation)
    {
      prm.declare_entry(entry,
                        default_value,
                        Patterns::List(Patterns::Double()),
                        documentation);
    }

    template Point<2>
    get_point<2>(const ParameterHandler &, const std::string &);
    template Point<3>
    get_point<3>(const ParameterHandler &, const std::string &);
    template Tensor<1, 2>
    get_tensor<2>(const ParameterHandler &, const std::string &);
    template Tensor<1, 3>
    get_tensor<3>(const ParameterHandler &, const std::string &);
  } // namespace base
} // namespace softsand
