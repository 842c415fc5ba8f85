// Plane strain: a steel slab (5 mm wide, 15 mm long) 0.1 mm above a steel plate
// (20 mm wide, 6 mm thick), as the half x >= 0 of the (x, y) plane with the
// symmetry line x = 0 (metres): penetration_2d.geo with the line named
// (physical curve "sym"). Structured right triangles, rod 0.3 mm and plate
// 0.25 mm cells (non-conforming).
DefineConstant[ R = {0.0025, Name "rod radius (m)"},
                L = {0.015, Name "rod length (m)"},
                gap = {0.1e-3, Name "gap between rod and plate (m)"},
                W = {0.01, Name "plate radius (m)"},
                T = {0.006, Name "plate thickness (m)"},
                h_rod = {0.3e-3, Name "rod cell (m)"},
                h_plate = {0.25e-3, Name "plate cell (m)"} ];
Point(1) = {0, -T, 0}; Point(2) = {W, -T, 0}; Point(3) = {W, 0, 0}; Point(4) = {0, 0, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = Round(W/h_plate) + 1;
Transfinite Curve{2, 4} = Round(T/h_plate) + 1;
Transfinite Surface{1};
Point(11) = {0, gap, 0}; Point(12) = {R, gap, 0}; Point(13) = {R, gap + L, 0}; Point(14) = {0, gap + L, 0};
Line(11) = {11, 12}; Line(12) = {12, 13}; Line(13) = {13, 14}; Line(14) = {14, 11};
Curve Loop(11) = {11, 12, 13, 14};
Plane Surface(11) = {11};
Transfinite Curve{11, 13} = Round(R/h_rod) + 1;
Transfinite Curve{12, 14} = Round(L/h_rod) + 1;
Transfinite Surface{11};
Physical Surface("plate") = {1};
Physical Surface("rod") = {11};
Physical Curve("sym") = {4, 14};
