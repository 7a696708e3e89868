// A 2D elastic wedge (the paper's "drop through" body): a downward-pointing triangle with a
// rounded top edge. Physical tags: surface 0 is material 0; its outline is boundary id 1.
lc = 0.04;
Point(1) = {0, 0, 0, lc};
Point(2) = {0.3, 0.5, 0, lc};
Point(3) = {-0.3, 0.5, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Physical Curve(1) = {1, 2, 3};
Physical Surface(0) = {1};
Mesh.MshFileVersion = 2.2;
