// A right-circular notch hinge (2-D, plane stress): a bar of height t + 2 R with two
// semicircular cuts of radius R facing each other, leaving a neck of thickness t at x = R
// (Paros and Weisbord's hinge). The bar's left end is held ("fixed"), its right end is the
// stage ("stage"). The notch runs from x = 0 to x = 2 R; the bar goes on Lb beyond it on
// both sides. Beam theory of the notch (Paros-Weisbord's integral) is stiffer than this
// model: docs/beam.md, "Notch hinges: the 2-D patch".
SetFactory("OpenCASCADE");
DefineConstant[
  R = {0.0025, Name "Parameters/R", Label "notch radius (m)"},
  t = {0.0005, Name "Parameters/t", Label "neck thickness (m)"},
  Lb = {0.005, Name "Parameters/Lb", Label "bar length beyond the notch, each side (m)"},
  lc_neck = {t / 12, Name "Parameters/lc_neck", Label "element size at the neck (m)"},
  lc_bar = {(t + 2 * R) / 8, Name "Parameters/lc_bar", Label "element size in the bar (m)"}
];
h = t / 2 + R;  // the bar's half height
Rectangle(1) = {-Lb, -h, 0, 2 * R + 2 * Lb, 2 * h};
Disk(2) = {R, h, 0, R};
Disk(3) = {R, -h, 0, R};
BooleanDifference{ Surface{1}; Delete; }{ Surface{2, 3}; Delete; }

// the size grows from lc_neck at the neck to lc_bar a notch radius away
Field[1] = Box;
Field[1].VIn = lc_neck;
Field[1].VOut = lc_bar;
Field[1].XMin = R - t;
Field[1].XMax = R + t;
Field[1].YMin = -h;
Field[1].YMax = h;
Field[1].Thickness = R;
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 36;

eps = 1e-6;  // OpenCASCADE bounding boxes are 1e-7 m larger than the curves
Physical Curve("fixed") = Curve In BoundingBox{-Lb - eps, -h - eps, -1, -Lb + eps, h + eps, 1};
Physical Curve("stage") = Curve In BoundingBox{2 * R + Lb - eps, -h - eps, -1, 2 * R + Lb + eps, h + eps, 1};
Physical Surface("body") = Surface{:};
