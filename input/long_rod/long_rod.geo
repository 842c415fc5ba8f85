// Long-rod penetration (Lanz-Odermatt validation): a tungsten-alloy rod,
// diameter D, length 10 D, 0.1 mm above a thick steel block; a quarter
// model about the rod axis z (symmetry planes x = 0 and y = 0); metres.
// The block is a quarter cylinder of radius 6 D and depth 20 D, meshed
// with h near the axis (out to 2 D) and coarser outside.
SetFactory("OpenCASCADE");
DefineConstant[ h = {0.6e-3, Name "element size near the axis"},
                D = {5.0e-3, Name "rod diameter"} ];
L = 10*D; R = 6*D; T = 20*D; gap = 0.1e-3;
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
