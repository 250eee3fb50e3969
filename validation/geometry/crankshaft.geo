// Parametric crankshaft of an in-line four (evas FE pipeline, docs/fe-pipeline.md).
// Crank axis = x, lengths in mm. Defaults: 4.1 L diesel, stroke 115 mm.
//
// Along x: pulley stub [-pulley_length, 0], then four throws of pitch
//   journal_length + 2 web_thickness + pin_length
// (journal i, web, crankpin i, web), then journal 5 and the flywheel flange.
// Each web is a box from the axis to web_overhang beyond the pin surface
// (width web_width); its counterweight is a box on the opposite side from the
// axis to -cw_depth (width cw_width), sharing the face at the axis. All parts
// touch only at faces (no overlaps), so the solid's volume is the sum of the
// part volumes, as long as each web/counterweight face covers the journal and
// pin disks it carries (true for the defaults).
// Throw angles throw1..throw4 [deg] rotate a throw about x; 0 puts the pin at +y.
//
// Output: second-order tetrahedra (C3D10), physical volume "crankshaft",
// physical surfaces (node sets via Mesh.SaveGroupsOfNodes):
//   journal1..journal5  main journal lateral surfaces
//   pin1..pin4          crankpin lateral surfaces
//   pulley              pulley stub (lateral + end face)
//   flywheel            flywheel flange (both faces + rim)
SetFactory("OpenCASCADE");

DefineConstant[ crank_radius = 57.5 ];
DefineConstant[ journal_diameter = 80 ];
DefineConstant[ journal_length = 30 ];
DefineConstant[ pin_diameter = 65 ];
DefineConstant[ pin_length = 32 ];
DefineConstant[ web_thickness = 22 ];
DefineConstant[ web_width = 110 ];
DefineConstant[ web_overhang = 10 ];
DefineConstant[ cw_depth = 70 ];
DefineConstant[ cw_width = 130 ];
DefineConstant[ throw1 = 0 ];
DefineConstant[ throw2 = 180 ];
DefineConstant[ throw3 = 180 ];
DefineConstant[ throw4 = 0 ];
DefineConstant[ pulley_diameter = 50 ];
DefineConstant[ pulley_length = 50 ];
DefineConstant[ flange_diameter = 130 ];
DefineConstant[ flange_thickness = 20 ];
DefineConstant[ mesh_size = 15 ];

pitch = journal_length + 2 * web_thickness + pin_length;
rj = journal_diameter / 2;
rp = pin_diameter / 2;
web_reach = crank_radius + rp + web_overhang;
angles[] = {throw1, throw2, throw3, throw4};

parts[] = {};
For i In {0:3}
  b = i * pitch;
  th = angles[i] * Pi / 180;
  j = newv;
  Cylinder(j) = {b, 0, 0, journal_length, 0, 0, rj};
  parts[] += {j};
  throw[] = {};
  For s In {0:1}
    xw = b + journal_length + s * (web_thickness + pin_length);
    w = newv;
    Box(w) = {xw, 0, -web_width / 2, web_thickness, web_reach, web_width};
    throw[] += {w};
    c = newv;
    Box(c) = {xw, -cw_depth, -cw_width / 2, web_thickness, cw_depth, cw_width};
    throw[] += {c};
  EndFor
  p = newv;
  Cylinder(p) = {b + journal_length + web_thickness, crank_radius, 0, pin_length, 0, 0, rp};
  throw[] += {p};
  Rotate {{1, 0, 0}, {0, 0, 0}, th} { Volume{throw[]}; }
  parts[] += throw[];
EndFor
x5 = 4 * pitch;
j5 = newv;
Cylinder(j5) = {x5, 0, 0, journal_length, 0, 0, rj};
stub = newv;
Cylinder(stub) = {-pulley_length, 0, 0, pulley_length, 0, 0, pulley_diameter / 2};
xf = x5 + journal_length;
flange = newv;
Cylinder(flange) = {xf, 0, 0, flange_thickness, 0, 0, flange_diameter / 2};
parts[] += {j5, stub, flange};

body() = BooleanUnion{ Volume{parts[0]}; Delete; }{ Volume{parts[{1:#parts[]-1}]}; Delete; };

// Physical groups from bounding boxes of the fused solid's faces.
eps = 0.5;
For i In {0:4}
  x0 = i * pitch;
  x1 = x0 + journal_length;
  js() = Surface In BoundingBox{x0 - eps, -rj - eps, -rj - eps, x1 + eps, rj + eps, rj + eps};
  e0() = Surface In BoundingBox{x0 - eps, -rj - eps, -rj - eps, x0 + eps, rj + eps, rj + eps};
  e1() = Surface In BoundingBox{x1 - eps, -rj - eps, -rj - eps, x1 + eps, rj + eps, rj + eps};
  js() -= e0();
  js() -= e1();
  Physical Surface(Sprintf("journal%g", i + 1)) = {js()};
EndFor
For i In {0:3}
  th = angles[i] * Pi / 180;
  yc = crank_radius * Cos(th);
  zc = crank_radius * Sin(th);
  x0 = i * pitch + journal_length + web_thickness;
  x1 = x0 + pin_length;
  ps() = Surface In BoundingBox{x0 - eps, yc - rp - eps, zc - rp - eps,
                                x1 + eps, yc + rp + eps, zc + rp + eps};
  e0() = Surface In BoundingBox{x0 - eps, yc - rp - eps, zc - rp - eps,
                                x0 + eps, yc + rp + eps, zc + rp + eps};
  e1() = Surface In BoundingBox{x1 - eps, yc - rp - eps, zc - rp - eps,
                                x1 + eps, yc + rp + eps, zc + rp + eps};
  ps() -= e0();
  ps() -= e1();
  Physical Surface(Sprintf("pin%g", i + 1)) = {ps()};
EndFor
rs = pulley_diameter / 2;
pul() = Surface In BoundingBox{-pulley_length - eps, -rs - eps, -rs - eps, eps, rs + eps, rs + eps};
rf = flange_diameter / 2;
fly() = Surface In BoundingBox{xf - eps, -rf - eps, -rf - eps,
                               xf + flange_thickness + eps, rf + eps, rf + eps};
Physical Surface("pulley") = {pul()};
Physical Surface("flywheel") = {fly()};
Physical Volume("crankshaft") = {body()};

Mesh.CharacteristicLengthMax = mesh_size;
Mesh.CharacteristicLengthMin = 0.1 * mesh_size;
Mesh.CharacteristicLengthFromCurvature = 0;
Mesh.ElementOrder = 2;
Mesh.SecondOrderLinear = 0;
Mesh.SaveGroupsOfNodes = 1;
