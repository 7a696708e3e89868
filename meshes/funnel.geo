// A rigid 2D obstacle outline: two blocks leaving a narrow gap (obstacle surfaces are the
// 1D line elements). Read by 'Obstacle N / type = file'.
lc = 0.1;
g = 0.08;  // half the gap
Point(1) = {-1.0, -0.2, 0, lc};
Point(2) = {-g, -0.2, 0, lc};
Point(3) = {-g, 0, 0, lc};
Point(4) = {-1.0, 0, 0, lc};
Point(5) = {g, -0.2, 0, lc};
Point(6) = {1.0, -0.2, 0, lc};
Point(7) = {1.0, 0, 0, lc};
Point(8) = {g, 0, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Physical Curve(0) = {1, 2, 3, 4, 5, 6, 7, 8};
Mesh.MshFileVersion = 2.2;
