// The Kalthoff-Winkler specimen as in the experiment (workflows/kalthoff-winkler/README.md, "The
// experiment's specimen"), in METRES (scenes: geometry.unit: m). 100 mm along the notches (x) by
// 200 mm along the struck edge (y); two zero-width pre-cracks, `notch_lower` and `notch_upper`,
// run 50 mm from the left edge at y = 75 mm and y = 125 mm, 50 mm apart and 75 mm from the top
// and bottom edges. The part of the left edge between them is `struck` (the impact), the rest of
// the left edge `left_lower` and `left_upper`. The names, the notches' placement between lattice
// rows and their ends 10 um past 50 mm are those of kalthoff_winkler_plate.geo (the case's
// default plate, turned the other way), for the same reasons.
L = 0.100;
H = 0.200;
A = 0.05001; // notch length (50 mm, past the cell face: above)
Y1 = 0.075;  // lower notch
Y2 = 0.125;  // upper notch
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
