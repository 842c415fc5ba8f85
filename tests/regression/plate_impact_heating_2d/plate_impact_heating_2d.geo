// Laterally constrained copper column, axisymmetric: radius 0.5 mm, length
// 20 mm, in the (r, z) = (x, y) half plane, axis on x = 0, impact end on
// y = 0; structured right triangles, metres.
DefineConstant[ L = {0.02, Name "column length (m)"},
                R = {0.0005, Name "column radius (m)"},
                nz = {200, Name "cells along"},
                nr = {5, Name "cells across the radius"} ];
Point(1) = {0, 0, 0}; Point(2) = {R, 0, 0}; Point(3) = {R, L, 0}; Point(4) = {0, L, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nr + 1;
Transfinite Curve{2, 4} = nz + 1;
Transfinite Surface{1};
Physical Surface("column") = {1};
Physical Curve("side") = {2};
Physical Curve("axis") = {4};
