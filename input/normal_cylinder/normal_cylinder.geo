// Normal impact of the seed paper's compact steel cylinder (L = D = 10 mm)
// on the 30 mm steel plate: the Fig. 3 geometry at zero obliquity.
// Set before the include, whose DefineConstants then keep these; h = 0.8 mm
// is the mesh of doc/validation.md 4k (87020 tetrahedra).
DefineConstant[ h = {0.8e-3, Name "element size near the impact (m)"},
                theta = {0, Name "obliquity (degrees from the plate normal)"} ];
Include "../oblique_cylinder/oblique_cylinder.geo";
