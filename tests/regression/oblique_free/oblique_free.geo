// A free elastic cube striking a free elastic plate obliquely and off its
// centre (metres): the cube (6 mm, 5 cells across and deep) lies wholly over the
// plate's face (16 x 16 x 6 mm, 8 cells across, 4 thick, non-conforming), 0.05 mm
// away, so its nodes slide over the plate's face and never past its edges.
DefineConstant[ a = {0.006, Name "cube edge (m)"},
                w = {0.016, Name "plate width (m)"},
                t = {0.006, Name "plate thickness (m)"},
                gap = {0.05e-3, Name "gap (m)"},
                xc = {0.004, Name "cube corner x over the plate (m)"},
                yc = {0.007, Name "cube corner y over the plate (m)"} ];
Point(1) = {0, 0, 0}; Point(2) = {w, 0, 0}; Point(3) = {w, w, 0}; Point(4) = {0, w, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = 9;
Transfinite Surface{1};
p1[] = Extrude{0, 0, t}{ Surface{1}; Layers{4}; };
z0 = t + gap;
Point(1011) = {xc, yc, z0}; Point(1012) = {xc + a, yc, z0}; Point(1013) = {xc + a, yc + a, z0}; Point(1014) = {xc, yc + a, z0};
Line(1011) = {1011, 1012}; Line(1012) = {1012, 1013}; Line(1013) = {1013, 1014}; Line(1014) = {1014, 1011};
Curve Loop(1011) = {1011, 1012, 1013, 1014};
Plane Surface(1011) = {1011};
Transfinite Curve{1011, 1012, 1013, 1014} = 6;
Transfinite Surface{1011};
c1[] = Extrude{0, 0, a}{ Surface{1011}; Layers{5}; };
Physical Volume("plate") = {p1[1]};
Physical Volume("cube") = {c1[1]};
