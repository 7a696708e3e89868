// The chicken drop's stiff spikes (paper Fig. 10), a second deformable body: a base 0.8 x 0.1
// x 0.8 (top at y = 0) with a 3 x 3 grid of sharp cones (base radius 0.07, height 0.15, pitch
// 0.25), tetrahedra. Physical tags: volume 1 is material 1 (the stiff material); its surface
// is boundary id 1.
SetFactory("OpenCASCADE");
Box(1) = {-0.4, -0.1, -0.4, 0.8, 0.1, 0.8};
n = 2;
For i In {0:2}
  For j In {0:2}
    Cone(n) = {-0.25 + 0.25*i, 0, -0.25 + 0.25*j, 0, 0.15, 0, 0.07, 0};
    n = n + 1;
  EndFor
EndFor
BooleanUnion{ Volume{1}; Delete; }{ Volume{2:10}; Delete; }
Physical Surface(1) = Surface{:};
Physical Volume(1) = Volume{:};
Mesh.CharacteristicLengthMax = 0.1;
Mesh.MshFileVersion = 2.2;
