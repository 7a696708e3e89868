#pragma once
// Rigid obstacles: a surface mesh (points in 1D, segments in 2D, triangles in 3D) moved by
// a scripted rigid motion x(t) = R(t) (X - c) + c + T(t).
#include <Eigen/Core>

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace ritr::contact
{
  template <int dim>
  struct RigidObstacle
  {
    using Point = Eigen::Matrix<double, dim, 1>;

    std::vector<Point>              rest_vertices;
    std::vector<std::array<int, 2>> edges;  // 2D segments (3D: derived from faces)
    std::vector<std::array<int, 3>> faces;  // 3D triangles

    Point                                center = Point::Zero();
    Eigen::Vector3d                      axis{0, 0, 1};
    std::function<Point(double)>         translation;  // T(t); empty: none
    std::function<double(double)>        angle;        // rotation angle(t); empty: none

    // Vertex positions at time t.
    std::vector<Point> vertices_at(double t) const;
  };

  // Generators. `up` conventions: planes use the given normal; spikes point along +y.
  template <int dim>
  RigidObstacle<dim> make_plane(const Eigen::Matrix<double, dim, 1> &point,
                                const Eigen::Matrix<double, dim, 1> &normal, double extent);
  template <int dim>
  RigidObstacle<dim> make_box(const Eigen::Matrix<double, dim, 1> &center,
                              const Eigen::Matrix<double, dim, 1> &size);
  // A row (2D) or grid (3D) of `count` sharp spikes of the given height whose bases span
  // `length` centred at `base_center`.
  template <int dim>
  RigidObstacle<dim> make_spikes(const Eigen::Matrix<double, dim, 1> &base_center, double length,
                                 unsigned int count, double height);

  // The index of the first segment (2D) or triangle (3D) of `obstacle` without a length or an
  // area -- shorter than 1e-12 of the obstacle's extent, or of an area below 1e-12 of its
  // longest edge squared -- or -1 when every one has: contact needs a direction on each.
  template <int dim>
  int first_degenerate_element(const RigidObstacle<dim> &obstacle);
} // namespace ritr::contact
