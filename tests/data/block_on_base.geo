// Two bodies in one geometry, told apart by physical surface groups (scenario reader tests).
//   block: [0.5, 1.0] x [0.21, 0.71]   (0.01 m above the base, so the meshes do not connect)
//   base:  [0.0, 2.0] x [0.0, 0.2]
Point(1) = {0, 0, 0};   Point(2) = {2, 0, 0};   Point(3) = {2, 0.2, 0}; Point(4) = {0, 0.2, 0};
Point(5) = {0.5, 0.21, 0}; Point(6) = {1.0, 0.21, 0}; Point(7) = {1.0, 0.71, 0};
Point(8) = {0.5, 0.71, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1};
Plane Surface(2) = {2};
Physical Surface("base") = {1};
Physical Surface("block") = {2};
Physical Curve("base_bottom") = {1};
Physical Curve("block_top") = {7};
Physical Point("block_corner") = {5};
