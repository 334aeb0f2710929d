// The POV-Ray comparison scene (scripts/compare-povray), the same as
// scenes/dragon_mirrors.toml: the libcgal-demo dragon and a sphere, both mirrors, on a
// checker plane, one light. dragon_mesh.inc is written by scripts/compare-povray from
// data/meshes/ChineseDragon-10kv.obj (the mesh is not in the repository); POV-Ray finds it
// on its library path (+L data/povray).
//   povray +Iscenes/dragon_mirrors.pov +Ldata/povray +W640 +H480 -A +WT1 +Oout/dragon.png
#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 17 ambient_light rgb 1 }

camera {
  perspective
  location <-3.6, 70.7, -790.8>
  look_at <-3.6, 3.7, -982.0>
  right -x * 640 / 480  // right-handed, as rt2
  angle 51.7  // horizontal: rt2's vertical 40 degrees at 4:3
}
background { rgb <0.05, 0.05, 0.08> }
light_source { <123.0, 256.9, -771.0> rgb 1 }

#declare Mirror = finish { ambient 0.2 * 0.05 diffuse 0.08 phong 0.9 phong_size 200 reflection 0.8 }

plane {
  y, -52.7
  pigment { checker rgb 0.8 rgb 0.3 scale 21.1 }
  finish { ambient 0.2 * 0.5 diffuse 1 }
}
sphere { <-75.0, -12.7, -1000.0>, 40 pigment { rgb 1 } finish { Mirror } }
#include "dragon_mesh.inc"
object { DragonMesh pigment { rgb 1 } finish { Mirror } }
