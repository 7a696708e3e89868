#pragma once
// Scenes built in code for physics tests: one body, one material, no obstacle, no output.
#include <ritr/scene/parameters.h>

namespace ritr::test_support
{
  inline Scene basic_scene(const int dim, const std::string &shape)
  {
    Scene s;
    s.parameter_file   = "test-scene";
    s.dimension        = dim;
    s.output_directory = "test-output";
    BodyScene body;
    body.geometry.shape = shape;
    body.initial_velocity = dim == 1 ? "0" : dim == 2 ? "0;0" : "0;0;0";
    s.bodies.push_back(body);
    s.materials.resize(max_materials);
    s.gravity          = {0, 0, 0};
    s.contact.enabled  = false;
    return s;
  }
  // A static rigid plane obstacle (a wall point in 1D) through `point` with normal `normal`.
  inline ObstacleScene plane_obstacle(const int dim, const std::vector<double> &point,
                                      const std::vector<double> &normal, const double size = 20)
  {
    ObstacleScene plane;
    plane.type           = "plane";
    plane.point          = point;
    plane.normal         = normal;
    plane.size           = {size, size, size};
    plane.translation    = dim == 1 ? "0" : dim == 2 ? "0;0" : "0;0;0";
    plane.rotation_angle = "0";
    return plane;
  }
} // namespace ritr::test_support
