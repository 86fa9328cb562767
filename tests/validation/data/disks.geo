// Two disks of radius 1 m, centres (-1.005, 0) and (1.005, 0): a 1 cm gap (spec §5.2).
// Mesh size from the caller (read_mesh(path, h)).
R = 1.0;
c = 1.005;
Point(1) = {-c, 0, 0};
Point(2) = {-c + R, 0, 0}; Point(3) = {-c, R, 0}; Point(4) = {-c - R, 0, 0}; Point(5) = {-c, -R, 0};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Point(11) = {c, 0, 0};
Point(12) = {c + R, 0, 0}; Point(13) = {c, R, 0}; Point(14) = {c - R, 0, 0}; Point(15) = {c, -R, 0};
Circle(11) = {12, 11, 13}; Circle(12) = {13, 11, 14}; Circle(13) = {14, 11, 15}; Circle(14) = {15, 11, 12};
Curve Loop(2) = {11, 12, 13, 14};
Plane Surface(2) = {2};
Physical Surface("left") = {1};
Physical Surface("right") = {2};
