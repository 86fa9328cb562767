// Example 08: the two rigid platens, 60 mm x 10 mm, touching the flats of disc.geo (no gap, no
// overlap). Every node is prescribed, so the mesh only needs to carry the contact: coarse.
R = 0.025;                 // m: disc radius (as disc.geo)
b = 0.004;                 // m: width of the flats (as disc.geo)
yf = Sqrt(R*R - b*b/4);    // m: height of the flats
W = 0.030;                 // m: half width of a platen
T = 0.010;                 // m: platen thickness
// top platen
Point(11) = {-W, yf, 0}; Point(12) = {W, yf, 0}; Point(13) = {W, yf + T, 0}; Point(14) = {-W, yf + T, 0};
Line(11) = {11, 12}; Line(12) = {12, 13}; Line(13) = {13, 14}; Line(14) = {14, 11};
Curve Loop(11) = {11, 12, 13, 14};
Plane Surface(11) = {11};
// bottom platen
Point(21) = {-W, -yf - T, 0}; Point(22) = {W, -yf - T, 0}; Point(23) = {W, -yf, 0}; Point(24) = {-W, -yf, 0};
Line(21) = {21, 22}; Line(22) = {22, 23}; Line(23) = {23, 24}; Line(24) = {24, 21};
Curve Loop(21) = {21, 22, 23, 24};
Plane Surface(21) = {21};
Physical Surface("platen_top") = {11};
Physical Surface("platen_bottom") = {21};
