// Benchmarks: a 100 x 100 x 100 mm block, in MILLIMETRES. At dx = 1 mm the lattice
// has 100^3 = 1 million points.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 100, 100, 100};
e = 1e-3;
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -e, 100 + e, e, 100 + e};
Physical Surface("top") = Surface In BoundingBox{-e, 100 - e, -e, 100 + e, 100 + e, 100 + e};
Physical Volume("body") = {1};
