// Example 09: UCS specimen, 50 mm wide x 100 mm high, centred at the origin, with the two rigid
// platens (70 mm x 10 mm) touching its ends (no gap, no overlap). The platens are separate
// surfaces with their own nodes (no shared points), so they are separate bodies.
// Mesh size comes from the scenario (mesh_size); the platens are meshed at the same size.
w = 0.025;                 // m: half width of the specimen
H = 0.050;                 // m: half height of the specimen
W = 0.035;                 // m: half width of a platen
T = 0.010;                 // m: platen thickness
Point(1) = {-w, -H, 0}; Point(2) = {w, -H, 0}; Point(3) = {w, H, 0}; Point(4) = {-w, H, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
// top platen
Point(11) = {-W, H, 0}; Point(12) = {W, H, 0}; Point(13) = {W, H + T, 0}; Point(14) = {-W, H + T, 0};
Line(11) = {11, 12}; Line(12) = {12, 13}; Line(13) = {13, 14}; Line(14) = {14, 11};
Curve Loop(11) = {11, 12, 13, 14};
Plane Surface(11) = {11};
// bottom platen
Point(21) = {-W, -H - T, 0}; Point(22) = {W, -H - T, 0}; Point(23) = {W, -H, 0}; Point(24) = {-W, -H, 0};
Line(21) = {21, 22}; Line(22) = {22, 23}; Line(23) = {23, 24}; Line(24) = {24, 21};
Curve Loop(21) = {21, 22, 23, 24};
Plane Surface(21) = {21};
Physical Surface("specimen") = {1};
Physical Surface("platen_top") = {11};
Physical Surface("platen_bottom") = {21};
Physical Curve("specimen_top") = {3};
Physical Curve("specimen_bottom") = {1};
