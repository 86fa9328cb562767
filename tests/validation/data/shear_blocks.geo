// Validation V2 of spec fracture.md §11 (tests/validation/cases/shear.hpp): the two blocks of
// examples/07_pull_apart/blocks.geo (0.02 m x 0.01 m each, 5 joints of h = 0.004 m on their
// common edge y = 0.01 m, structured), with the blocks as surface groups "lower" and "upper"
// so that supports and grips can act on a whole block.
W = 0.02;
H = 0.01;
Point(1) = {0, 0, 0};
Point(2) = {W, 0, 0};
Point(3) = {W, H, 0};
Point(4) = {0, H, 0};
Point(5) = {W, 2 * H, 0};
Point(6) = {0, 2 * H, 0};
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
Transfinite Curve {1, 3, 6} = 6;     // 5 edges of 0.004 m across
Transfinite Curve {2, 4, 5, 7} = 4;  // 3 edges of 0.00333 m through each block
Transfinite Surface {1};
Transfinite Surface {2};
Physical Surface("blocks") = {1, 2};
Physical Surface("lower") = {1};
Physical Surface("upper") = {2};
Physical Curve("joint") = {3};
Physical Curve("bottom") = {1};
Physical Curve("top") = {6};
