// Round elastic bar, axisymmetric: radius 5 mm, length 100 mm, in the
// (r, z) = (x, y) half plane, axis on x = 0, impact end on y = 0; metres.
// Structured right triangles (a transfinite rectangle).
DefineConstant[ L = {0.1, Name "bar length (m)"},
                R = {0.005, Name "bar radius (m)"},
                nz = {200, Name "cells along"},
                nr = {5, Name "cells across the radius"} ];
Point(1) = {0, 0, 0}; Point(2) = {R, 0, 0}; Point(3) = {R, L, 0}; Point(4) = {0, L, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nr + 1;
Transfinite Curve{2, 4} = nz + 1;
Transfinite Surface{1};
Physical Surface("bar") = {1};
Physical Curve("impact_face") = {1};
Physical Curve("axis") = {4};
