// Self-contact, plane strain: the cross-section of the 3D clamp
// (tests/regression/self_contact) in z = 0, y its fall direction. One
// elastic C-shaped body opening towards +x, moving at 100 m/s onto a rigid
// wall y = 0: two arms 4 mm thick, 30 mm long, 0.2 mm apart, joined by a
// 4 mm bridge at x < 0; metres. Unstructured triangles of size h (the
// arms' faces across the gap do not conform).
SetFactory("OpenCASCADE");
DefineConstant[ h = {0.5e-3, Name "element size (m)"},
                L = {0.03, Name "arm length (m)"},
                t = {0.004, Name "arm thickness (m)"},
                g = {0.2e-3, Name "gap between the arms (m)"},
                b = {0.004, Name "bridge thickness (m)"} ];
Rectangle(1) = {0, 0, 0, L, t};
Rectangle(2) = {0, t + g, 0, L, t};
Rectangle(3) = {-b, 0, 0, b, 2*t + g};
BooleanUnion(4) = { Surface{3}; Delete; }{ Surface{1, 2}; Delete; };
Physical Surface("clamp") = {4};
Mesh.CharacteristicLengthMin = h;
Mesh.CharacteristicLengthMax = h;
