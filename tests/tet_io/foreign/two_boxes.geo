SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.4, 1, 1};
Box(2) = {0.4, 0, 0, 0.6, 1, 1};
Coherence;
Physical Volume("bone", 2) = {1};
Physical Volume("soft tissue", 5) = {2};
Physical Surface("skin", 9) = {1};
Mesh.CharacteristicLengthMax = 1.0;
