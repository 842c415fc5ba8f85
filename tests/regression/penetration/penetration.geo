// A steel rod (diameter 5 mm, length 15 mm) 0.1 mm above a steel plate
// (20 mm x 20 mm x 6 mm), both axisymmetric about z; metres.
SetFactory("OpenCASCADE");
DefineConstant[ h = {0.8e-3, Name "element size"} ];
Box(1) = {-0.01, -0.01, -0.006, 0.02, 0.02, 0.006};
Cylinder(2) = {0, 0, 0.1e-3, 0, 0, 0.015, 0.0025};
Physical Volume("plate") = {1};
Physical Volume("rod") = {2};
Mesh.CharacteristicLengthMax = h;
Mesh.CharacteristicLengthMin = 0.5*h;
