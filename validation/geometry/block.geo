// Simplified cylinder block of an in-line four (evas FE pipeline, docs/fe-pipeline.md).
// Lengths in mm. Defaults: 4.1 L diesel proportions (stroke 115 mm), grey iron.
//
// Engine frame, shared with crankshaft.geo: crank axis = x (through the origin),
// cylinder axes = +z (towards the head), y lateral. crankshaft.geo puts throw
// angle 0 at +y and rotates throws about +x, so a throw points up a cylinder
// (TDC) at throw angle 90; the block does not depend on throw angles, only on
// the x positions below.
//
// Along x the block uses the crankshaft's throw pitch
//   pitch = journal_length + 2 web_thickness + pin_length   (106 mm by default)
// from the same three parameters (pass the same values to both scripts):
//   main journal i (i = 0..4) spans x = i pitch .. i pitch + journal_length,
//   bulkhead i is centred on it, at xb_i = i pitch + journal_length / 2,
//   cylinder i (i = 0..3) is centred over crankpin i, xc_i = xb_i + pitch / 2.
// The block runs from the front face of bulkhead 1 to the rear face of bulkhead 5.
//
// Bore: the crankshaft's pitch (106 mm) equals the engine's bore (106 mm), which
// leaves no metal between adjacent bores. The default bore is therefore 96 mm
// (siamesed liners, bridge pitch - bore = 10 mm); bore = 106 needs a longer
// crankshaft (pitch >= bore + min_bridge). The script stops with an error when
// pitch - bore < min_bridge.
//
// Parts (all boxes and cylinders, fused into one solid; z in mm for the defaults):
//   deck        z = deck_height - deck_thickness .. deck_height (300..320),
//               |y| <= jacket_half_width; its top face is the head face (the head
//               is not modelled)
//   liners      tubes of wall liner_thickness about each cylinder axis from the
//               deck down into the shelf (siamesed: neighbours overlap)
//   jacket      water-jacket side walls |y| = jacket_half_width - wall_thickness ..
//               jacket_half_width and end walls (end_wall_thickness) at the block's
//               ends, between the shelf and the deck
//   shelf       crankcase top plate, z = liner_bottom .. crankcase_top (110..130),
//               |y| <= crankcase_half_width
//   skirt       crankcase side walls |y| = crankcase_half_width - wall_thickness ..
//               crankcase_half_width, z = -skirt_depth .. shelf (deep skirt:
//               skirt_depth > 0 puts the pan rail below the crank axis)
//   bulkheads   five transverse walls of thickness bulkhead_thickness at the main
//               journals, from the bearing split plane z = 0 up to the shelf,
//               across the full inner width (1 and 5 close the crankcase's ends)
//   caps        main-bearing caps: boxes cap_width wide, from z = -cap_depth to 0,
//               fused with the bulkheads (a simplified block models the caps as
//               part of the block)
//   bearing     a cylinder of journal_diameter about x is cut through bulkheads
//               and caps: a full-circle main-bearing bore at each bulkhead
//   bores       cylinders of diameter bore cut from the head face down to
//               z = liner_bottom, where they open into the crankcase
//   mount pads  four boxes on the skirt walls (two per side) at x = mount_x_front,
//               mount_x_rear, z = mount_z
//   flange      optional (flywheel_flange = 1) flywheel-housing flange: a plate
//               behind bulkhead 5 with a hole of flange_hole_diameter about x
// Bulkheads stop at the shelf and the jacket's end walls stay clear of the bores:
// a plane face crossing a bore leaves a thin wedge that spoils the curved
// second-order elements (see the mesh settings at the end).
//
// Output: second-order tetrahedra (C3D10), physical volume "block", physical
// surfaces (node sets via Mesh.SaveGroupsOfNodes):
//   bore1..bore5       main-bearing bore surfaces (radius journal_diameter / 2 about x)
//   liner1..liner4     cylinder bore surfaces (radius bore / 2 about each cylinder axis)
//   head               deck top face (z = deck_height), where the gas force acts
//   side_walls         outer faces of the skirt (|y| = crankcase_half_width) and of
//                      the water jacket (|y| = jacket_half_width), both sides
//   mount1..mount4     outer faces of the mount pads: 1 front +y, 2 front -y,
//                      3 rear +y, 4 rear -y
//   pan_rail           bottom faces of the skirt walls (oil pan joint)
//   flywheel_housing   rear face of the flywheel-housing flange (if present)
SetFactory("OpenCASCADE");

DefineConstant[ journal_length = 30 ];     // crankshaft.geo: main journal length
DefineConstant[ web_thickness = 22 ];      // crankshaft.geo: web thickness
DefineConstant[ pin_length = 32 ];         // crankshaft.geo: crankpin length
DefineConstant[ journal_diameter = 80 ];   // main-bearing bore (no shell modelled)
DefineConstant[ bore = 96 ];               // cylinder bore diameter (see above)
DefineConstant[ min_bridge = 6 ];          // least metal between bores (check only)
DefineConstant[ liner_thickness = 7 ];
DefineConstant[ liner_bottom = 110 ];      // z of the liners' lower end = shelf's lower face
DefineConstant[ deck_height = 320 ];       // z of the head face
DefineConstant[ deck_thickness = 20 ];
DefineConstant[ jacket_half_width = 80 ];  // outer half width of the cylinder section
DefineConstant[ crankcase_top = 130 ];     // z of the shelf's top face
DefineConstant[ end_wall_thickness = 12 ];  // water-jacket end walls
DefineConstant[ crankcase_half_width = 130 ];
DefineConstant[ wall_thickness = 8 ];
DefineConstant[ skirt_depth = 60 ];        // pan rail at z = -skirt_depth
DefineConstant[ bulkhead_thickness = 24 ];
DefineConstant[ cap_width = 150 ];
DefineConstant[ cap_depth = 55 ];
DefineConstant[ pad_length = 60 ];         // mount pad along x
DefineConstant[ pad_height = 50 ];         // along z
DefineConstant[ pad_depth = 20 ];          // outwards (y)
DefineConstant[ mount_x_front = 68 ];
DefineConstant[ mount_x_rear = 386 ];
DefineConstant[ mount_z = 30 ];
DefineConstant[ flywheel_flange = 1 ];
DefineConstant[ flange_thickness = 15 ];
DefineConstant[ flange_half_width = 170 ];
DefineConstant[ flange_bottom = -110 ];
DefineConstant[ flange_top = 250 ];
DefineConstant[ flange_hole_diameter = 140 ];
DefineConstant[ mesh_size = 30 ];
DefineConstant[ curve_elements = 16 ];  // elements per circle on curved faces (see below)

pitch = journal_length + 2 * web_thickness + pin_length;
rj = journal_diameter / 2;
rb = bore / 2;
tb = bulkhead_thickness;
hu = jacket_half_width;
hc = crankcase_half_width;
tw = wall_thickness;
zd = deck_height - deck_thickness;  // deck's lower face
x0 = journal_length / 2 - tb / 2;  // front face of bulkhead 1
x1 = 4 * pitch + journal_length / 2 + tb / 2;  // rear face of bulkhead 5
len = x1 - x0;

If (pitch - bore < min_bridge)
  Error("block.geo: bore %g mm leaves %g mm between bores at pitch %g mm (min_bridge %g)",
        bore, pitch - bore, pitch, min_bridge);
  Abort;
EndIf
// Checks that keep the solid connected and free of tangent faces and of thin
// wedges that spoil curved second-order elements.
If (tb >= journal_length || liner_bottom >= crankcase_top || crankcase_top >= zd ||
    rj >= cap_depth || rj >= liner_bottom || hu >= hc || rb + liner_thickness >= hu - tw ||
    cap_width / 2 >= hc - tw || Fabs(rb + liner_thickness - pitch / 2) < 1 ||
    x0 + end_wall_thickness >= journal_length / 2 + pitch / 2 - rb - 1 ||
    flange_hole_diameter / 2 >= flange_half_width || flange_top >= zd ||
    Fabs(flange_hole_diameter - cap_width) < 2)
  Error("block.geo: inconsistent parameters (see the checks in the script)");
  Abort;
EndIf

parts[] = {};
zm = (liner_bottom + crankcase_top) / 2;  // parts overlap into the shelf and the deck
zt = zd + deck_thickness / 2;
v = newv; Box(v) = {x0, -hu, zd, len, 2 * hu, deck_thickness}; parts[] += {v};
v = newv; Box(v) = {x0, hu - tw, zm, len, tw, zt - zm}; parts[] += {v};
v = newv; Box(v) = {x0, -hu, zm, len, tw, zt - zm}; parts[] += {v};
v = newv; Box(v) = {x0, -hu + tw / 2, zm, end_wall_thickness, 2 * hu - tw, zt - zm};
parts[] += {v};
v = newv; Box(v) = {x1 - end_wall_thickness, -hu + tw / 2, zm, end_wall_thickness, 2 * hu - tw,
                    zt - zm};
parts[] += {v};
v = newv; Box(v) = {x0, -hc, liner_bottom, len, 2 * hc, crankcase_top - liner_bottom};
parts[] += {v};
v = newv; Box(v) = {x0, hc - tw, -skirt_depth, len, tw, zm + skirt_depth}; parts[] += {v};
v = newv; Box(v) = {x0, -hc, -skirt_depth, len, tw, zm + skirt_depth}; parts[] += {v};
For i In {0:3}
  xc = i * pitch + journal_length / 2 + pitch / 2;
  v = newv;
  Cylinder(v) = {xc, 0, zm, 0, 0, zt - zm, rb + liner_thickness};
  parts[] += {v};
EndFor
For i In {0:4}
  xb = i * pitch + journal_length / 2 - tb / 2;
  v = newv; Box(v) = {xb, -hc + tw / 2, 0, tb, 2 * hc - tw, zm}; parts[] += {v};
  v = newv; Box(v) = {xb, -cap_width / 2, -cap_depth, tb, cap_width, cap_depth}; parts[] += {v};
EndFor
mx[] = {mount_x_front, mount_x_front, mount_x_rear, mount_x_rear};
my[] = {1, -1, 1, -1};
For k In {0:3}
  v = newv;
  If (my[k] > 0)
    Box(v) = {mx[k] - pad_length / 2, hc - tw / 2, mount_z - pad_height / 2,
              pad_length, pad_depth + tw / 2, pad_height};
  Else
    Box(v) = {mx[k] - pad_length / 2, -hc - pad_depth, mount_z - pad_height / 2,
              pad_length, pad_depth + tw / 2, pad_height};
  EndIf
  parts[] += {v};
EndFor
If (flywheel_flange)
  v = newv;
  Box(v) = {x1, -flange_half_width, flange_bottom, flange_thickness, 2 * flange_half_width,
            flange_top - flange_bottom};
  h = newv;
  Cylinder(h) = {x1 - 1, 0, 0, flange_thickness + 2, 0, 0, flange_hole_diameter / 2};
  plate() = BooleanDifference{ Volume{v}; Delete; }{ Volume{h}; Delete; };
  parts[] += {plate()};
EndIf

fused() = BooleanUnion{ Volume{parts[0]}; Delete; }{ Volume{parts[{1:#parts[]-1}]}; Delete; };

cuts[] = {};
For i In {0:3}
  xc = i * pitch + journal_length / 2 + pitch / 2;
  v = newv;
  Cylinder(v) = {xc, 0, liner_bottom, 0, 0, deck_height + 1 - liner_bottom, rb};
  cuts[] += {v};
EndFor
v = newv; Cylinder(v) = {x0 - 1, 0, 0, len + 2, 0, 0, rj}; cuts[] += {v};
body() = BooleanDifference{ Volume{fused()}; Delete; }{ Volume{cuts[]}; Delete; };
If (#body[] != 1)
  Error("block.geo: the solid has %g volumes, not 1", #body[]);
  Abort;
EndIf

// Physical groups from bounding boxes of the solid's faces.
eps = 0.5;
For i In {0:4}
  xa = i * pitch + journal_length / 2 - tb / 2;
  xe = xa + tb;
  s() = Surface In BoundingBox{xa - eps, -rj - eps, -rj - eps, xe + eps, rj + eps, rj + eps};
  e0() = Surface In BoundingBox{xa - eps, -rj - eps, -rj - eps, xa + eps, rj + eps, rj + eps};
  e1() = Surface In BoundingBox{xe - eps, -rj - eps, -rj - eps, xe + eps, rj + eps, rj + eps};
  s() -= e0();
  s() -= e1();
  Physical Surface(Sprintf("bore%g", i + 1)) = {s()};
EndFor
For i In {0:3}
  xc = i * pitch + journal_length / 2 + pitch / 2;
  s() = Surface In BoundingBox{xc - rb - eps, -rb - eps, liner_bottom - eps,
                               xc + rb + eps, rb + eps, deck_height + eps};
  e0() = Surface In BoundingBox{xc - rb - eps, -rb - eps, liner_bottom - eps,
                                xc + rb + eps, rb + eps, liner_bottom + eps};
  e1() = Surface In BoundingBox{xc - rb - eps, -rb - eps, deck_height - eps,
                                xc + rb + eps, rb + eps, deck_height + eps};
  s() -= e0();
  s() -= e1();
  Physical Surface(Sprintf("liner%g", i + 1)) = {s()};
EndFor
head() = Surface In BoundingBox{x0 - eps, -hu - eps, deck_height - eps,
                                x1 + eps, hu + eps, deck_height + eps};
Physical Surface("head") = {head()};
For k In {0:3}
  yo = my[k] * (hc + pad_depth);
  s() = Surface In BoundingBox{mx[k] - pad_length / 2 - eps, yo - eps, mount_z - pad_height / 2 - eps,
                               mx[k] + pad_length / 2 + eps, yo + eps, mount_z + pad_height / 2 + eps};
  Physical Surface(Sprintf("mount%g", k + 1)) = {s()};
EndFor
pr() = Surface In BoundingBox{x0 - eps, hc - tw - eps, -skirt_depth - eps,
                              x1 + eps, hc + eps, -skirt_depth + eps};
pr() += Surface In BoundingBox{x0 - eps, -hc - eps, -skirt_depth - eps,
                               x1 + eps, -hc + tw + eps, -skirt_depth + eps};
Physical Surface("pan_rail") = {pr()};
// outer side walls, both sides: the skirt's (|y| = hc) and the water jacket's
// (|y| = hu) outside faces, the block's largest radiating faces (ERP outputs)
sw() = Surface In BoundingBox{x0 - eps, hc - eps, -skirt_depth - eps, x1 + eps, hc + eps, deck_height + eps};
sw() += Surface In BoundingBox{x0 - eps, -hc - eps, -skirt_depth - eps, x1 + eps, -hc + eps, deck_height + eps};
sw() += Surface In BoundingBox{x0 - eps, hu - eps, -skirt_depth - eps, x1 + eps, hu + eps, deck_height + eps};
sw() += Surface In BoundingBox{x0 - eps, -hu - eps, -skirt_depth - eps, x1 + eps, -hu + eps, deck_height + eps};
Physical Surface("side_walls") = {sw()};
If (flywheel_flange)
  xr = x1 + flange_thickness;
  fr() = Surface In BoundingBox{xr - eps, -flange_half_width - eps, flange_bottom - eps,
                                xr + eps, flange_half_width + eps, flange_top + eps};
  Physical Surface("flywheel_housing") = {fr()};
EndIf
Physical Volume("block") = {body()};

Mesh.CharacteristicLengthMax = mesh_size;
Mesh.CharacteristicLengthMin = 0.1 * mesh_size;
// Element size on curved faces: at most 2 pi R / curve_elements. Second-order
// elements curved onto the bores of the thin liners get negative Jacobians when
// they are long compared to the liner wall; 16 per circle keeps every element
// valid without optimisation at mesh_size 20..40, coarser settings (e.g. 8 at
// mesh_size 50) rely on the high-order optimiser (HighOrderOptimize), which
// moves nodes to restore positive Jacobians (boundary nodes stay on the CAD).
Mesh.CharacteristicLengthFromCurvature = 1;
Mesh.MinimumElementsPerTwoPi = curve_elements;
Mesh.ElementOrder = 2;
Mesh.SecondOrderLinear = 0;
Mesh.HighOrderOptimize = 1;
Mesh.SaveGroupsOfNodes = 1;
