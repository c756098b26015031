// Stability suite: a ring of outer radius 10 mm and inner radius 9.96 mm centred in its
// 20 x 20 mm bounding box, in MILLIMETRES. At dx = 1 mm the lattice cell centres are at
// half-integer offsets from the centre, so their distances d satisfy d^2 = m(m+1) + n(n+1) + 1/2
// (m, n integers): the largest below 10^2 is 98.5 (d = 9.925 mm), the next is 100.5 (10.025
// mm). No centre lies in the ring, even on gmsh's polygon (sagitta < 0.03 mm): the body is
// 20 dx wide and still yields no points.
SetFactory("OpenCASCADE");
Disk(1) = {10, 10, 0, 10, 10};
Disk(2) = {10, 10, 0, 9.96, 9.96};
BooleanDifference(3) = { Surface{1}; Delete; }{ Surface{2}; Delete; };
Physical Surface("body") = {3};
