// Laterally constrained copper column, 1 mm x 1 mm x 20 mm, structured tets, metres.
DefineConstant[ L = {0.02, Name "column length (m)"},
                a = {0.001, Name "column width (m)"},
                nz = {200, Name "cells along"},
                nxy = {2, Name "cells across"} ];
Point(1) = {0, 0, 0}; Point(2) = {a, 0, 0}; Point(3) = {a, a, 0}; Point(4) = {0, a, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = nxy + 1;
Transfinite Surface{1};
out[] = Extrude{0, 0, L}{ Surface{1}; Layers{nz}; };
Physical Volume("column") = {out[1]};
Physical Surface("side_x0") = {out[5]};
Physical Surface("side_x1") = {out[3]};
Physical Surface("side_y0") = {out[2]};
Physical Surface("side_y1") = {out[4]};
