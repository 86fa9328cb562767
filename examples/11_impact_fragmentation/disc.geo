// Example 11: the disc, D = 0.1 m, above the plate (plate.geo, top face y = 0) with a gap of
// 0.2 mm at its lowest point. Every internal edge becomes a cohesive joint ([material.fracture]).
// Mesh seed (spec fracture.md §11 V8: "3 mesh seeds", different unstructured meshes): `seed`
// picks the Gmsh 2-D algorithm (seed mod 3: Frontal-Delaunay, Delaunay, MeshAdapt) and turns
// the four boundary points that start the circle's discretisation by seed x 37 degrees, so each
// seed is a different mesh (not a rotated copy: the algorithms differ) with its own node
// positions on the circle. run.py writes a copy with seed = 1, 2, 3.
// Mesh size comes from the scenario (mesh_size).
seed = 1;
R = 0.05;                  // m: disc radius
gap = 2.0e-4;              // m: initial gap to the plate
yc = R + gap;              // m: centre height
th = seed * 37 * Pi / 180; // rad: turn of the boundary points
algo[] = {6, 5, 1};
Mesh.Algorithm = algo[seed % 3];
Mesh.RandomSeed = seed;
Point(1) = {0, yc, 0};
For k In {0:3}
  Point(2 + k) = {R * Cos(th + k * Pi / 2), yc + R * Sin(th + k * Pi / 2), 0};
EndFor
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("disc") = {1};
