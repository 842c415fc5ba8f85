// Long-rod penetration (Lanz-Odermatt validation): a tungsten-alloy rod,
// diameter D, length 10 D, 0.1 mm above a thick steel block; a quarter
// model about the rod axis z (symmetry planes x = 0 and y = 0); metres.
// The block is a quarter cylinder of radius 6 D and depth 20 D, meshed
// with h near the axis (out to 2 D) and coarser outside. The default h =
// 1 mm is the mesh of the validation (doc/validation.md 4i, make validate);
// refine with e.g. gmsh -3 -setnumber h 0.7e-3 long_rod.geo (203005 tetrahedra).
SetFactory("OpenCASCADE");
DefineConstant[ h = {1.0e-3, Name "element size near the axis (m)"},
                D = {5.0e-3, Name "rod diameter (m)"} ];
// separate, so that their defaults follow a D set on the command line
DefineConstant[ L = {10*D, Name "rod length (m)"},
                R = {6*D, Name "block radius (m)"},
                T = {20*D, Name "block depth (m)"},
                gap = {0.1e-3, Name "gap between rod and block (m)"} ];
Cylinder(1) = {0, 0, gap, 0, 0, L, D/2, Pi/2};
Cylinder(2) = {0, 0, -T, 0, 0, T, R, Pi/2};
Physical Volume("rod") = {1};
Physical Volume("block") = {2};
// the symmetry planes: faces of either volume lying in x = 0 or y = 0
e = 1e-5;
sx[] = Surface In BoundingBox{-e, -e, -T - e, e, R + e, gap + L + e};
sy[] = Surface In BoundingBox{-e, -e, -T - e, R + e, e, gap + L + e};
Physical Surface("sym_x0") = {sx[]};
Physical Surface("sym_y0") = {sy[]};
Field[1] = MathEval;
Field[1].F = Sprintf("%g + (%g - %g)*Max(0, Sqrt(x*x + y*y) - %g)/%g", h, 4*h, h, 2*D, 4*D);
Background Field = 1;
Mesh.CharacteristicLengthExtendFromBoundary = 0;
Mesh.CharacteristicLengthFromPoints = 0;
Mesh.CharacteristicLengthMax = 4*h;
