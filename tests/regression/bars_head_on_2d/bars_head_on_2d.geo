// Two identical round elastic bars, radius 5 mm, length 20 mm, on one
// axis, 0.05 mm apart, axisymmetric: the (r, z) = (x, y) half plane, axis
// on x = 0 (metres). Structured right triangles; different radial
// divisions (4 and 5 cells), so the contact faces do not conform.
DefineConstant[ L = {0.02, Name "bar length along the axis (m)"},
                R = {0.005, Name "bar radius (m)"},
                gap = {0.05e-3, Name "gap between the bars (m)"},
                nz = {60, Name "cell layers along each bar"},
                n_striker = {4, Name "cells across the striker's radius"},
                n_target = {5, Name "cells across the target's radius"} ];
Point(1) = {0, 0, 0}; Point(2) = {R, 0, 0}; Point(3) = {R, L, 0}; Point(4) = {0, L, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = n_striker + 1;
Transfinite Curve{2, 4} = nz + 1;
Transfinite Surface{1};
y0 = L + gap;
Point(11) = {0, y0, 0}; Point(12) = {R, y0, 0}; Point(13) = {R, y0 + L, 0}; Point(14) = {0, y0 + L, 0};
Line(11) = {11, 12}; Line(12) = {12, 13}; Line(13) = {13, 14}; Line(14) = {14, 11};
Curve Loop(11) = {11, 12, 13, 14};
Plane Surface(11) = {11};
Transfinite Curve{11, 13} = n_target + 1;
Transfinite Curve{12, 14} = nz + 1;
Transfinite Surface{11};
Physical Surface("striker") = {1};
Physical Surface("target") = {11};
Physical Curve("striker_face") = {3};
Physical Curve("target_face") = {11};
