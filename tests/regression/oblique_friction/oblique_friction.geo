// A 10 mm steel cube 0.1 mm above a 40 mm x 40 mm x 5 mm steel plate
// (metres), structured tetrahedra; the plate's bottom face is fixed.
DefineConstant[ a = {0.01, Name "cube edge (m)"},
                gap = {0.1e-3, Name "gap between cube and plate (m)"},
                w = {0.04, Name "plate width (m)"},
                th = {0.005, Name "plate thickness (m)"},
                n_plate = {8, Name "cells across the plate"},
                nz_plate = {3, Name "cell layers through the plate"},
                n_cube = {4, Name "cells along each cube edge"} ];
// plate: z in [-th, 0]
Point(1) = {-w/2, -w/2, -th}; Point(2) = {w/2, -w/2, -th}; Point(3) = {w/2, w/2, -th}; Point(4) = {-w/2, w/2, -th};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = n_plate + 1;
Transfinite Surface{1};
p[] = Extrude{0, 0, th}{ Surface{1}; Layers{nz_plate}; };
// cube: z in [gap, gap + a]
Point(1001) = {-a/2, -a/2, gap}; Point(1002) = {a/2, -a/2, gap}; Point(1003) = {a/2, a/2, gap}; Point(1004) = {-a/2, a/2, gap};
Line(1001) = {1001, 1002}; Line(1002) = {1002, 1003}; Line(1003) = {1003, 1004}; Line(1004) = {1004, 1001};
Curve Loop(1001) = {1001, 1002, 1003, 1004};
Plane Surface(1001) = {1001};
Transfinite Curve{1001, 1002, 1003, 1004} = n_cube + 1;
Transfinite Surface{1001};
c[] = Extrude{0, 0, a}{ Surface{1001}; Layers{n_cube}; };
Physical Volume("plate") = {p[1]};
Physical Volume("block") = {c[1]};
Physical Surface("plate_bottom") = {1};
