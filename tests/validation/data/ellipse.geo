// Ellipse with semi-axes 1 m and 0.6 m (paper Fig. 19-20 analogue: unstructured mesh).
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0}; Point(3) = {0, 0.6, 0}; Point(4) = {-1, 0, 0}; Point(5) = {0, -0.6, 0};
Ellipse(1) = {2, 1, 2, 3}; Ellipse(2) = {3, 1, 2, 4}; Ellipse(3) = {4, 1, 2, 5};
Ellipse(4) = {5, 1, 2, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("ellipse") = {1};
