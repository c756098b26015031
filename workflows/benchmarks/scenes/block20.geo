// Benchmarks: a 20 x 20 x 20 mm block, in MILLIMETRES. At dx = 1 mm the lattice has 20^3 = 8000
// points: the 3-D block's instruction counts under callgrind (count_instructions.py --block-scene).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 20, 20, 20};
e = 1e-3;
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -e, 20 + e, e, 20 + e};
Physical Surface("top") = Surface In BoundingBox{-e, 20 - e, -e, 20 + e, 20 + e, 20 + e};
Physical Volume("body") = {1};
