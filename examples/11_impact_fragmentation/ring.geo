// Example 11, optional part of spec V8: an expanding ring for the fragment size. Mean radius
// 0.1 m, thickness 2.5 mm (inner 98.75 mm, outer 101.25 mm), centred at the origin: thinner than
// the fragments it is checked for (>= 3.9 mm, theory §9.8), so it segments as the 1-D bar of the
// reference. Every internal edge becomes a cohesive joint. Mesh size: ring.toml (mesh_size).
Ri = 0.09875;              // m: inner radius
Ro = 0.10125;              // m: outer radius
Point(1) = {0, 0, 0};
Point(2) = {Ri, 0, 0}; Point(3) = {0, Ri, 0}; Point(4) = {-Ri, 0, 0}; Point(5) = {0, -Ri, 0};
Point(6) = {Ro, 0, 0}; Point(7) = {0, Ro, 0}; Point(8) = {-Ro, 0, 0}; Point(9) = {0, -Ro, 0};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Circle(5) = {6, 1, 7}; Circle(6) = {7, 1, 8}; Circle(7) = {8, 1, 9}; Circle(8) = {9, 1, 6};
Curve Loop(1) = {5, 6, 7, 8};
Curve Loop(2) = {1, 2, 3, 4};
Plane Surface(1) = {1, 2};
Physical Surface("ring") = {1};
