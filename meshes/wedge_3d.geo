// A 3D elastic wedge (the paper's dynamic drop-through body, Fig. 2): the 2D wedge's
// downward-pointing triangle (0.6 wide, 0.5 tall) extruded 0.3 in z, tetrahedra.
// Physical tags: volume 0 is material 0; its surface is boundary id 1.
lc = 0.09;
Point(1) = {0, 0, -0.15, lc};
Point(2) = {0.3, 0.5, -0.15, lc};
Point(3) = {-0.3, 0.5, -0.15, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
out[] = Extrude {0, 0, 0.3} { Surface{1}; };
Physical Surface(1) = {1, out[0], out[2], out[3], out[4]};
Physical Volume(0) = {out[1]};
Mesh.MshFileVersion = 2.2;
