// Two steel bars of square section (4 mm, 20 mm long) crossing at right
// angles, each turned 45 degrees about its axis so that an edge faces the
// other bar's edge: 'upper' along x, its lower edge at z = 0.3 mm, 'lower'
// along y, its upper edge at z = -0.3 mm. Each bar is shifted half an
// element along its axis, so that no node lies at the crossing (x = y = 0):
// only edge-to-edge contact can stop the edges passing through each other
// (issue 13, item 4). Units mm.
SetFactory("OpenCASCADE");
DefineConstant[ h = {1.0, Name "h"} ];
Box(1) = {-10.5, -2, -2, 20, 4, 4};
Rotate {{1, 0, 0}, {0, 0, 0}, Pi/4} { Volume{1}; }
Translate {0, 0, 2*Sqrt(2) + 0.3} { Volume{1}; }
Box(2) = {-2, -10.5, -2, 4, 20, 4};
Rotate {{0, 1, 0}, {0, 0, 0}, Pi/4} { Volume{2}; }
Translate {0, 0, -2*Sqrt(2) - 0.3} { Volume{2}; }
Physical Volume("upper") = {1};
Physical Volume("lower") = {2};
Mesh.CharacteristicLengthMin = h;
Mesh.CharacteristicLengthMax = h;
