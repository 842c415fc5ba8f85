// Ricochet: a steel rod (diameter 6 mm, length 18 mm, lying along x, tilted
// 10 degrees nose-down) just above a 60 mm x 30 mm x 6 mm steel plate;
// metres. The rod flies along +x and down at 15 degrees (deck).
SetFactory("OpenCASCADE");
DefineConstant[ h = {1.0e-3, Name "element size"} ];
Box(1) = {-0.02, -0.015, -0.006, 0.06, 0.03, 0.006};
Cylinder(2) = {-0.015, 0, 0.0045, 0.018, 0, 0, 0.003};
Rotate {{0, 1, 0}, {-0.006, 0, 0.0045}, 10*Pi/180} { Volume{2}; }
Physical Volume("plate") = {1};
Physical Volume("rod") = {2};
Physical Surface("plate_bottom") = {5};
Mesh.CharacteristicLengthMax = h;
