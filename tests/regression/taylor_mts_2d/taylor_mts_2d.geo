// The copper bar of Johnson and Cook (1983), axisymmetric: L0 25.4 mm, D0
// 7.62 mm in the (r, z) = (x, y) half plane, axis on x = 0, impact end on
// y = 0; mm. input/taylor_ofhc_2d/taylor_ofhc_2d.geo at h = 0.45 mm.
DefineConstant[ h = {0.45, Name "mesh size (mm)"},
                L = {25.4, Name "rod length (mm)"},
                R = {3.81, Name "rod radius (mm)"} ];
Point(1) = {0, 0, 0, h}; Point(2) = {R, 0, 0, h}; Point(3) = {R, L, 0, h}; Point(4) = {0, L, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("rod") = {1};
Physical Curve("impact_face") = {1};
Physical Curve("axis") = {4};
Mesh.CharacteristicLengthMax = h;
Mesh.Algorithm = 6;   // Frontal-Delaunay: near-equilateral triangles
