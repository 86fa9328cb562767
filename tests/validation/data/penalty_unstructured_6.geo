// Validation V3 of spec fracture.md §11 (tests/validation/cases/penalty.hpp): the 0.02 m square
// of penalty_structured.geo, unstructured (Gmsh algorithm 6, frontal; mesh_size 0.002 m in
// the scenario). The three unstructured meshes differ only by the meshing algorithm.
L = 0.02;
Point(1) = {0, 0, 0};
Point(2) = {L, 0, 0};
Point(3) = {L, L, 0};
Point(4) = {0, L, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Mesh.Algorithm = 6;
Physical Surface("square") = {1};
Physical Curve("left") = {4};
Physical Curve("right") = {2};
