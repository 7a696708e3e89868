#include <ritr/contact/obj_file.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace ritr::contact
{
  namespace
  {
    // Throws "FILE:LINE: what".
    class LineError
    {
    public:
      LineError(const std::string &file, const unsigned int line) : prefix_(file + ":" + std::to_string(line) + ": ") {}
      [[noreturn]] void operator()(const std::string &what) const { throw std::runtime_error(prefix_ + what); }

    private:
      std::string prefix_;
    };

    std::string quoted(const std::string &token) { return "'" + token.substr(0, 40) + "'"; }

    double coordinate(const std::string &token, const LineError &fail)
    {
      char        *end   = nullptr;
      const double value = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0')
        fail("vertex coordinate " + quoted(token) + " is not a number");
      if (!std::isfinite(value))
        fail("vertex coordinate " + quoted(token) + " is not a finite number");
      return value;
    }

    // A face or line entry "i", "i/t" or "i/t/n": the 0-based index of vertex i.
    int vertex_index(const std::string &token, const int n_vertices, const LineError &fail)
    {
      const std::string digits = token.substr(0, token.find('/'));
      char             *end    = nullptr;
      const long        index  = std::strtol(digits.c_str(), &end, 10);
      if (end == digits.c_str() || *end != '\0')
        fail("vertex index " + quoted(token) + " is not an integer");
      if (index < 1 || index > n_vertices)
        fail("vertex index " + quoted(digits) + " names no vertex (" + std::to_string(n_vertices) +
             " are defined before this line)");
      return static_cast<int>(index - 1);
    }
  } // namespace

  template <int dim>
  RigidObstacle<dim> read_obj(const std::string &file)
  {
    std::ifstream in(file);
    if (!in)
      throw std::runtime_error("cannot open obstacle file '" + file + "'");
    RigidObstacle<dim>        o;
    std::vector<unsigned int> element_line;  // the line of each segment (2D) or triangle (3D)
    std::string               line;
    for (unsigned int number = 1; std::getline(in, line); ++number)
      {
        std::istringstream       fields(line.substr(0, line.find('#')));
        std::vector<std::string> tokens;
        for (std::string token; fields >> token;)
          tokens.push_back(token);
        if (tokens.empty())
          continue;
        const LineError fail(file, number);
        const int       n_given    = static_cast<int>(tokens.size()) - 1;
        const int       n_vertices = static_cast<int>(o.rest_vertices.size());
        if (tokens[0] == "v")
          {
            // x y [z [w]]: the first dim are the position, the rest must still be numbers.
            if (n_given < dim || n_given > 4)
              fail("a vertex needs " + std::to_string(dim) + " coordinates, this one has " + std::to_string(n_given));
            Eigen::Matrix<double, dim, 1> p;
            for (int k = 0; k < n_given; ++k)
              {
                const double c = coordinate(tokens[k + 1], fail);
                if (k < dim)
                  p[k] = c;
              }
            o.rest_vertices.push_back(p);
          }
        else if (tokens[0] == "f" && dim == 3)
          {
            if (n_given != 3)
              fail("a face needs 3 vertices (triangles only), this one has " + std::to_string(n_given));
            o.faces.push_back({{vertex_index(tokens[1], n_vertices, fail), vertex_index(tokens[2], n_vertices, fail),
                                vertex_index(tokens[3], n_vertices, fail)}});
            element_line.push_back(number);
          }
        else if (tokens[0] == "l" && dim == 2)
          {
            if (n_given < 2)
              fail("a line needs at least 2 vertices");
            for (int k = 1; k < n_given; ++k)
              {
                o.edges.push_back({{vertex_index(tokens[k], n_vertices, fail), vertex_index(tokens[k + 1], n_vertices, fail)}});
                element_line.push_back(number);
              }
          }
      }
    if (o.rest_vertices.empty() || (dim == 2 && o.edges.empty()) || (dim == 3 && o.faces.empty()))
      throw std::runtime_error("obstacle file '" + file + "' has no " +
                               (dim == 2 ? "segments ('l' lines)" : "triangles ('f' lines)"));

    if (const int e = first_degenerate_element(o); e >= 0)
      LineError(file, element_line[e])(dim == 2 ? "a segment of zero length" : "a triangle of zero area");
    return o;
  }

  template RigidObstacle<1> read_obj<1>(const std::string &);
  template RigidObstacle<2> read_obj<2>(const std::string &);
  template RigidObstacle<3> read_obj<3>(const std::string &);
} // namespace ritr::contact
