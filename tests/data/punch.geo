// A wedge whose tip, at (0.3, 0.9), lies 0.1 m inside the unit square of square.geo, between
// the square's boundary nodes (tests/input/io/initial_overlap_test.cpp: the depth of a point
// inside a body with fracture is measured to its outer boundary, not to a joint face).
lc = 0.05;
Point(1) = {0.3, 0.9, 0, lc};
Point(2) = {0.4, 1.5, 0, lc};
Point(3) = {0.2, 1.5, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Physical Surface("punch") = {1};
