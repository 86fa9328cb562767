// A geometry without a surface (mpi.same_failure.bad_mesh): read_mesh finds no triangles and
// throws an InputError on process 0, which the other processes receive (mesh_broadcast.hpp).
Point(1) = {0, 0, 0, 0.1};
Point(2) = {1, 0, 0, 0.1};
Line(1) = {1, 2};
