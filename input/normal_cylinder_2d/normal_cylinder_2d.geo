// Normal impact of the seed paper's compact steel cylinder (L = D = 10 mm)
// on the 30 mm steel plate, axisymmetric: the (r, z) = (x, y) half plane,
// axis on x = 0 (metres). The 3D deck input/normal_cylinder in 2D: the plate
// a disc of the 3D box's half width (30 mm) and thickness (30 mm), meshed
// with h near the impact (out to 20 mm from the axis, 16 mm deep) and 4 h
// outside, as the 3D box field; the cylinder with h. h = 0.8 mm is the 3D
// deck's (doc/validation.md 4k).
DefineConstant[ h = {0.8e-3, Name "element size near the impact (m)"},
                D = {0.01, Name "cylinder diameter (m)"},
                L = {0.01, Name "cylinder length (m)"},
                gap = {0.1e-3, Name "gap between cylinder and plate (m)"},
                R = {0.03, Name "plate radius (m)"},
                T = {0.03, Name "plate thickness (m)"} ];
Point(1) = {0, -T, 0}; Point(2) = {R, -T, 0}; Point(3) = {R, 0, 0}; Point(4) = {0, 0, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Point(11) = {0, gap, 0}; Point(12) = {D/2, gap, 0}; Point(13) = {D/2, gap + L, 0}; Point(14) = {0, gap + L, 0};
Line(11) = {11, 12}; Line(12) = {12, 13}; Line(13) = {13, 14}; Line(14) = {14, 11};
Curve Loop(11) = {11, 12, 13, 14};
Plane Surface(11) = {11};
Physical Surface("plate") = {1};
Physical Surface("cylinder") = {11};
Field[1] = Box;
Field[1].VIn = h; Field[1].VOut = 4*h;
Field[1].XMin = -0.001; Field[1].XMax = 0.02; Field[1].YMin = -0.016; Field[1].YMax = 0.02;
Field[1].Thickness = 0.01;
Background Field = 1;
Mesh.CharacteristicLengthExtendFromBoundary = 0;
Mesh.CharacteristicLengthFromPoints = 0;
Mesh.CharacteristicLengthMax = 4*h;
Mesh.Algorithm = 6;
