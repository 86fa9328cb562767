// tests/mpi/units_block.toml: a 0.4 m x 0.4 m block, its bottom edge held (mesh size from the
// scenario).
Point(1) = {0, 0, 0}; Point(2) = {0.4, 0, 0}; Point(3) = {0.4, 0.4, 0}; Point(4) = {0, 0.4, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("block") = {1};
Physical Curve("bottom") = {1};
