// Disk of radius 0.1 m centred at (0, 0.1005) m (0.5 mm above the slab top y = 0) for the Python
// drop test (examples/python/drop_test.py). Element size: the script's mesh_size.
lc = 0.02;
Point(1) = {0, 0.1005, 0, lc};
Point(2) = {0.1, 0.1005, 0, lc};
Point(3) = {0, 0.2005, 0, lc};
Point(4) = {-0.1, 0.1005, 0, lc};
Point(5) = {0, 0.0005, 0, lc};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("disk") = {1};
Physical Curve("rim") = {1, 2, 3, 4};
