// The built-in scene (src/parallax/scene/scene.cpp, defaultScene) for POV-Ray 3.7: the peer
// route's input in examples/povray/run.sh, which renders one ordinary view per design eye of
// the built-in display and interleaves them with `parallax interlace` (docs/speed.md).
// POV-Ray is left-handed: its z is parallax's -z. One unit is 131.8 mm (the display, 527 mm
// wide, is 4 units across). EYE_X is the view's eye, declared on the command line.
#version 3.7;
#ifndef (EYE_X) #declare EYE_X = 0; #end
#declare D = 600 / 131.82;  // the design view distance, 600 mm
global_settings { assumed_gamma 1.0 ambient_light rgb 1 }
background { rgb <0.02, 0.025, 0.035> }
// Off-axis: the film is the display's window (4 x 2.25 units, centred at the origin) seen from
// the eye, so every view frames the same window, as parallax's design-eye views do.
camera {
  perspective
  location <EYE_X, 0, -D>
  direction <-EYE_X, 0, D>
  right <4, 0, 0>
  up <0, 2.25, 0>
}
// A square area light above and to the left, 4 x 4 samples: soft shadows.
light_source {
  <-1.8, 3.2, -0.8>, rgb 2.4
  area_light <0.8, 0, 0>, <0, 0, 0.8>, 4, 4
  jitter
}
#declare Matte = finish { diffuse 1 ambient 0.04 };
polygon {
  5, <-6, -1.1, -1.5>, <6, -1.1, -1.5>, <6, -1.1, 12.5>, <-6, -1.1, 12.5>, <-6, -1.1, -1.5>
  pigment { checker rgb 0.75, rgb 0.08 scale 0.5 }
  finish { Matte }
}
box {
  <-0.45, -0.35, -0.45>, <0.45, 0.45, 0.45>
  rotate <-15, 0, 0>
  rotate <0, -30, 0>
  translate <0.1, 0, 0.2>
  pigment { rgb <0.75, 0.22, 0.12> }
  finish { Matte }
}
