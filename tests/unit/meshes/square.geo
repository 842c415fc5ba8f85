// A 1 x 2 rectangle in the plane z = 0 for the gmsh reader's 2D unit test:
// built-in kernel, coarse triangles.  The test meshes it with gmsh -2 in
// MSH 4.1 binary, 4.1 ASCII and 2.2 ASCII and checks that the three
// readings agree; with quadrangles (Mesh.RecombineAll) and second-order
// triangles (-order 2) it must be refused.
lc = 0.5;
Point(1) = {0, 0, 0, lc};
Point(2) = {1, 0, 0, lc};
Point(3) = {1, 2, 0, lc};
Point(4) = {0, 2, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("plate") = {1};
Physical Curve("axis") = {4};
Physical Curve("bottom") = {1};
