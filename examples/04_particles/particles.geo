// Example 04: a raster of N x N irregular deformable particles in a closed box (the paper's
// Fig. 1). Each particle is a star-shaped polygon of 5-8 vertices at jittered angles and radii
// around its raster point, fanned from its centre: one triangular surface (one element at
// these mesh sizes) per edge. The "random" numbers are a fixed hash of the particle index
// (fract(sin(x) * 43758.5453)), so the mesh is the same on every machine and run. Meshing time
// grows with N: N = 50 takes ~15 s, N = 100 (the benchmark scene's 10^4 particles) ~1-2 min. Particles go into 8 physical groups p0..p7
// by hash; the scenario gives each group its own initial velocity. The walls are one ring-shaped
// surface "walls" around [0, N s] x [0, N s].
If (!Exists(N))
  N = 50;       // particles per side (particles_10k.geo sets 100 and includes this file)
EndIf
s = 0.01;       // raster pitch [m]
R = 0.0045;     // largest vertex distance from the raster point [m]
T = 0.02;       // wall thickness [m]
lw = 0.005;     // wall mesh size [m]

For g In {0:7}
  grp~{g}[] = {};
EndFor

For j In {0:N-1}
  For i In {0:N-1}
    id = j * N + i;
    cx = (i + 0.5) * s;
    cy = (j + 0.5) * s;
    h = Fabs(Sin(id * 12.9898 + 78.233) * 43758.5453);
    k = 5 + Floor((h - Floor(h)) * 4);
    h = Fabs(Sin(id * 39.3468 + 11.135) * 24634.6345);
    a0 = 2 * Pi * (h - Floor(h));
    fan[] = {};
    pc = newp;
    Point(pc) = {cx, cy, 0, 2 * R};
    For q In {0:k-1}
      h = Fabs(Sin(id * 7.233 + q * 91.17 + 3.1) * 15731.743);
      a = a0 + 2 * Pi * (q + 0.4 * (h - Floor(h) - 0.5)) / k;
      h = Fabs(Sin(id * 5.977 + q * 63.71 + 9.4) * 31337.113);
      r = R * (0.6 + 0.4 * (h - Floor(h)));
      pp~{q} = newp;
      Point(pp~{q}) = {cx + r * Cos(a), cy + r * Sin(a), 0, 2 * R};
    EndFor
    // fan: one triangular surface per polygon edge, sharing the centre and the spokes
    For q In {0:k-1}
      sp~{q} = newl;
      Line(sp~{q}) = {pc, pp~{q}};
    EndFor
    For q In {0:k-1}
      l = newl;
      Line(l) = {pp~{q}, pp~{(q + 1) % k}};
      cl = newll;
      Curve Loop(cl) = {sp~{q}, l, -sp~{(q + 1) % k}};
      sf = news;
      Plane Surface(sf) = {cl};
      fan[] += {sf};
    EndFor
    h = Fabs(Sin(id * 3.7719 + 45.21) * 12345.678);
    g = Floor((h - Floor(h)) * 8);
    grp~{g}[] += {fan[]};
  EndFor
EndFor

// walls: ring between the outer and the inner rectangle
W = N * s;
p1 = newp; Point(p1) = {-T, -T, 0, lw};    Point(p1 + 1) = {W + T, -T, 0, lw};
Point(p1 + 2) = {W + T, W + T, 0, lw};     Point(p1 + 3) = {-T, W + T, 0, lw};
Point(p1 + 4) = {0, 0, 0, lw};             Point(p1 + 5) = {W, 0, 0, lw};
Point(p1 + 6) = {W, W, 0, lw};             Point(p1 + 7) = {0, W, 0, lw};
l1 = newl;
For q In {0:3}
  Line(l1 + q) = {p1 + q, p1 + (q + 1) % 4};
  Line(l1 + 4 + q) = {p1 + 4 + q, p1 + 4 + (q + 1) % 4};
EndFor
c1 = newll; Curve Loop(c1) = {l1, l1 + 1, l1 + 2, l1 + 3};
c2 = newll; Curve Loop(c2) = {l1 + 4, l1 + 5, l1 + 6, l1 + 7};
sw = news; Plane Surface(sw) = {c1, c2};

Physical Surface("walls") = {sw};
For g In {0:7}
  Physical Surface(Sprintf("p%g", g)) = {grp~{g}[]};
EndFor
