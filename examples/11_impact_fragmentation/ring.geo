// Example 11, optional part of spec V8: an expanding ring for Grady's fragment size. Mean radius
// 0.1 m, thickness 10 mm (inner 95 mm, outer 105 mm), centred at the origin. Every internal edge
// becomes a cohesive joint. Mesh size comes from the scenario (ring.toml, mesh_size).
Ri = 0.095;                // m: inner radius
Ro = 0.105;                // m: outer radius
Point(1) = {0, 0, 0};
Point(2) = {Ri, 0, 0}; Point(3) = {0, Ri, 0}; Point(4) = {-Ri, 0, 0}; Point(5) = {0, -Ri, 0};
Point(6) = {Ro, 0, 0}; Point(7) = {0, Ro, 0}; Point(8) = {-Ro, 0, 0}; Point(9) = {0, -Ro, 0};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Circle(5) = {6, 1, 7}; Circle(6) = {7, 1, 8}; Circle(7) = {8, 1, 9}; Circle(8) = {9, 1, 6};
Curve Loop(1) = {5, 6, 7, 8};
Curve Loop(2) = {1, 2, 3, 4};
Plane Surface(1) = {1, 2};
Physical Surface("ring") = {1};
