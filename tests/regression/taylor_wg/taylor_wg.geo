// Wilkins-Guinan copper Taylor bar: L0 32.4 mm, R0 3.2 mm. Quarter model, mm.
SetFactory("OpenCASCADE");
DefineConstant[ h = {0.6, Name "mesh size (mm)"},
                L = {32.4, Name "bar length (mm)"},
                R = {3.2, Name "bar radius (mm)"} ];
e = 1e-6;
Cylinder(1) = {0, 0, 0, 0, 0, L, R, Pi/2};
Physical Volume("bar") = {1};
Physical Surface("sym_x") = Surface In BoundingBox{-e, -e, -e, e, R+e, L+e};
Physical Surface("sym_y") = Surface In BoundingBox{-e, -e, -e, R+e, e, L+e};
Mesh.CharacteristicLengthMax = h;
Mesh.CharacteristicLengthMin = 0.5*h;
Mesh.Optimize = 1;
