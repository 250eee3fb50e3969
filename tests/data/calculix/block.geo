// Fixture for tests/test_calculix.cpp: a 20 x 20 x 60 mm steel block, coarse C3D10 (mesh size 25).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 60, 20, 20};
Physical Volume("body") = {1};
Physical Surface("x0") = {1};
Mesh.CharacteristicLengthMax = 25;
Mesh.CharacteristicLengthMin = 20;
Mesh.ElementOrder = 2;
Mesh.SaveGroupsOfNodes = 1;
