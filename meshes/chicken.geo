// The chicken drop's soft body (paper Fig. 10, a marshmallow chicken): an ellipsoid body
// (semi-axes 0.25, 0.16, 0.16), a head of radius 0.1 and a conical beak, tetrahedra; its lowest
// point at y = 0.17, 0.02 above the spike bed's tips. Physical tags: volume 0 is material 0
// (the soft material); its surface is boundary id 1.
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 1};
Dilate {{0, 0, 0}, {0.25, 0.16, 0.16}} { Volume{1}; }
Sphere(2) = {0.17, 0.17, 0, 0.1};
Cone(3) = {0.25, 0.18, 0, 0.08, 0, 0, 0.03, 0};
BooleanUnion{ Volume{1}; Delete; }{ Volume{2, 3}; Delete; }
Translate {0, 0.33, 0} { Volume{:}; }
Physical Surface(1) = Surface{:};
Physical Volume(0) = Volume{:};
Mesh.CharacteristicLengthMax = 0.07;
Mesh.MshFileVersion = 2.2;
