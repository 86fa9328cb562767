// Example 04 at the size of the paper's Fig. 1: 100 x 100 = 10^4 particles (same shapes, pitch,
// walls and groups as particles.geo, which this file includes). Gmsh needs a minute or two.
N = 100;
Include "particles.geo";
