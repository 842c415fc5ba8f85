// Long-rod penetration (Lanz-Odermatt validation), axisymmetric: the rod
// of input/long_rod (diameter D, length 10 D) 0.1 mm above a thick steel
// block, in the (r, z) = (x, y) half plane, axis on x = 0 (metres). The
// block is radius 6 D and depth 20 D, meshed with h near the axis (out to
// 2 D) and coarser (4 h) outside; the rod with h. The default h = 0.5 mm
// puts 5 elements across the rod's radius (the 3D deck's 1 mm: 2.5); refine
// with e.g. gmsh -2 -setnumber h 0.25e-3 long_rod_2d.geo.
DefineConstant[ h = {0.5e-3, Name "element size near the axis (m)"},
                D = {5.0e-3, Name "rod diameter (m)"} ];
DefineConstant[ L = {10*D, Name "rod length (m)"},
                R = {6*D, Name "block radius (m)"},
                T = {20*D, Name "block depth (m)"},
                gap = {0.1e-3, Name "gap between rod and block (m)"} ];
// block: (0, -T) .. (R, 0)
Point(1) = {0, -T, 0}; Point(2) = {R, -T, 0}; Point(3) = {R, 0, 0}; Point(4) = {0, 0, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
// rod: (0, gap) .. (D/2, gap + L)
Point(11) = {0, gap, 0}; Point(12) = {D/2, gap, 0}; Point(13) = {D/2, gap + L, 0}; Point(14) = {0, gap + L, 0};
Line(11) = {11, 12}; Line(12) = {12, 13}; Line(13) = {13, 14}; Line(14) = {14, 11};
Curve Loop(11) = {11, 12, 13, 14};
Plane Surface(11) = {11};
Physical Surface("block") = {1};
Physical Surface("rod") = {11};
Physical Curve("block_base") = {1};
Field[1] = MathEval;
Field[1].F = Sprintf("%g + (%g - %g)*Min(1, Max(0, x - %g)/%g)", h, 4*h, h, 2*D, 4*D);
Background Field = 1;
Mesh.CharacteristicLengthExtendFromBoundary = 0;
Mesh.CharacteristicLengthFromPoints = 0;
Mesh.CharacteristicLengthFromCurvature = 0;
Mesh.Algorithm = 6;
