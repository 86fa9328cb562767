// tests/mpi/ghosts_far_body.toml: a 0.55 m x 0.1 m block 0.5 m right of example 11's disc,
// never in contact with it (mesh size from the scenario).
Point(1) = {0.55, 0, 0}; Point(2) = {1.1, 0, 0}; Point(3) = {1.1, 0.1, 0}; Point(4) = {0.55, 0.1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("far") = {1};
