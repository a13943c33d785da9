// Parallel leaf-spring guide (2-D, plane stress): a fixed base, two parallel leaves of length
// L and thickness t, and a stage much stiffer than the leaves. SI units (m).
// Lateral stiffness (x) of the stage, beam theory: k = 24 E I / L^3, I = w t^3 / 12 (w: the
// out-of-plane thickness, [section] thickness of the model file).
DefineConstant[
  L = {0.04, Name "Parameters/L", Label "leaf length (m)"},
  t = {0.001, Name "Parameters/t", Label "leaf thickness (m)"},
  d = {0.02, Name "Parameters/d", Label "leaf spacing, centre to centre (m)"},
  hb = {0.005, Name "Parameters/hb", Label "base height (m)"},
  hs = {0.008, Name "Parameters/hs", Label "stage height (m)"},
  m = {0.005, Name "Parameters/m", Label "base/stage overhang beyond the leaves (m)"},
  lc_leaf = {t / 2, Name "Parameters/lc_leaf", Label "element size in the leaves (m)"},
  lc_block = {0.004, Name "Parameters/lc_block", Label "element size in base and stage (m)"}
];
a = d / 2 - t / 2;   // inner faces of the leaves at x = +-a
b = d / 2 + t / 2;   // outer faces at x = +-b
e = b + m;           // block ends at x = +-e

// outer outline, counter-clockwise from the base's bottom-left corner
Point(1) = {-e, -hb, 0, lc_block};
Point(2) = {e, -hb, 0, lc_block};
Point(3) = {e, 0, 0, lc_block};
Point(4) = {b, 0, 0, lc_leaf};
Point(5) = {b, L, 0, lc_leaf};
Point(6) = {e, L, 0, lc_block};
Point(7) = {e, L + hs, 0, lc_block};
Point(8) = {-e, L + hs, 0, lc_block};
Point(9) = {-e, L, 0, lc_block};
Point(10) = {-b, L, 0, lc_leaf};
Point(11) = {-b, 0, 0, lc_leaf};
Point(12) = {-e, 0, 0, lc_block};
For i In {1:11}
  Line(i) = {i, i + 1};
EndFor
Line(12) = {12, 1};
// window between the leaves
Point(13) = {-a, 0, 0, lc_leaf};
Point(14) = {a, 0, 0, lc_leaf};
Point(15) = {a, L, 0, lc_leaf};
Point(16) = {-a, L, 0, lc_leaf};
Line(13) = {13, 14};
Line(14) = {14, 15};
Line(15) = {15, 16};
Line(16) = {16, 13};
Curve Loop(1) = {1:12};
Curve Loop(2) = {13:16};
Plane Surface(1) = {1, 2};

Physical Curve("fixed") = {1};     // bottom of the base
Physical Curve("stage") = {7};     // top of the stage
Physical Surface("body") = {1};
