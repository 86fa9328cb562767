// Cantilever beam 2 m x 0.2 m, clamped on its left edge.
// Mesh size comes from the scenario (mesh_size); Physical groups name what the scenario uses.
L = 2.0;
H = 0.2;
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
Physical Surface("beam") = {1};
Physical Curve("clamp") = {4};
Physical Curve("tip") = {2};
