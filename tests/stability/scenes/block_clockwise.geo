// Stability suite: the 20 mm x 20 mm block of block.geo with its outline traversed clockwise
// (every curve reversed in the loop): the orientation that gives a negative signed area, i.e. a
// negative volume in a code that takes the outline's orientation for granted. The preprocessor
// orients the boundary itself (preprocess/boundary_validation.hpp): the points must be those of
// block.geo, every volume dx^2 t > 0.
Point(1) = {0, 0, 0};
Point(2) = {20, 0, 0};
Point(3) = {20, 20, 0};
Point(4) = {0, 20, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {-4, -3, -2, -1};
Plane Surface(1) = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Surface("body") = {1};
