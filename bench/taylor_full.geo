// The full OFHC Taylor cylinder of the OpenRadioss side-by-side (issue 12):
// L0 = 25.4 mm, D0 = 7.62 mm (units mm), axis +z, impact face at z = 0,
// physical volume "rod", no symmetry planes. make bench meshes it with
//   env -i PATH=/usr/bin:/bin gmsh -3 -v 0 -nt 1 -setnumber h 0.62 -format msh22 taylor_full.geo -o full_coarse.msh
//   env -i PATH=/usr/bin:/bin gmsh -3 -v 0 -nt 1 -setnumber h 0.31 -format msh22 taylor_full.geo -o full_fine.msh
// in the folder /tmp/udar-bench-mesh holding a copy of this file: with
// gmsh 4.8.4 the 3D mesh changes with the working folder's path, the size
// of the environment and the thread count, and is the same from call to
// call when all three are (19,525 and 148,103 tets on the machine of
// doc/performance.md).
SetFactory("OpenCASCADE");
If (!Exists(h))
  h = 0.62;
EndIf
R  = 3.81;
L0 = 25.4;
Cylinder(1) = {0, 0, 0, 0, 0, L0, R};
Physical Volume("rod", 1) = {1};
Mesh.CharacteristicLengthMin = h;
Mesh.CharacteristicLengthMax = h;
Mesh.CharacteristicLengthFromCurvature = 0;
Mesh.CharacteristicLengthExtendFromBoundary = 1;
Mesh.Algorithm = 6;      // Frontal-Delaunay 2D
Mesh.Algorithm3D = 10;   // HXT
Mesh.Optimize = 1;
Mesh.OptimizeThreshold = 0.5;
Mesh.ElementOrder = 1;
