// Example 08: Brazilian disc (flattened, ISRM 1978 / Wang et al. 2004 style) between rigid platens.
//   disc: D = 50 mm centred at the origin, cut flat at top and bottom over a chord of width
//         b = 4 mm = 0.08 D (the loading strips of spec V4: the load enters over b, not a line)
//   the loaded diameter x = 0 is a mesh line (two half discs sharing it, one conforming mesh):
//   joints lie along it, so the splitting crack can run straight, as in the test; without it
//   (disc_unaligned.geo) the crack has to zig-zag along inclined edges (README)
//   the platens are in platens.geo
// Mesh size comes from the scenario (mesh_size).
R = 0.025;                 // m: disc radius
b = 0.004;                 // m: width of the flats (loading strips), b/D = 0.08
yf = Sqrt(R*R - b*b/4);    // m: height of the flats
Point(1) = {0, 0, 0};
Point(2) = { b/2,  yf, 0}; Point(3) = {-b/2,  yf, 0};
Point(4) = {-b/2, -yf, 0}; Point(5) = { b/2, -yf, 0};
Point(6) = {-R, 0, 0};     Point(7) = { R, 0, 0};
Point(8) = {0, yf, 0};     Point(9) = {0, -yf, 0};
Line(1) = {2, 8}; Line(2) = {8, 3};        // top flat, right and left halves
Circle(3) = {3, 1, 6}; Circle(4) = {6, 1, 4};
Line(5) = {4, 9}; Line(6) = {9, 5};        // bottom flat, left and right halves
Circle(7) = {5, 1, 7}; Circle(8) = {7, 1, 2};
Line(9) = {9, 8};                          // the loaded diameter
Curve Loop(1) = {2, 3, 4, 5, 9};           // left half
Curve Loop(2) = {6, 7, 8, 1, -9};          // right half
Plane Surface(1) = {1};
Plane Surface(2) = {2};
Physical Surface("disc") = {1, 2};
Physical Curve("flat_top") = {1, 2};
Physical Curve("flat_bottom") = {5, 6};
Physical Curve("diameter") = {9};
