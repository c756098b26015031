// Disc of radius 20 mm with an off-centre hole of radius 8 mm (OpenCASCADE), in MILLIMETRES.
// Area = pi (20^2 - 8^2) = 1055.575 mm^2. Physical curves: outer, hole.
SetFactory("OpenCASCADE");
Disk(1) = {0, 0, 0, 20, 20};
Disk(2) = {3, 2, 0, 8, 8};
BooleanDifference(3) = { Surface{1}; Delete; }{ Surface{2}; Delete; };
e = 1e-3;
all[] = Curve In BoundingBox{-20 - e, -20 - e, -e, 20 + e, 20 + e, e};
hole[] = Curve In BoundingBox{-5 - e, -6 - e, -e, 11 + e, 10 + e, e};
outer[] = all[];
outer[] -= hole[];
Physical Curve("outer") = outer[];
Physical Curve("hole") = hole[];
Physical Surface("body") = {3};
