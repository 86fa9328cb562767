// Example 11: the plate, 0.3 m x 0.03 m, top face y = 0 (the disc falls onto it). The body is
// fixed (every node stays put: a rigid plate), so the mesh only carries the contact: coarse.
W = 0.15;                  // m: half width
T = 0.03;                  // m: thickness
Point(1) = {-W, -T, 0}; Point(2) = {W, -T, 0}; Point(3) = {W, 0, 0}; Point(4) = {-W, 0, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("plate") = {1};
