// Ricochet: a steel rod (diameter 6 mm, length 18 mm, lying along x, tilted
// 10 degrees nose-down) just above a 60 mm x 30 mm x 6 mm steel plate;
// metres. The rod flies along +x and down at 15 degrees (deck).
SetFactory("OpenCASCADE");
DefineConstant[ h = {1.0e-3, Name "element size (m)"},
                D = {0.006, Name "rod diameter (m)"},
                L = {0.018, Name "rod length (m)"},
                tilt = {10, Name "rod tilt, nose down (degrees)"},
                T = {0.006, Name "plate thickness (m)"} ];
Box(1) = {-0.02, -0.015, -T, 0.06, 0.03, T};
Cylinder(2) = {-0.015, 0, 0.0045, L, 0, 0, D/2};
Rotate {{0, 1, 0}, {-0.006, 0, 0.0045}, tilt*Pi/180} { Volume{2}; }
Physical Volume("plate") = {1};
Physical Volume("rod") = {2};
Physical Surface("plate_bottom") = {5};
Mesh.CharacteristicLengthMax = h;
