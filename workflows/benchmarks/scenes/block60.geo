// Benchmarks: a 60 x 60 x 60 mm block, in MILLIMETRES. At dx = 1 mm the lattice
// has 60^3 = 216 000 points (the 3-D side-by-side with LAMMPS: lammps/make_block_input.py).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 60, 60, 60};
e = 1e-3;
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -e, 60 + e, e, 60 + e};
Physical Surface("top") = Surface In BoundingBox{-e, 60 - e, -e, 60 + e, 60 + e, 60 + e};
Physical Volume("body") = {1};
