// The jelly poke's fork (paper Fig. 1), a rigid obstacle: four round tines (radius 0.012,
// 0.06 apart along x) with conical tips ending at y = 0 (blunted to radius 0.001 so gmsh meshes
// them cleanly), joined by a bridge at the top. Only its surface is meshed (gmsh -2).
SetFactory("OpenCASCADE");
// Four tines along x with conical tips at y = 0, and the bridge that joins them.
r = 0.012;
For i In {0:3}
  Cylinder(1 + 2*i) = {-0.09 + 0.06*i, 0.04, 0, 0, 0.2, 0, r};
  Cone(2 + 2*i) = {-0.09 + 0.06*i, 0.04, 0, 0, -0.04, 0, r, 0.001};
EndFor
Box(20) = {-0.12, 0.22, -0.02, 0.24, 0.04, 0.04};
BooleanUnion{ Volume{20}; Delete; }{ Volume{1:8}; Delete; }
Physical Surface(1) = Surface{:};
Mesh.CharacteristicLengthMax = 0.02;
Mesh.MshFileVersion = 2.2;
