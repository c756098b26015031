// Crack-branching plate (workflows/crack-branching/README.md), in METRES (scenes: geometry.unit: m).
// 100 mm (x) by 40 mm (y); a zero-width pre-crack `notch` runs from the middle of the left
// edge to the plate centre. The notch is a separate curve (not embedded): the preprocessor only
// needs its geometry to cut bonds, and the body stays a plain rectangle. It lies at y = 20 mm,
// half-way between two lattice rows for dx = 0.5 mm, so no lattice point sits on it.
L = 0.100;
H = 0.040;
Point(1) = {0, 0, 0};
Point(2) = {L, 0, 0};
Point(3) = {L, H, 0};
Point(4) = {0, H, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Point(5) = {0, H / 2, 0};
Point(6) = {L / 2, H / 2, 0};
Line(5) = {5, 6};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Curve("notch") = {5};
Physical Surface("body") = {1};
