// A steel rod (diameter 5 mm, length 15 mm) 0.1 mm above a steel plate
// (20 mm x 20 mm x 6 mm), both axisymmetric about z; metres.
SetFactory("OpenCASCADE");
DefineConstant[ h = {0.6e-3, Name "element size (m)"},
                D = {0.005, Name "rod diameter (m)"},
                L = {0.015, Name "rod length (m)"},
                gap = {0.1e-3, Name "gap between rod and plate (m)"},
                w = {0.02, Name "plate width (m)"},
                T = {0.006, Name "plate thickness (m)"} ];
Box(1) = {-w/2, -w/2, -T, w, w, T};
Cylinder(2) = {0, 0, gap, 0, 0, L, D/2};
Physical Volume("plate") = {1};
Physical Volume("rod") = {2};
Mesh.CharacteristicLengthMax = h;
Mesh.CharacteristicLengthMin = 0.5*h;
