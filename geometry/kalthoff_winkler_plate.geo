// Kalthoff-Winkler plate (workflows/kalthoff-winkler/README.md), in METRES (scenes: geometry.unit: m).
// 200 mm (x) by 100 mm (y); two zero-width pre-cracks, `notch_lower` and `notch_upper`, run 50 mm
// from the left edge at y = 25 mm and y = 75 mm. The part of the left edge between them is
// `struck` (the impact), the rest of the left edge `left_lower` and `left_upper`. The notches are
// separate curves (not embedded): the preprocessor only needs their geometry to cut bonds. They
// lie half-way between two lattice rows for dx = 1 mm and 0.5 mm (rows at (k + 1/2) dx), so no
// lattice point sits on them. They end 10 um past 50 mm: at exactly 50 mm the tip would lie on a
// cell face, where the diagonal bonds crossing the notch line at the tip are cut or not by the
// rounding of the coordinates, differently at the two notches (1791 cuts instead of 1794 at
// dx = 1 mm, and cracks 5.6 degrees from mirror images).
L = 0.200;
H = 0.100;
A = 0.05001; // notch length (50 mm, past the cell face: above)
Y1 = 0.025;  // lower notch
Y2 = 0.075;  // upper notch
Point(1) = {0, 0, 0};
Point(2) = {L, 0, 0};
Point(3) = {L, H, 0};
Point(4) = {0, H, 0};
Point(5) = {0, Y2, 0};
Point(6) = {0, Y1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Point(7) = {A, Y1, 0};
Point(8) = {A, Y2, 0};
Line(7) = {6, 7};
Line(8) = {5, 8};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left_upper") = {4};
Physical Curve("struck") = {5};
Physical Curve("left_lower") = {6};
Physical Curve("notch_lower") = {7};
Physical Curve("notch_upper") = {8};
Physical Surface("body") = {1};
