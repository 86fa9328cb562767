// Steel bar 1 m x 0.05 m; its left end is hit (prescribed velocity pulse).
L = 1.0;
H = 0.05;
Point(1) = {0, 0, 0};
Point(2) = {L, 0, 0};
Point(3) = {L, H, 0};
Point(4) = {0, H, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("bar") = {1};
Physical Curve("struck_end") = {4};
Physical Curve("free_end") = {2};
