// Example 08, variant without the diameter line (run.py --unaligned): the crack has to follow
// the edges of an unstructured mesh across the loaded diameter. Otherwise as disc.geo.
//   disc: D = 50 mm centred at the origin, cut flat at top and bottom over a chord of width
//         b = 4 mm = 0.08 D (the loading strips of spec V4: the load enters over b, not a line)
//   the platens are in platens.geo
// Mesh size comes from the scenario (mesh_size).
R = 0.025;                 // m: disc radius
b = 0.004;                 // m: width of the flats (loading strips), b/D = 0.08
yf = Sqrt(R*R - b*b/4);    // m: height of the flats
Point(1) = {0, 0, 0};
Point(2) = { b/2,  yf, 0}; Point(3) = {-b/2,  yf, 0};
Point(4) = {-b/2, -yf, 0}; Point(5) = { b/2, -yf, 0};
Point(6) = {-R, 0, 0};     Point(7) = { R, 0, 0};
Line(1) = {2, 3};                  // top flat
Circle(2) = {3, 1, 6}; Circle(3) = {6, 1, 4};
Line(4) = {4, 5};                  // bottom flat
Circle(5) = {5, 1, 7}; Circle(6) = {7, 1, 2};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Physical Surface("disc") = {1};
Physical Curve("flat_top") = {1};
Physical Curve("flat_bottom") = {4};
