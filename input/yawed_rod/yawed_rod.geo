// The seed paper's Fig. 4: a tungsten-nickel-iron rod (D = 6 mm, L = 5 D)
// onto a steel plate one rod diameter thick (6 mm); velocity at 35 degrees
// from the plate's inward normal (-z), rod axis yawed 10 degrees further
// (45 degrees from the normal, in the same plane); half model (symmetry
// plane y = 0), metres. The rod's lowest point starts 0.1 mm above the
// plate face z = 0.
SetFactory("OpenCASCADE");
DefineConstant[ h = {0.8e-3, Name "element size near the impact (m)"},
                axis_angle = {45, Name "rod axis from the plate normal (degrees): obliquity + yaw"},
                D = {0.006, Name "rod diameter (m)"} ];
// separate, so that their defaults follow a D set on the command line
DefineConstant[ L = {5*D, Name "rod length (m)"},
                T = {D, Name "plate thickness (m)"},
                gap = {0.1e-3, Name "gap between rod and plate (m)"} ];
th = axis_angle*Pi/180;
ax = Sin(th); az = -Cos(th);                 // unit rod axis, nose first
cx = 0; cz = gap + 0.5*D*Sin(th);            // centre of the front face
Cylinder(1) = {cx, 0, cz, -L*ax, 0, -L*az, D/2};
Box(2) = {-0.03, 0, -T, 0.07, 0.03, T};
Box(3) = {-0.1, 0, -0.1, 0.2, 0.1, 0.2};
BooleanIntersection(4) = { Volume{1}; Delete; }{ Volume{3}; Delete; };
Physical Volume("rod") = {4};
Physical Volume("plate") = {2};
e = 1e-5;
sy[] = Surface In BoundingBox{-0.1, -e, -0.1, 0.1, e, 0.1};
Physical Surface("sym_y0") = {sy[]};
Field[1] = Box;
Field[1].VIn = h; Field[1].VOut = 4*h;
Field[1].XMin = -0.03; Field[1].XMax = 0.02; Field[1].YMin = -0.001; Field[1].YMax = 0.01;
Field[1].ZMin = -0.008; Field[1].ZMax = 0.03; Field[1].Thickness = 0.008;
Background Field = 1;
Mesh.CharacteristicLengthExtendFromBoundary = 0;
Mesh.CharacteristicLengthFromPoints = 0;
Mesh.CharacteristicLengthMax = 4*h;
