// Self-contact: one elastic C-shaped body (a clamp), opening towards +x,
// moving at 100 m/s onto a rigid wall z = 0. Two arms 4 mm thick, 30 mm
// long, 0.2 mm apart, joined by a 4 mm bridge at x < 0; a slab 4 mm deep
// (y), half of it modelled (symmetry plane y = 0), metres.
SetFactory("OpenCASCADE");
DefineConstant[ h = {1.0e-3, Name "element size (m)"},
                L = {0.03, Name "arm length (m)"},
                t = {0.004, Name "arm thickness (m)"},
                g = {0.2e-3, Name "gap between the arms (m)"},
                b = {0.004, Name "bridge thickness (m)"},
                W = {0.004, Name "half depth of the slab (m)"} ];
Box(1) = {0, 0, 0, L, W, t};
Box(2) = {0, 0, t + g, L, W, t};
Box(3) = {-b, 0, 0, b, W, 2*t + g};
BooleanUnion(4) = { Volume{3}; Delete; }{ Volume{1, 2}; Delete; };
Physical Volume("clamp") = {4};
e = 1e-6;
sy[] = Surface In BoundingBox{-1, -e, -1, 1, e, 1};
Physical Surface("sym_y0") = {sy[]};
Mesh.CharacteristicLengthMin = h;
Mesh.CharacteristicLengthMax = h;
