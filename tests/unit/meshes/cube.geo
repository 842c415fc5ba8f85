// Unit cube for the gmsh reader unit test: built-in kernel, coarse mesh.
// The test meshes it with gmsh -3 in MSH 4.1 binary, 4.1 ASCII and 2.2 ASCII
// and checks that the three readings agree.
lc = 0.5;
Point(1) = {0, 0, 0, lc};
Point(2) = {1, 0, 0, lc};
Point(3) = {1, 1, 0, lc};
Point(4) = {0, 1, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
out[] = Extrude {0, 0, 1} { Surface{1}; };
Physical Volume("cube") = {out[1]};
Physical Surface("zmin") = {1};
Physical Surface("zmax") = {out[0]};
