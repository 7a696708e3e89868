// A rigid 2D obstacle outline for the paper's varying-friction scene (Fig. 21): two blocks
// 0.2 thick whose inner faces slope like the sides of meshes/wedge.geo (0.6 across per unit
// of height), leaving an angled gap 2 gb wide at the bottom (y = -0.2) and 2 gb + 0.24 at the
// top (y = 0). Obstacle surfaces are the 1D line elements; read by 'Obstacle N / type = file'.
lc = 0.1;
gb = 0.04;     // half the gap at the bottom
slope = 0.6;   // horizontal run of the inner faces per unit of height
h = 0.2;
Point(1) = {-1.0, -h, 0, lc};
Point(2) = {-gb, -h, 0, lc};
Point(3) = {-gb - slope * h, 0, 0, lc};
Point(4) = {-1.0, 0, 0, lc};
Point(5) = {gb, -h, 0, lc};
Point(6) = {1.0, -h, 0, lc};
Point(7) = {1.0, 0, 0, lc};
Point(8) = {gb + slope * h, 0, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Physical Curve(0) = {1, 2, 3, 4, 5, 6, 7, 8};
Mesh.MshFileVersion = 2.2;
