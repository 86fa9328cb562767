// Example 03: a deformable block thrown obliquely onto a deformable slab.
//   slab:  [0, 3] x [0, 0.4], held at its base (Physical Curve "slab_base")
//   block: [0.2, 1.2] x [0.42, 0.67] (2 cm above the slab, so the meshes do not connect)
// Mesh size comes from the scenario (mesh_size).
Point(1) = {0, 0, 0};      Point(2) = {3, 0, 0};      Point(3) = {3, 0.4, 0};
Point(4) = {0, 0.4, 0};
Point(5) = {0.2, 0.42, 0}; Point(6) = {1.2, 0.42, 0}; Point(7) = {1.2, 0.67, 0};
Point(8) = {0.2, 0.67, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1};
Plane Surface(2) = {2};
Physical Surface("slab") = {1};
Physical Surface("block") = {2};
Physical Curve("slab_base") = {1};
