// Stability suite: a 20 mm x 20 mm square block, in MILLIMETRES (scenes: geometry.unit: mm).
// At dx = 1 mm the lattice is 20 x 20 points: small enough for 10^4-10^5 steps in seconds.
Point(1) = {0, 0, 0};
Point(2) = {20, 0, 0};
Point(3) = {20, 20, 0};
Point(4) = {0, 20, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Surface("body") = {1};
