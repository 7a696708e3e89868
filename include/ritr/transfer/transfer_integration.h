#pragma once
// How the L2 transfer between two meshes is integrated (transfer_operator.h).
namespace ritr::transfer
{
  enum class TransferIntegration
  {
    quadrature,  // the paper's: a fixed rule on each candidate cell, points located in the old mesh
    exact        // on the overlap polygons of the two meshes (triangles)
  };
} // namespace ritr::transfer
