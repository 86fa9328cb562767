// A 0.2 m x 0.1 m block lying at zero depth on a 2 m x 0.1 m slab (contact stability test).
Point(1) = {0, 0, 0};   Point(2) = {2, 0, 0};   Point(3) = {2, 0.1, 0}; Point(4) = {0, 0.1, 0};
Point(5) = {0.2, 0.1, 0}; Point(6) = {0.4, 0.1, 0}; Point(7) = {0.4, 0.2, 0};
Point(8) = {0.2, 0.2, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1};
Plane Surface(2) = {2};
Physical Surface("slab") = {1};
Physical Surface("block") = {2};
Physical Curve("slab_base") = {1};
