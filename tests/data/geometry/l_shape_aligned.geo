// The same L-shape without rotation, in MILLIMETRES: every edge (the re-entrant corner at
// (18, 12) included) lies on lattice cell faces for dx = 0.5 mm, so the count is exact:
// 504 / 0.25 = 2016 points.
Point(1) = {0, 0, 0}; Point(2) = {30, 0, 0}; Point(3) = {30, 12, 0};
Point(4) = {18, 12, 0}; Point(5) = {18, 20, 0}; Point(6) = {0, 20, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("reentrant") = {3, 4};
Physical Curve("top") = {5};
Physical Curve("left") = {6};
Physical Surface("body") = {1};
