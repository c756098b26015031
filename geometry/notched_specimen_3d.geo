// 3-D notched bar (OpenCASCADE kernel), in MILLIMETRES (scenes: geometry.unit: mm).
// 100 x 20 x 10 mm bar with a U-notch (radius 2 mm, 6 mm deep) cut from the bottom face at
// mid-span through the whole thickness. notched_specimen_3d.step is the same part exported by
// gmsh (`gmsh notched_specimen_3d.geo -0 -o notched_specimen_3d.step`); STEP files carry no
// physical groups, so scenes select its faces with `box:` or `entities:`.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 100, 20, 10};
Box(2) = {48, -1, -1, 4, 5, 12};                 // notch flanks, 4 mm wide, up to y = 4
Cylinder(3) = {50, 4, -1, 0, 0, 12, 2};          // rounded notch root at y = 6
BooleanDifference(4) = { Volume{1}; Delete; }{ Volume{2, 3}; Delete; };
e = 1e-3;
Physical Surface("left") = Surface In BoundingBox{-e, -e, -e, e, 20 + e, 10 + e};
Physical Surface("right") = Surface In BoundingBox{100 - e, -e, -e, 100 + e, 20 + e, 10 + e};
Physical Surface("top") = Surface In BoundingBox{-e, 20 - e, -e, 100 + e, 20 + e, 10 + e};
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -e, 100 + e, e, 10 + e};
Physical Volume("body") = {4};
