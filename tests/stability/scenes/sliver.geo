// Stability suite: a 20 mm x 0.2 mm strip, in MILLIMETRES. At dx = 1 mm no lattice point
// (cell centre) lies inside it: the preprocessor must refuse it (exit 2), not write an empty
// points file that the solver would choke on.
Point(1) = {0, 0, 0};
Point(2) = {20, 0, 0};
Point(3) = {20, 0.2, 0};
Point(4) = {0, 0.2, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
Physical Surface("body") = {1};
