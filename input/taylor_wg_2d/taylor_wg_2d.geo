// Wilkins-Guinan copper Taylor bar, axisymmetric: L0 32.4 mm, R0 3.2 mm, in
// the (r, z) = (x, y) half plane, axis on x = 0, impact end on y = 0; mm.
DefineConstant[ h = {0.2, Name "mesh size (mm)"},
                L = {32.4, Name "bar length (mm)"},
                R = {3.2, Name "bar radius (mm)"} ];
Point(1) = {0, 0, 0, h}; Point(2) = {R, 0, 0, h}; Point(3) = {R, L, 0, h}; Point(4) = {0, L, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("bar") = {1};
Physical Curve("impact_face") = {1};
Physical Curve("axis") = {4};
Mesh.CharacteristicLengthMax = h;
Mesh.Algorithm = 6;   // Frontal-Delaunay: near-equilateral triangles
