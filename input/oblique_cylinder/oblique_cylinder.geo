// The seed paper's Fig. 3: a compact steel cylinder (L = D = 10 mm) strikes
// a thick steel plate obliquely; half model (symmetry plane y = 0), metres.
// The cylinder's axis lies along its velocity, at angle theta from the
// plate's inward normal (-z); its front edge starts 0.1 mm above the plate
// face z = 0. The plate (60 x 30 x 30 mm, half) is meshed with h near the
// impact and coarser away from it. The default h = 1 mm is the mesh of the
// numbers in doc/validation.md 4j (45510 tetrahedra); normal_cylinder.geo
// includes this file with h = 0.8 mm.
SetFactory("OpenCASCADE");
DefineConstant[ h = {1.0e-3, Name "element size near the impact (m)"},
                theta = {30, Name "obliquity (degrees from the plate normal)"},
                D = {0.01, Name "cylinder diameter (m)"},
                L = {0.01, Name "cylinder length (m)"},
                gap = {0.1e-3, Name "gap between cylinder edge and plate (m)"},
                W = {0.06, Name "plate length along x (m)"},
                B = {0.03, Name "plate half width, y (m)"},
                T = {0.03, Name "plate thickness (m)"} ];
th = theta*Pi/180;
ax = Sin(th); az = -Cos(th);                 // unit axis along the velocity
cx = 0; cz = gap + 0.5*D*Sin(th);            // centre of the front face
Cylinder(1) = {cx, 0, cz, -L*ax, 0, -L*az, D/2};   // front face at (cx, cz), body behind it
Box(2) = {-W/2, 0, -T, W, B, T};
Box(3) = {-0.1, 0, -0.1, 0.2, 0.1, 0.2};
BooleanIntersection(4) = { Volume{1}; Delete; }{ Volume{3}; Delete; };
Physical Volume("cylinder") = {4};
Physical Volume("plate") = {2};
e = 1e-5;
sy[] = Surface In BoundingBox{-0.1, -e, -0.1, 0.1, e, 0.1};
Physical Surface("sym_y0") = {sy[]};
Field[1] = Box;
Field[1].VIn = h; Field[1].VOut = 4*h;
Field[1].XMin = -0.012; Field[1].XMax = 0.02; Field[1].YMin = -0.001; Field[1].YMax = 0.012;
Field[1].ZMin = -0.016; Field[1].ZMax = 0.02; Field[1].Thickness = 0.01;
Background Field = 1;
Mesh.CharacteristicLengthExtendFromBoundary = 0;
Mesh.CharacteristicLengthFromPoints = 0;
Mesh.CharacteristicLengthMax = 4*h;
