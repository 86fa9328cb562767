// Thick-walled ring, inner radius 0.5 m, outer 1 m, centred at the origin, for the Lame test
// (tests/verification/integrate/loads_test.cpp). Physical curves "outer" and "inner".
lc = 0.1;
a = 0.5;
b = 1.0;
Point(1) = {0, 0, 0, lc};
Point(2) = {b, 0, 0, lc};
Point(3) = {0, b, 0, lc};
Point(4) = {-b, 0, 0, lc};
Point(5) = {0, -b, 0, lc};
Point(6) = {a, 0, 0, lc};
Point(7) = {0, a, 0, lc};
Point(8) = {-a, 0, 0, lc};
Point(9) = {0, -a, 0, lc};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Circle(5) = {6, 1, 7};
Circle(6) = {7, 1, 8};
Circle(7) = {8, 1, 9};
Circle(8) = {9, 1, 6};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};
Physical Surface("ring") = {1};
Physical Curve("outer") = {1, 2, 3, 4};
Physical Curve("inner") = {5, 6, 7, 8};
