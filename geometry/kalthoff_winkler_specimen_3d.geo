// The Kalthoff-Winkler specimen in 3-D (workflows/kalthoff-winkler/README.md, "The 3-D form"), in
// METRES (scenes: geometry.unit: m): kalthoff_winkler_specimen.geo's plate, 100 mm along the
// notches (x) by 200 mm along the struck edge (y), extruded through the specimen's 9 mm thickness
// (z). The notches are the two zero-width pre-crack surfaces `notch_lower` and `notch_upper`,
// 50 mm long from the left face at y = 75 mm and 125 mm, through the whole thickness (the lines of
// the 2-D file extruded: half-way between two lattice rows at dx = 1 mm and 0.5 mm, ending 10 um
// past 50 mm, for the reasons given there). `struck` is the part of the left face between them.
L = 0.100;
H = 0.200;
T = 0.009;   // thickness
A = 0.05001; // notch length (50 mm, past the cell face)
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
// Extruding the surface gives [top face, volume, the side faces of lines 1..6 in order]: the
// struck face is the side of line 5. Extruding a line gives [its far copy, the surface].
plate[] = Extrude {0, 0, T} { Surface{1}; };
lower[] = Extrude {0, 0, T} { Curve{7}; };
upper[] = Extrude {0, 0, T} { Curve{8}; };
Physical Surface("struck") = {plate[6]};
Physical Surface("notch_lower") = {lower[1]};
Physical Surface("notch_upper") = {upper[1]};
Physical Volume("body") = {plate[1]};
