// OFHC copper Taylor rod (Johnson and Cook 1983): L0 25.4 mm, D0 7.62 mm.
// Quarter model in mm (the deck scales by 1e-3); impact face at z = 0.
SetFactory("OpenCASCADE");
DefineConstant[ h = {0.45, Name "mesh size (mm)"},
                L = {25.4, Name "rod length (mm)"},
                R = {3.81, Name "rod radius (mm)"} ];
e = 1e-6;
Cylinder(1) = {0, 0, 0, 0, 0, L, R, Pi/2};
Physical Volume("rod") = {1};
Physical Surface("sym_x") = Surface In BoundingBox{-e, -e, -e, e, R+e, L+e};
Physical Surface("sym_y") = Surface In BoundingBox{-e, -e, -e, R+e, e, L+e};
Physical Surface("impact_face") = Surface In BoundingBox{-e, -e, -e, R+e, R+e, e};
Mesh.CharacteristicLengthMax = h;
Mesh.CharacteristicLengthMin = 0.5*h;
Mesh.Optimize = 1;
