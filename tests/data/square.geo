// Unit square [0, 1] x [0, 1] for the mesh-reader tests (tests/unit/io/gmsh_reader_test.cpp).
// The .msh files next to it were generated from this file with
//   gmsh -2 -format msh22|msh41 [-bin] square.geo -o square_<version>_<ascii|bin>.msh
lc = 0.5;
Point(1) = {0, 0, 0, lc};
Point(2) = {1, 0, 0, lc};
Point(3) = {1, 1, 0, lc};
Point(4) = {0, 1, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("block") = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Curve("sides") = {2, 4};
Physical Point("origin") = {1};
