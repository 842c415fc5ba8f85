// Square elastic bar, 100 mm x 10 mm x 10 mm, structured tetrahedra, metres.
DefineConstant[ L = {0.1, Name "bar length (m)"},
                a = {0.01, Name "bar width (m)"},
                nz = {100, Name "cells along"},
                nxy = {2, Name "cells across"} ];
Point(1) = {0, 0, 0}; Point(2) = {a, 0, 0}; Point(3) = {a, a, 0}; Point(4) = {0, a, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = nxy + 1;
Transfinite Surface{1};
out[] = Extrude{0, 0, L}{ Surface{1}; Layers{nz}; };
Physical Volume("bar") = {out[1]};
Physical Surface("impact_face") = {1};
