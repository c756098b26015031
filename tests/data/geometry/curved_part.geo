// Curved 3-D CAD part (OpenCASCADE), in MILLIMETRES: a cylinder of radius 6 and height 10
// with a closed spherical cavity of radius 2.5 at its centre (a second, nested boundary
// shell). Volume = pi 6^2 10 - 4/3 pi 2.5^3 = 1065.52 mm^3. Exported to curved_part.step with
// `gmsh curved_part.geo -0 -o curved_part.step`.
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, 0, 0, 0, 10, 6};
Sphere(2) = {0, 0, 5, 2.5};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
