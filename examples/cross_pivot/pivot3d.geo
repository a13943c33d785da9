// Classic cross-spring pivot (3-D solid): two leaves of length L, thickness t and width w
// crossing at their middles at 90 degrees in plan, in two layers (z in [0, w] and
// [w + g, 2 w + g]) so that they pass each other without touching. A fixed base, a stage
// whose side faces "left" and "right" carry a couple.
// Rotational stiffness, beam theory (Wittrick 1948): K = 2 E I / L, I = w t^3 / 12.
SetFactory("OpenCASCADE");
DefineConstant[
  L = {0.03, Name "Parameters/L", Label "leaf length (m)"},
  t = {0.001, Name "Parameters/t", Label "leaf thickness (m)"},
  w = {0.002, Name "Parameters/w", Label "leaf width (m)"},
  g = {0.001, Name "Parameters/g", Label "gap between the two leaf layers (m)"},
  arm = {0.012, Name "Parameters/arm", Label "half width of the stage (m)"},
  hb = {0.004, Name "Parameters/hb", Label "base height (m)"},
  hs = {0.004, Name "Parameters/hs", Label "stage height (m)"},
  lc_leaf = {t, Name "Parameters/lc_leaf", Label "element size in the leaves (m)"},
  lc_block = {0.004, Name "Parameters/lc_block", Label "element size in base and stage (m)"}
];
c = L / (2 * Sqrt(2));   // the leaves end on the blocks at y = +-c
e = c + 2 * t;
ext = 2 * t;
H = 2 * w + g;           // depth of base and stage (z)

Box(1) = {-L / 2 - ext, -t / 2, 0, L + 2 * ext, t, w};
Box(2) = {-L / 2 - ext, -t / 2, w + g, L + 2 * ext, t, w};
Rotate {{0, 0, 1}, {0, 0, 0}, Pi / 4} { Volume{1}; }
Rotate {{0, 0, 1}, {0, 0, 0}, -Pi / 4} { Volume{2}; }
Box(3) = {-e, -c - hb, 0, 2 * e, hb, H};
Box(4) = {-arm, c, 0, 2 * arm, hs, H};
BooleanUnion{ Volume{3}; Delete; }{ Volume{1, 2, 4}; Delete; }

eps = 1e-6;   // gmsh pads OpenCASCADE bounding boxes by 1e-7
MeshSize{ PointsOf{ Volume{:}; } } = lc_block;
MeshSize{ Point In BoundingBox{-c - t, -c - t, -1, c + t, c + t, 1} } = lc_leaf;
Physical Surface("fixed") = Surface In BoundingBox{-e - eps, -c - hb - eps, -eps, e + eps, -c - hb + eps, H + eps};
Physical Surface("left") = Surface In BoundingBox{-arm - eps, c - eps, -eps, -arm + eps, c + hs + eps, H + eps};
Physical Surface("right") = Surface In BoundingBox{arm - eps, c - eps, -eps, arm + eps, c + hs + eps, H + eps};
Physical Volume("body") = Volume{:};
