// L-shape (built-in kernel), in MILLIMETRES: a 30 x 20 rectangle without its 12 x 8 top-right
// corner, rotated by 30 degrees about the origin so that no edge follows the lattice.
// Area = 30*20 - 12*8 = 504 mm^2. The re-entrant corner is at (18, 12) before rotation.
Point(1) = {0, 0, 0}; Point(2) = {30, 0, 0}; Point(3) = {30, 12, 0};
Point(4) = {18, 12, 0}; Point(5) = {18, 20, 0}; Point(6) = {0, 20, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Rotate {{0, 0, 1}, {0, 0, 0}, Pi / 6} { Surface{1}; }
Physical Curve("bottom") = {1};
Physical Curve("reentrant") = {3, 4};
Physical Surface("body") = {1};
