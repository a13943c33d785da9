// One leaf (2-D, plane stress) of length L and thickness t between a fixed base and a stage,
// meeting both block faces at the angle phi (90 degrees: square). Its centre line runs from
// (-L/2 cos phi, -L/2 sin phi) to (L/2 cos phi, L/2 sin phi); L is its length between the
// faces along the centre line. The stage's side faces "left" and "right" carry a couple, so
// the leaf carries a pure moment: beam theory K = E I / L, I = w t^3 / 12.
SetFactory("OpenCASCADE");
DefineConstant[
  L = {0.03, Name "Parameters/L", Label "leaf length between the faces (m)"},
  t = {0.001, Name "Parameters/t", Label "leaf thickness (m)"},
  phi = {Pi / 4, Name "Parameters/phi", Label "angle between leaf and block faces (rad)"},
  hb = {0.012, Name "Parameters/hb", Label "base height (m)"},
  hs = {0.012, Name "Parameters/hs", Label "stage height (m)"},
  lc_leaf = {t / 4, Name "Parameters/lc_leaf", Label "element size in the leaf (m)"},
  lc_block = {0.003, Name "Parameters/lc_block", Label "element size in base and stage (m)"}
];
c = L / 2 * Sin(phi);               // the faces at y = +-c
ext = t * (1 + 1 / Tan(phi));        // the leaf reaches this far into the blocks (union)
arm = L / 2 * Cos(phi) + ext + 2 * t;  // half width of both blocks
Rectangle(1) = {-L / 2 - ext, -t / 2, 0, L + 2 * ext, t};
Rotate {{0, 0, 1}, {0, 0, 0}, phi} { Surface{1}; }
Rectangle(2) = {-arm, -c - hb, 0, 2 * arm, hb};
Rectangle(3) = {-arm, c, 0, 2 * arm, hs};
BooleanUnion{ Surface{2}; Delete; }{ Surface{1, 3}; Delete; }

eps = 1e-6;
MeshSize{ PointsOf{ Surface{:}; } } = lc_block;
MeshSize{ Point In BoundingBox{-L / 2 * Cos(phi) - ext - t, -c - t, -1, L / 2 * Cos(phi) + ext + t, c + t, 1} } = lc_leaf;
Physical Curve("fixed") = Curve In BoundingBox{-arm - eps, -c - hb - eps, -1, arm + eps, -c - hb + eps, 1};
Physical Curve("left") = Curve In BoundingBox{-arm - eps, c - eps, -1, -arm + eps, c + hs + eps, 1};
Physical Curve("right") = Curve In BoundingBox{arm - eps, c - eps, -1, arm + eps, c + hs + eps, 1};
Physical Surface("body") = Surface{:};
