// 10 x 6 x 4 mm box (built-in kernel), in MILLIMETRES, with a zero-width pre-crack: the separate
// rectangle `crack` at z = 2 mm (between lattice planes for dx = 0.5 mm) from the face x = 0 to
// x = 5 mm, across the whole width.
Point(1) = {0, 0, 0}; Point(2) = {10, 0, 0}; Point(3) = {10, 6, 0}; Point(4) = {0, 6, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
out[] = Extrude {0, 0, 4} { Surface{1}; };
// out[0] = top (z = 4), out[1] = volume, out[2..5] = sides along lines 1..4
Physical Surface("zmin") = {1};
Physical Surface("zmax") = {out[0]};
Physical Surface("ymin") = {out[2]};
Physical Surface("xmax") = {out[3]};
Physical Surface("ymax") = {out[4]};
Physical Surface("xmin") = {out[5]};
Physical Volume("body") = {out[1]};
Point(101) = {0, 0, 2}; Point(102) = {5, 0, 2}; Point(103) = {5, 6, 2}; Point(104) = {0, 6, 2};
Line(101) = {101, 102}; Line(102) = {102, 103}; Line(103) = {103, 104}; Line(104) = {104, 101};
Curve Loop(101) = {101, 102, 103, 104};
Plane Surface(101) = {101};
Physical Surface("crack") = {101};
