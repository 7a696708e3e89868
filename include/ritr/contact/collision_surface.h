#pragma once
// The collision mesh seen by the contact module: vertex count, boundary primitives and
// per-vertex flags. Positions are not stored here; every function takes them as an
// n x dim matrix so that the same surface serves rest, lagged, start and trial positions.
#include <array>
#include <vector>

namespace ritr::contact
{
  // Kind of primitive pair. 1D: vertex_vertex; 2D: point_edge; 3D: point_triangle and
  // edge_edge.
  enum class ContactKind
  {
    vertex_vertex,
    point_edge,
    point_triangle,
    edge_edge
  };

  template <int dim>
  struct CollisionSurface
  {
    static_assert(dim >= 1 && dim <= 3, "dim must be 1, 2 or 3");

    int n_vertices = 0;

    // 2D: boundary segments. 3D: every edge of a boundary face (see edges_of_faces).
    // Ignored in 1D, where the primitives are the vertices themselves.
    std::vector<std::array<int, 2>> edges;

    // 3D only: boundary triangles.
    std::vector<std::array<int, 3>> faces;

    // Per vertex: vertex of a rigid scripted obstacle. Pairs whose two primitives are both
    // made of obstacle vertices only are never considered. Empty means "no obstacles".
    std::vector<bool> is_obstacle;

    // Per vertex: id of the body the vertex belongs to (informational; not used to filter,
    // since self-contact is included).
    std::vector<int> body_id;

    bool vertex_is_obstacle(const int v) const
    {
      return !is_obstacle.empty() && is_obstacle[v];
    }
    bool edge_is_obstacle(const int e) const
    {
      return vertex_is_obstacle(edges[e][0]) && vertex_is_obstacle(edges[e][1]);
    }
    bool face_is_obstacle(const int f) const
    {
      return vertex_is_obstacle(faces[f][0]) && vertex_is_obstacle(faces[f][1]) &&
             vertex_is_obstacle(faces[f][2]);
    }

    // Throws std::invalid_argument if indices are out of range, primitives are degenerate
    // (repeated vertex) or per-vertex arrays have the wrong size.
    void check() const;
  };

  // The unique undirected edges of a triangle set, each stored with (smaller, larger) vertex
  // index and sorted lexicographically.
  std::vector<std::array<int, 2>> edges_of_faces(const std::vector<std::array<int, 3>> &faces);
} // namespace ritr::contact
