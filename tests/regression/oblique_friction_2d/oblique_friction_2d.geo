// Plane strain (a section in z = 0, x along the plate, y its normal;
// metres): a 10 mm x 10 mm steel block 0.1 mm above a 40 mm long, 5 mm
// thick steel plate. Structured right triangles (transfinite rectangles)
// with different cell sizes (block 0.625 mm, plate 0.5 mm), so the contact
// faces do not conform; the plate's bottom line is fixed.
DefineConstant[ a = {0.01, Name "block edge (m)"},
                gap = {0.1e-3, Name "gap between block and plate (m)"},
                w = {0.04, Name "plate length (m)"},
                th = {0.005, Name "plate thickness (m)"},
                n_plate = {80, Name "cells along the plate"},
                ny_plate = {10, Name "cells through the plate"},
                n_block = {16, Name "cells along each block edge"} ];
// plate: y in [-th, 0]
Point(1) = {-w/2, -th, 0}; Point(2) = {w/2, -th, 0}; Point(3) = {w/2, 0, 0}; Point(4) = {-w/2, 0, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = n_plate + 1;
Transfinite Curve{2, 4} = ny_plate + 1;
Transfinite Surface{1};
// block: y in [gap, gap + a]
Point(11) = {-a/2, gap, 0}; Point(12) = {a/2, gap, 0}; Point(13) = {a/2, gap + a, 0}; Point(14) = {-a/2, gap + a, 0};
Line(11) = {11, 12}; Line(12) = {12, 13}; Line(13) = {13, 14}; Line(14) = {14, 11};
Curve Loop(11) = {11, 12, 13, 14};
Plane Surface(11) = {11};
Transfinite Curve{11, 12, 13, 14} = n_block + 1;
Transfinite Surface{11};
Physical Surface("plate") = {1};
Physical Surface("block") = {11};
Physical Curve("plate_bottom") = {1};
