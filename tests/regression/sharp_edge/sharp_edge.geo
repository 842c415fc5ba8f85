// A steel block sliding down the top face of a steel wedge towards its
// sharp edge (issue 13: the contact at a sharp convex edge). The wedge:
// the triangle (0,0), (20,0), (20, 20 tan 30) in the x-z plane extruded
// over y = -5..5 mm, meshed coarsely (a few tetrahedra: each of its faces
// is one or two triangles, so the bottom face's triangles under the block's
// path meet the sharp edge along an edge); its edge along y at the origin
// has an interior angle of 30 degrees between the bottom face (z = 0) and
// the top face (z = x tan 30). The block: 4 x 4 x 2 mm, h = 1 mm, on the
// top face 0.05 mm above it, its lower edge 4 mm up the slope from the
// wedge's edge. Units mm.
SetFactory("OpenCASCADE");
a = Pi/6;
Point(1) = {0, -5, 0};
Point(2) = {20, -5, 0};
Point(3) = {20, -5, 20*Tan(a)};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
w[] = Extrude {0, 10, 0} { Surface{1}; };
Box(2) = {4, -2, 0.05, 4, 4, 2};
Rotate {{0, 1, 0}, {0, 0, 0}, -a} { Volume{2}; }
Physical Volume("slider") = {2};
Physical Volume("wedge") = {w[1]};
MeshSize{PointsOf{Volume{w[1]};}} = 25;
MeshSize{PointsOf{Volume{2};}} = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
