// Uniform solid cylinder along x (evas FE pipeline, docs/fe-pipeline.md).
// Parameters (override with gmsh -setnumber NAME VALUE), lengths in mm:
//   radius     cylinder radius
//   length     cylinder length (x from 0 to length)
//   mesh_size  largest element edge
// Output: second-order tetrahedra (C3D10 in the .inp), physical volume "body",
// physical surfaces "end0" (x = 0), "end1" (x = length) and "lateral"
// (written as node sets by Mesh.SaveGroupsOfNodes).
SetFactory("OpenCASCADE");

DefineConstant[ radius = 20 ];
DefineConstant[ length = 400 ];
DefineConstant[ mesh_size = 10 ];

Cylinder(1) = {0, 0, 0, length, 0, 0, radius};

eps = 1e-6 * length;
end0() = Surface In BoundingBox{-eps, -radius - eps, -radius - eps, eps, radius + eps, radius + eps};
end1() = Surface In BoundingBox{length - eps, -radius - eps, -radius - eps, length + eps,
                                radius + eps, radius + eps};
all() = Boundary{ Volume{1}; };
lateral() = all();
lateral() -= end0();
lateral() -= end1();

Physical Volume("body") = {1};
Physical Surface("end0") = {end0()};
Physical Surface("end1") = {end1()};
Physical Surface("lateral") = {lateral()};

Mesh.CharacteristicLengthMax = mesh_size;
Mesh.CharacteristicLengthMin = 0.1 * mesh_size;
Mesh.CharacteristicLengthFromCurvature = 0;
Mesh.ElementOrder = 2;
Mesh.SecondOrderLinear = 0;
Mesh.SaveGroupsOfNodes = 1;
