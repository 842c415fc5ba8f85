// Normal impact of the seed paper's compact steel cylinder (L = D = 10 mm)
// on the 30 mm steel plate: the Fig. 3 geometry at zero obliquity.
theta = 0;
Include "../oblique_cylinder/oblique_cylinder.geo";
