// Cross-spring pivot (2-D, plane stress): two leaves of length L and thickness t crossing at
// their middles at 2 beta (default 90 degrees: each leaf beta = 45 degrees from the horizontal),
// joined where they cross, between a fixed base and a stage. The stage's side faces "left" and
// "right" carry a couple.
// Rotational stiffness, beam theory: K = 8 E I / L, I = w t^3 / 12 (w: [section] thickness).
SetFactory("OpenCASCADE");
DefineConstant[
  L = {0.03, Name "Parameters/L", Label "leaf length (m)"},
  t = {0.0005, Name "Parameters/t", Label "leaf thickness (m)"},
  arm = {0.015, Name "Parameters/arm", Label "half width of the stage (m)"},
  beta = {Pi / 4, Name "Parameters/beta", Label "angle of the leaves from the horizontal (rad)"},
  hb = {0.004, Name "Parameters/hb", Label "base height (m)"},
  hs = {0.004, Name "Parameters/hs", Label "stage height (m)"},
  lc_leaf = {t / 2, Name "Parameters/lc_leaf", Label "element size in the leaves (m)"},
  lc_block = {0.003, Name "Parameters/lc_block", Label "element size in base and stage (m)"}
];
c = L / 2 * Sin(beta);   // the leaves end on the blocks at y = +-c
e = L / 2 * Cos(beta) + 2 * t;   // half width of the base
ext = 2 * t;             // leaves reach this far into the blocks (merged by the union)

Rectangle(1) = {-L / 2 - ext, -t / 2, 0, L + 2 * ext, t};
Rectangle(2) = {-L / 2 - ext, -t / 2, 0, L + 2 * ext, t};
Rotate {{0, 0, 1}, {0, 0, 0}, beta} { Surface{1}; }
Rotate {{0, 0, 1}, {0, 0, 0}, -beta} { Surface{2}; }
Rectangle(3) = {-e, -c - hb, 0, 2 * e, hb};
Rectangle(4) = {-arm, c, 0, 2 * arm, hs};
BooleanUnion{ Surface{3}; Delete; }{ Surface{1, 2, 4}; Delete; }

eps = 1e-6;   // gmsh pads OpenCASCADE bounding boxes by 1e-7
MeshSize{ PointsOf{ Surface{:}; } } = lc_block;
MeshSize{ Point In BoundingBox{-L / 2 * Cos(beta) - t, -c - t, -1, L / 2 * Cos(beta) + t, c + t, 1} } = lc_leaf;
Physical Curve("fixed") = Curve In BoundingBox{-e - eps, -c - hb - eps, -1, e + eps, -c - hb + eps, 1};
Physical Curve("left") = Curve In BoundingBox{-arm - eps, c - eps, -1, -arm + eps, c + hs + eps, 1};
Physical Curve("right") = Curve In BoundingBox{arm - eps, c - eps, -1, arm + eps, c + hs + eps, 1};
Physical Surface("body") = Surface{:};
