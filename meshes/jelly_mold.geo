// The jelly poke's mold (paper Fig. 1), a rigid obstacle: a plate 0.9 x 0.04 x 0.9 (top at
// y = 0) with a cat's face raised 0.02 on it (a disk of radius 0.15 with two ears). Only its
// surface is meshed (gmsh -2): the triangles of 'Obstacle N / type = file'.
SetFactory("OpenCASCADE");
Box(1) = {-0.45, -0.04, -0.45, 0.9, 0.04, 0.9};
// The cat's face, raised 0.02: a disk with two ears.
Disk(10) = {0, 0, 0, 0.15};
Point(20) = {-0.15, 0, -0.06}; Point(21) = {-0.13, 0, -0.22}; Point(22) = {-0.03, 0, -0.14};
Line(20) = {20, 21}; Line(21) = {21, 22}; Line(22) = {22, 20};
Curve Loop(20) = {20, 21, 22}; Plane Surface(20) = {20};
Point(30) = {0.15, 0, -0.06}; Point(31) = {0.13, 0, -0.22}; Point(32) = {0.03, 0, -0.14};
Line(30) = {30, 31}; Line(31) = {31, 32}; Line(32) = {32, 30};
Curve Loop(30) = {30, 31, 32}; Plane Surface(30) = {30};
Rotate {{1, 0, 0}, {0, 0, 0}, Pi/2} { Surface{10}; }
face() = BooleanUnion{ Surface{10}; Delete; }{ Surface{20, 30}; Delete; };
relief() = Extrude {0, 0.02, 0} { Surface{face()}; };
BooleanUnion{ Volume{1}; Delete; }{ Volume{relief(1)}; Delete; }
Physical Surface(1) = Surface{:};
Mesh.CharacteristicLengthMax = 0.05;
Mesh.MshFileVersion = 2.2;
