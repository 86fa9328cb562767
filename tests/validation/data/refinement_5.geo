// Validation V7 on V1 of spec fracture.md §11 (tests/validation/cases/refinement.hpp): the two
// blocks of examples/07_pull_apart (W x H = 0.02 m x 0.01 m each, joined along their common
// edge, the curve group "joint") turned by 30 degrees about the origin, so the jointed line is
// inclined to the axes; unstructured (Gmsh algorithm 5), mesh_size from the scenario.
W = 0.02;
H = 0.01;
c = Cos(Pi / 6);
s = Sin(Pi / 6);
Point(1) = {0, 0, 0};
Point(2) = {W * c, W * s, 0};
Point(3) = {W * c - H * s, W * s + H * c, 0};
Point(4) = {-H * s, H * c, 0};
Point(5) = {W * c - 2 * H * s, W * s + 2 * H * c, 0};
Point(6) = {-2 * H * s, 2 * H * c, 0};
Line(1) = {1, 2};  // bottom grip
Line(2) = {2, 3};
Line(3) = {3, 4};  // the joint line
Line(4) = {4, 1};
Line(5) = {3, 5};
Line(6) = {5, 6};  // top grip
Line(7) = {6, 4};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {-3, 5, 6, 7};
Plane Surface(1) = {1};
Plane Surface(2) = {2};
Mesh.Algorithm = 5;
Physical Surface("blocks") = {1, 2};
Physical Curve("joint") = {3};
Physical Curve("bottom") = {1};
Physical Curve("top") = {6};
