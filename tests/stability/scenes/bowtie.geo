// Stability suite: a self-overlapping outline (a bow tie: the 20 mm square with two corners
// swapped, so that its edges cross at the centre). Its two lobes are traversed in opposite senses:
// the shoelace area is zero, one lobe counts negative. A code that trusts the outline makes
// negative or zero volumes from it; mppm-preprocess must refuse it (exit 2) naming the file.
Point(1) = {0, 0, 0};
Point(2) = {20, 0, 0};
Point(3) = {0, 20, 0};
Point(4) = {20, 20, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("outline") = {1, 2, 3, 4};
Physical Surface("body") = {1};
