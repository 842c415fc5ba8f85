// Two identical square elastic blocks, 10 mm x 10 mm x 20 mm, on one axis,
// 0.05 mm apart, structured tetrahedra (metres). Different cross-section
// meshes (2x2 and 3x3 cells), so the contact faces do not conform.
DefineConstant[ L = {0.02, Name "block length along the axis (m)"},
                a = {0.01, Name "block width (m)"},
                gap = {0.05e-3, Name "gap between the blocks (m)"},
                nz = {60, Name "cell layers along each block"},
                n_striker = {2, Name "cells across the striker"},
                n_target = {3, Name "cells across the target"} ];
Point(1) = {0, 0, 0}; Point(2) = {a, 0, 0}; Point(3) = {a, a, 0}; Point(4) = {0, a, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = n_striker + 1;
Transfinite Surface{1};
a1[] = Extrude{0, 0, L}{ Surface{1}; Layers{nz}; };
z0 = L + gap;
Point(1011) = {0, 0, z0}; Point(1012) = {a, 0, z0}; Point(1013) = {a, a, z0}; Point(1014) = {0, a, z0};
Line(1011) = {1011, 1012}; Line(1012) = {1012, 1013}; Line(1013) = {1013, 1014}; Line(1014) = {1014, 1011};
Curve Loop(1011) = {1011, 1012, 1013, 1014};
Plane Surface(1011) = {1011};
Transfinite Curve{1011, 1012, 1013, 1014} = n_target + 1;
Transfinite Surface{1011};
b1[] = Extrude{0, 0, L}{ Surface{1011}; Layers{nz}; };
Physical Volume("striker") = {a1[1]};
Physical Volume("target") = {b1[1]};
