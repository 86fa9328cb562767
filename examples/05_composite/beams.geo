// Two identical cantilevers 2 m x 0.2 m, clamped on their left edges: beam "a" (y in [0, 0.2])
// and beam "b" (y in [-1, -0.8]). The scenario runs "a" as composite elements and "b" as plain
// CSTs on the same 6-node mesh. beams.msh was made from this file with
//   gmsh -2 -order 2 -format msh41 beams.geo -o beams.msh
L = 2.0;
H = 0.2;
lc = 0.05;  // 4 six-node triangles through the thickness
Point(1) = {0, 0, 0, lc};
Point(2) = {L, 0, 0, lc};
Point(3) = {L, H, 0, lc};
Point(4) = {0, H, 0, lc};
Point(5) = {0, -1, 0, lc};
Point(6) = {L, -1, 0, lc};
Point(7) = {L, -1 + H, 0, lc};
Point(8) = {0, -1 + H, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {5, 6};
Line(6) = {6, 7};
Line(7) = {7, 8};
Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1};
Plane Surface(2) = {2};
Transfinite Curve{1, 3, 5, 7} = 41;  // structured mesh: the same triangles in both beams
Transfinite Curve{2, 4, 6, 8} = 5;
Transfinite Surface{1};
Transfinite Surface{2};
Physical Surface("a") = {1};
Physical Surface("b") = {2};
Physical Curve("clamp_a") = {4};
Physical Curve("clamp_b") = {8};
Physical Point("tip_a") = {2};
Physical Point("tip_b") = {6};
