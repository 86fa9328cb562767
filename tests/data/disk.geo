// Disk of radius 0.1 m centred at (1, 2) for the initial-velocity tests
// (tests/unit/io/velocity_field_test.cpp).
lc = 0.02;
Point(1) = {1, 2, 0, lc};
Point(2) = {1.1, 2, 0, lc};
Point(3) = {1, 2.1, 0, lc};
Point(4) = {0.9, 2, 0, lc};
Point(5) = {1, 1.9, 0, lc};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("disk") = {1};
Physical Curve("rim") = {1, 2, 3, 4};
