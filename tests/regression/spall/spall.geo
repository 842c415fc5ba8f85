// Flyer plate (2 mm) onto a target plate (6 mm), both 1 mm x 1 mm across
// with symmetry planes on the sides (uniaxial strain), structured
// tetrahedra of 0.1 mm along the axis, conforming contact faces (metres).
// The flyer moves along -z onto the target's top face at z = 0; the
// target spans z = -6 mm .. 0.
DefineConstant[ a = {0.001, Name "column width (m)"},
                tf = {0.002, Name "flyer thickness (m)"},
                tt = {0.006, Name "target thickness (m)"},
                gap = {0.01e-3, Name "gap between flyer and target (m)"},
                h = {0.1e-3, Name "element size along the axis (m)"},
                nxy = {2, Name "cells across"} ];
Point(1) = {0, 0, -tt}; Point(2) = {a, 0, -tt}; Point(3) = {a, a, -tt}; Point(4) = {0, a, -tt};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = nxy + 1;
Transfinite Surface{1};
t[] = Extrude{0, 0, tt}{ Surface{1}; Layers{Round(tt/h)}; };
Point(111) = {0, 0, gap}; Point(112) = {a, 0, gap}; Point(113) = {a, a, gap}; Point(114) = {0, a, gap};
Line(111) = {111, 112}; Line(112) = {112, 113}; Line(113) = {113, 114}; Line(114) = {114, 111};
Curve Loop(111) = {111, 112, 113, 114};
Plane Surface(111) = {111};
Transfinite Curve{111, 112, 113, 114} = nxy + 1;
Transfinite Surface{111};
f[] = Extrude{0, 0, tf}{ Surface{111}; Layers{Round(tf/h)}; };
Physical Volume("target") = {t[1]};
Physical Volume("flyer") = {f[1]};
Physical Surface("side_x0") = {t[5], f[5]};
Physical Surface("side_x1") = {t[3], f[3]};
Physical Surface("side_y0") = {t[2], f[2]};
Physical Surface("side_y1") = {t[4], f[4]};
