// Example 10: notched three-point-bending beam (spec V6), per unit thickness.
//   depth D, span S = 4 D (supports at x = +-S/2 on the bottom face y = 0), length S + D/2
//   (overhang D/4 each side), load at the top centre (0, D).
//   notch: the line x = 0 from the mouth (0, 0) to the tip (0, a0), a0 = D/2, a zero-width
//   notch made of pre-broken joints (scenario `prebroken = ["notch"]`).
//   ligament: the line x = 0 from the tip to the top, a mesh line (joints along it: the
//   "aligned" mesh of spec V6). Set aligned = 0 for the unstructured variant (no line there).
//   CMOD: two points on the bottom face at x = -e and x = +e next to the mouth.
// run.py rewrites the parameter lines D, h, aligned, band (keep their form "name = value;").
// Mesh: h near the ligament (|x| <= band D), growing to the scenario's mesh_size away from it.
D = 0.05;                  // m: depth
h = 0.001;                 // m: mesh size at the ligament
aligned = 1;               // 1: mesh line along the ligament; 0: none (unstructured)
band = 0.25;               // -: mesh size h in |x| <= band D, growing to mesh_size over D/2
S = 4 * D;                 // m: span
L = S + D / 2;             // m: length
a0 = D / 2;                // m: notch depth
e = h;                     // m: CMOD points at x = -e and +e
Point(1) = {-L/2, 0, 0};  Point(2) = {-S/2, 0, 0}; Point(3) = {-e, 0, 0};
Point(4) = {0, 0, 0};     Point(5) = {e, 0, 0};    Point(6) = {S/2, 0, 0};
Point(7) = {L/2, 0, 0};   Point(8) = {L/2, D, 0};  Point(9) = {0, D, 0};
Point(10) = {-L/2, D, 0}; Point(11) = {0, a0, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6};
Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 9}; Line(9) = {9, 10}; Line(10) = {10, 1};
Line(11) = {4, 11};        // notch
Line(12) = {11, 9};        // ligament
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
Plane Surface(1) = {1};
Line{11} In Surface{1};
If (aligned == 1)
  Line{12} In Surface{1};
EndIf
Field[1] = Box;
Field[1].VIn = h;
Field[1].VOut = 1.0;       // capped by the scenario's mesh_size (Mesh.MeshSizeMax)
Field[1].XMin = -band * D; Field[1].XMax = band * D;
Field[1].YMin = -1; Field[1].YMax = 1;
Field[1].Thickness = D / 2;
Background Field = 1;
Physical Surface("beam") = {1};
Physical Curve("notch") = {11};
If (aligned == 1)
  Physical Curve("ligament") = {12};
EndIf
Physical Point("support_left") = {2};
Physical Point("support_right") = {6};
Physical Point("load") = {9};
Physical Point("mouth_left") = {3};
Physical Point("mouth_right") = {5};
