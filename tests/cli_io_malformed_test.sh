#!/usr/bin/env bash
# Malformed and nonsense input files, end to end: every case must exit 2 with exactly one line
# on stderr that names the file (and the JSON key or element), and write no output file.
# Usage: cli_io_malformed_test.sh PARALLAX_BINARY SOURCE_DIR
# 178 cases (each `bad`, `bad_scene`, `bad_display` or `bad_mesh` call is one case: exit 2, one
# line on stderr naming the file and key, no output file); the script prints the count it ran.
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"

cases=0
# bad NAME NEEDLE OUTPUT ARGS...: exit 2, one line naming NEEDLE, OUTPUT not written.
bad() {
  local name=$1 needle=$2 output=$3
  shift 3
  cases=$((cases + 1))
  check "$name: exit 2" run 2 "$@"
  check "$name: one line naming '$needle'" one_line_naming "$needle"
  check "$name: no output" test ! -e "$output"
}
# bad_scene NAME KEY JSON: a scene file, viewed.
bad_scene() {
  printf '%s' "$3" >"$tmp/scene.json"
  bad "scene $1" "scene.json: $2" "$tmp/v.png" view "$tmp/scene.json" --size 8x8 --spp 1 \
    -o "$tmp/v.png"
}
# bad_display NAME KEY JSON: a display file, designed (the design goes to stdout: none).
bad_display() {
  printf '%s' "$3" >"$tmp/display.json"
  bad "display $1" "display.json: $2" "$tmp/rd" render --display "$tmp/display.json" --spp 1 \
    -o "$tmp/rd"
}
# bad_mesh NAME NEEDLE FILE: a mesh file viewed as a scene.
bad_mesh() {
  bad "mesh $1" "$2" "$tmp/m.png" view "$3" --size 8x8 --spp 1 -o "$tmp/m.png"
}
sphere() { printf '{"objects": [{"shape": "sphere", "radius": 1%s}]%s}' "$1" "${2:-}"; }
cam() { printf ', "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]%s}' "$1"; }

# ---- Scene keys: wrong type, out of range, overflow ----------------------------------------
bad_scene "radius string" "/objects/0/radius" '{"objects": [{"shape": "sphere", "radius": "1"}]}'
bad_scene "radius negative" "/objects/0/radius" '{"objects": [{"shape": "sphere", "radius": -1}]}'
bad_scene "radius zero" "/objects/0/radius" '{"objects": [{"shape": "sphere", "radius": 0}]}'
bad_scene "radius 1e39" "/objects/0/radius" '{"objects": [{"shape": "sphere", "radius": 1e39}]}'
bad_scene "radius 1e400" "/objects/0/radius" '{"objects": [{"shape": "sphere", "radius": 1e400}]}'
bad_scene "radius 1e-300" "/objects/0/radius" '{"objects": [{"shape": "sphere", "radius": 1e-300}]}'
bad_scene "radius null" "/objects/0/radius" '{"objects": [{"shape": "sphere", "radius": null}]}'
bad_scene "radius array" "/objects/0/radius" '{"objects": [{"shape": "sphere", "radius": [1]}]}'
bad_scene "center 1e39" "/objects/0/center/0" "$(sphere ', "center": [1e39, 0, 0]')"
bad_scene "center 1e7" "/objects/0/center" "$(sphere ', "center": [0, 1e7, 0]')"
bad_scene "center two numbers" "/objects/0/center" "$(sphere ', "center": [0, 0]')"
bad_scene "center string" "/objects/0/center" "$(sphere ', "center": "origin"')"
bad_scene "center overflow" "/objects/0/center/2" "$(sphere ', "center": [0, 0, -1e999]')"
bad_scene "name number" "/objects/0/name" "$(sphere ', "name": 3')"
bad_scene "shape number" "/objects/0/shape" '{"objects": [{"shape": 1, "radius": 1}]}'
bad_scene "shape unknown" "/objects/0/shape" '{"objects": [{"shape": "blob"}]}'
bad_scene "light_samples 0" "/objects/0/light_samples" "$(sphere ', "light_samples": 0')"
bad_scene "light_samples 1.5" "/objects/0/light_samples" "$(sphere ', "light_samples": 1.5')"
bad_scene "light_two_sided number" "/objects/0/light_two_sided" "$(sphere ', "light_two_sided": 1')"
bad_scene "scale 1e30" "/objects/0/transform/0/scale" "$(sphere ', "transform": [{"scale": 1e30}]')"
bad_scene "scale 1e-30" "/objects/0/transform/0/scale" "$(sphere ', "transform": [{"scale": 1e-30}]')"
bad_scene "translate 1e39" "/objects/0/transform/0/translate/0" \
  "$(sphere ', "transform": [{"translate": [1e39, 0, 0]}]')"
bad_scene "rotate angle 1e300" "/objects/0/transform/0/rotate/angle" \
  "$(sphere ', "transform": [{"rotate": {"angle": 1e300, "axis": [0, 1, 0]}}]')"
bad_scene "rotate axis zero" "/objects/0/transform/0/rotate/axis" \
  "$(sphere ', "transform": [{"rotate": {"angle": 10, "axis": [0, 0, 0]}}]')"
bad_scene "matrix 1e39" "/objects/0/transform/matrix/0" \
  "$(sphere ', "transform": {"matrix": [1e39,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}')"
bad_scene "scales overflow together" "/objects/0/transform/" \
  "$(sphere ', "transform": [{"scale": 1e5}, {"scale": 1e5}, {"scale": 1e5}, {"scale": 1e5}, {"scale": 1e5}, {"scale": 1e5}, {"scale": 1e5}, {"scale": 1e5}]')"
bad_scene "box size 1e39" "/objects/0/size" '{"objects": [{"shape": "box", "size": 1e39}]}'
bad_scene "box size 0" "/objects/0/size" '{"objects": [{"shape": "box", "size": [1, 0, 1]}]}'
bad_scene "box min 1e39" "/objects/0/min/0" \
  '{"objects": [{"shape": "box", "min": [1e39, 0, 0], "max": [1, 1, 1]}]}'
bad_scene "box max below min" "/objects/0/max" \
  '{"objects": [{"shape": "box", "min": [0, 0, 0], "max": [1, -1, 1]}]}'
bad_scene "quad edge 1e39" "/objects/0/edge_u/0" \
  '{"objects": [{"shape": "quad", "corner": [0,0,0], "edge_u": [1e39,0,0], "edge_v": [0,1,0]}]}'
bad_scene "quad corner string" "/objects/0/corner" \
  '{"objects": [{"shape": "quad", "corner": "a", "edge_u": [1,0,0], "edge_v": [0,1,0]}]}'
bad_scene "plane size 1e39" "/objects/0/size" '{"objects": [{"shape": "plane", "size": 1e39}]}'
bad_scene "plane size 1e-30" "/objects/0/size/1" '{"objects": [{"shape": "plane", "size": [1, 1e-30]}]}'
bad_scene "plane normal zero" "/objects/0/normal" \
  '{"objects": [{"shape": "plane", "size": 1, "normal": [0, 0, 0]}]}'
bad_scene "mesh file number" "/objects/0/file" '{"objects": [{"shape": "mesh", "file": 7}]}'
bad_scene "mesh file missing" "/objects/0/file" '{"objects": [{"shape": "mesh", "file": "no.obj"}]}'
bad_scene "material color 2" "/objects/0/material/color" "$(sphere ', "material": {"color": 2}')"
bad_scene "material color NaN-like" "/objects/0/material/color" "$(sphere ', "material": {"color": "NaN"}')"
bad_scene "material emission 1e39" "/objects/0/material/emission/0" \
  "$(sphere ', "material": {"emission": [1e39, 0, 0]}')"
bad_scene "material emission 1e30" "/objects/0/material/emission" \
  "$(sphere ', "material": {"emission": [1e30, 0, 0]}')"
bad_scene "emission_strength 1e39" "/objects/0/material/emission_strength" \
  "$(sphere ', "material": {"emission_strength": 1e39}')"
bad_scene "emission_strength negative" "/objects/0/material/emission_strength" \
  "$(sphere ', "material": {"emission_strength": -1}')"
bad_scene "mirror 1.5" "/objects/0/material/mirror" "$(sphere ', "material": {"mirror": 1.5}')"
bad_scene "checker size 1e39" "/textures/c/size" \
  "{\"textures\": {\"c\": {\"type\": \"checker\", \"size\": 1e39}}, \"objects\": []}"
bad_scene "checker size 0" "/textures/c/size" \
  "{\"textures\": {\"c\": {\"type\": \"checker\", \"size\": 0}}, \"objects\": []}"
bad_scene "ambient 1e39" "/ambient" "$(sphere '' ', "ambient": 1e39')"
bad_scene "background negative" "/background/1" "$(sphere '' ', "background": [0, -1, 0]')"
bad_scene "max_depth 1e9" "/max_depth" "$(sphere '' ', "max_depth": 1e9')"
bad_scene "version 2" "/version" "$(sphere '' ', "version": 2')"
bad_scene "fov 1e-30" "/camera/fov" "$(sphere '' "$(cam ', "fov": 1e-30')")"
bad_scene "fov 179.5" "/camera/fov" "$(sphere '' "$(cam ', "fov": 179.5')")"
bad_scene "fov string" "/camera/fov" "$(sphere '' "$(cam ', "fov": "wide"')")"
bad_scene "eye 1e39" "/camera/eye/2" \
  "$(sphere '' ', "camera": {"eye": [0, 0, 1e39], "look_at": [0, 0, 0]}')"
bad_scene "look_at equals eye" "/camera/look_at" \
  "$(sphere '' ', "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 5]}')"
bad_scene "up zero" "/camera/up" "$(sphere '' "$(cam ', "up": [0, 0, 0]')")"
bad_scene "point light intensity 1e39" "/lights/0/intensity" \
  "$(sphere '' ', "lights": [{"type": "point", "position": [0, 5, 0], "intensity": 1e39}]')"
bad_scene "point light position 1e39" "/lights/0/position/1" \
  "$(sphere '' ', "lights": [{"type": "point", "position": [0, 1e39, 0], "intensity": 1}]')"
bad_scene "quad light edge 1e39" "/lights/0/edge_u/0" \
  "$(sphere '' ', "lights": [{"type": "quad", "corner": [0,5,0], "edge_u": [1e39,0,0], "edge_v": [0,0,1], "radiance": 1}]')"
bad_scene "light samples 0" "/lights/0/samples" \
  "$(sphere '' ', "lights": [{"type": "quad", "corner": [0,5,0], "edge_u": [1,0,0], "edge_v": [0,0,1], "radiance": 1, "samples": 0}]')"
bad_scene "directional direction zero" "/lights/0/direction" \
  "$(sphere '' ', "lights": [{"type": "directional", "direction": [0,0,0], "irradiance": 1}]')"
bad_scene "display width 1e39" "/display/width" "$(sphere '' ', "display": {"width": 1e39}')"
bad_scene "display center 1e39" "/display/center/0" "$(sphere '' ', "display": {"center": [1e39, 0, 0]}')"
bad_scene "duplicate key" "/objects/0/radius" '{"objects": [{"shape": "sphere", "radius": 1, "radius": 2}]}'
bad_scene "number overflow" "/objects/0/radius" '{"objects": [{"shape": "sphere", "radius": 1e400}]}'
bad_scene "newline in key" '/objects/0/bad\nkey' \
  "$(printf '{"objects": [{"shape": "sphere", "radius": 1, "bad\\nkey": 1}]}')"
bad_scene "tab and escape in key" '/x\t\x1b' "$(printf '{"x\\t\\u001b": 1}')"
head -c 70000 /dev/zero | tr '\0' '[' >"$tmp/deep.json"
bad "scene nested 70000 deep" "deep.json: /0/0" "$tmp/v.png" view "$tmp/deep.json" --size 8x8 -o "$tmp/v.png"
bad "scene truncated" "scene.json" "$tmp/v.png" view "$tmp/scene.json" --size 8x8 -o "$tmp/v.png"

# ---- Display keys --------------------------------------------------------------------------
bad_display "pitch 1e-300" "/image_layer/pixel_pitch_mm" '{"image_layer": {"pixel_pitch_mm": 1e-300}}'
bad_display "pitch 1e300" "/image_layer/pixel_pitch_mm" '{"image_layer": {"pixel_pitch_mm": 1e300}}'
bad_display "pitch string" "/image_layer/pixel_pitch_mm" '{"image_layer": {"pixel_pitch_mm": "0.3"}}'
bad_display "mask pitch 20" "/mask_layer/pixel_pitch_mm" '{"mask_layer": {"pixel_pitch_mm": 20}}'
bad_display "resolution 0" "/image_layer/resolution/0" '{"image_layer": {"resolution": [0, 10]}}'
bad_display "resolution huge" "/image_layer/resolution/1" '{"image_layer": {"resolution": [10, 1e9]}}'
bad_display "resolution one number" "/image_layer/resolution" '{"image_layer": {"resolution": [10]}}'
bad_display "subpixels unknown" "/image_layer/subpixels" '{"image_layer": {"subpixels": "RGBW"}}'
bad_display "gap 1e300" "/gap_mm" '{"gap_mm": 1e300}'
bad_display "gap 0" "/gap_mm" '{"gap_mm": 0}'
bad_display "gap -3" "/gap_mm" '{"gap_mm": -3}'
bad_display "gap overflow" "/gap_mm" '{"gap_mm": 1e400}'
bad_display "gap string" "/gap_mm" '{"gap_mm": "3"}'
bad_display "distance 1e300" "/view_distance_mm" '{"view_distance_mm": 1e300}'
bad_display "distance 1" "/view_distance_mm" '{"view_distance_mm": 1}'
bad_display "distance negative" "/view_distance_mm" '{"view_distance_mm": -600}'
bad_display "views 1e300" "/views" '{"views": 1e300}'
bad_display "views 1" "/views" '{"views": 1}'
bad_display "zone width 1e300" "/view_zone/width_mm" '{"view_zone": {"width_mm": 1e300}}'
bad_display "zone centre 1e300" "/view_zone/center_x_mm" '{"view_zone": {"center_x_mm": 1e300}}'
bad_display "zone height 1e300" "/view_zone/height_mm" '{"view_zone": {"height_mm": 1e300}}'
bad_display "slit period 1e300" "/slit_period_px" '{"screen_period_px": 9, "slit_period_px": 1e300}'
bad_display "screen period only" "/slit_period_px" '{"screen_period_px": 9}'
bad_display "duty cycle 2" "/mask/duty_cycle" '{"mask": {"duty_cycle": 2}}'
bad_display "phase 1e300" "/mask/phase_px" '{"mask": {"phase_px": 1e300}}'
bad_display "panel offset 1e300" "/mask/panel_offset_px" '{"mask": {"panel_offset_px": 1e300}}'
bad_display "slant 1e300" "/mask/angle_deg" '{"mask": {"type": "slanted", "angle_deg": 1e300}}'
bad_display "wavelength 1e300" "/mask/wavelength_mm" '{"mask": {"type": "wiggling", "wavelength_mm": 1e300}}'
bad_display "amplitude 1e300" "/mask/amplitude_mm" '{"mask": {"type": "wiggling", "wavelength_mm": 7, "amplitude_mm": 1e300}}'
bad_display "jitter 1e300" "/mask/jitter" '{"mask": {"type": "jittered", "jitter": 1e300}}'
bad_display "pinhole period 1e300" "/mask/vertical_period_px" '{"mask": {"type": "pinholes", "vertical_period_px": 1e300}}'
bad_display "mask type" "/mask/type" '{"mask": {"type": "holes"}}'
bad_display "layer order" "/layer_order" '{"layer_order": "sideways"}'
bad_display "virtual gap 1e300" "/virtual/gap_mm" '{"virtual": {"gap_mm": 1e300}}'
bad_display "virtual distance 1e300" "/virtual/distance_mm" '{"virtual": {"distance_mm": 1e300}}'
bad_display "virtual distance word" "/virtual/distance_mm" '{"virtual": {"distance_mm": "far"}}'
bad_display "subpixel_rays number" "/subpixel_rays" '{"subpixel_rays": 1}'
bad_display "unknown key" "/gap" '{"gap": 3}'
bad_display "newline in key" '/a\nb' "$(printf '{"a\\nb": 3}')"

# ---- Lenticular calibration (visual.json) -------------------------------------------------
cal() {  # cal 'EXTRA FIELDS'  (overrides come later and win... fields must be unique: replace)
  printf '{"pitch": %s, "slope": %s, "center": 0.1, "viewCone": %s, "invView": 1, "DPI": %s, "screenW": 1536, "screenH": 2048}' \
    "$1" "$2" "$3" "$4"
}
for spec in "pitch:1e300:-6:40:324" "pitch:1e-300:-6:40:324" "slope:47:1e-300:40:324" \
  "viewCone:47:-6:1e-30:324" "viewCone:47:-6:179.9:324" "DPI:47:-6:40:1e300" "DPI:47:-6:40:1e-300"; do
  IFS=: read -r key p s v d <<<"$spec"
  cal "$p" "$s" "$v" "$d" >"$tmp/visual.json"
  bad "visual.json $key $p $s $v $d" "visual.json: /$key" "$tmp/lr" lenticular render "$tmp/visual.json" \
    --spp 1 -o "$tmp/lr"
done

# ---- Formats only assimp reads (docs/import.md): its message on one line after the file --------
printf 'Kaydara FBX Binary  \000\032\000\350\034\000\000garbage' >"$tmp/cut.fbx"  # header, then garbage
bad_mesh "fbx truncated" "cut.fbx: assimp cannot read it" "$tmp/cut.fbx"
printf '<?xml version="1.0"?>\n<COLLADA version="1.4.1"><library_geometries><geometry id="g"><mesh>' >"$tmp/cut.dae"
bad_mesh "dae truncated" "cut.dae: assimp cannot read it" "$tmp/cut.dae"
printf 'no Blender file at all\n' >"$tmp/bad.blend"
bad_mesh "blend without its magic" "bad.blend: assimp cannot read it" "$tmp/bad.blend"

# ---- Meshes: truncated, lying about counts, NaN --------------------------------------------
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement vertex 2\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' >"$tmp/twov.ply"
bad_mesh "ply second vertex element" "twov.ply: the header declares more than one 'vertex'" "$tmp/twov.ply"
printf 'ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header' >"$tmp/eof.ply"
bad_mesh "ply header at EOF" "eof.ply" "$tmp/eof.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 1000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n' >"$tmp/count.ply"
bad_mesh "ply vertex count lies" "count.ply: element 'vertex' announces 1000000" "$tmp/count.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n' >"$tmp/index.ply"
bad_mesh "ply index out of range" "index.ply: face 0: vertex index 7" "$tmp/index.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n' >"$tmp/nan.ply"
bad_mesh "ply NaN" "nan.ply: vertex 1: coordinate is NaN" "$tmp/nan.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n' >"$tmp/short.ply"
bad_mesh "ply truncated" "short.ply: element 'vertex' announces 3" "$tmp/short.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nend_header\n' >"$tmp/noz.ply"
bad_mesh "ply without z" "noz.ply: the vertex element lacks" "$tmp/noz.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n' >"$tmp/nohead.ply"
bad_mesh "ply without end_header" "nohead.ply: the header has no end_header" "$tmp/nohead.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 1e39\n' >"$tmp/big.ply"
bad_mesh "ply coordinate beyond float" "big.ply: vertex 0: coordinate is infinite" "$tmp/big.ply"
# A face index stored as the double 1e300: quoted as given, no integer conversion.
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar double vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 1e300\n' >"$tmp/dindex.ply"
bad_mesh "ply double index 1e300" "dindex.ply: face 0: vertex index 1e+300 is out of range (3 vertices)" "$tmp/dindex.ply"
# OFF (our reader): 10^9 vertices in 25 bytes refused before allocating (a peak resident set
# far below the 12 GB they would take; measured by GNU time, since an address-space limit
# cannot be set under AddressSanitizer, whose shadow alone reserves terabytes); an index 7 of 3
# vertices named with its line; NaN; truncation; binary.
printf 'OFF\n1000000000 0 0\n0 0 0\n' >"$tmp/billion.off"
check "mesh off 10^9 vertices: exit 2" \
  bash -c "/usr/bin/time -f %M -o '$tmp/peak' '$bin' info '$tmp/billion.off' 2>'$tmp/err'; test \$? -eq 2"
check "mesh off 10^9 vertices: peak resident set under 512 MB" \
  bash -c "test \$(tail -n 1 '$tmp/peak') -lt 524288"
check "mesh off 10^9 vertices: the message" \
  grep -q "billion.off: line 2: the header announces 1000000000 vertices and 0 faces, more than the 6 bytes" "$tmp/err"
printf 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n' >"$tmp/index.off"
bad_mesh "off index out of range" "index.off: line 6: face 0: vertex index 7 is out of range (3 vertices)" "$tmp/index.off"
printf 'OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n' >"$tmp/nan.off"
bad_mesh "off NaN" "nan.off: line 4: vertex 1: coordinate is NaN" "$tmp/nan.off"
printf 'OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' >"$tmp/short.off"
bad_mesh "off truncated" "short.off: the file ends after 1 of 2 faces" "$tmp/short.off"
printf 'OFF BINARY\n\0\0\0\3' >"$tmp/binary.off"
bad_mesh "off binary" "binary.off: line 1: binary OFF" "$tmp/binary.off"
{ head -c 80 /dev/zero; printf '\x10\x27\x00\x00'; head -c 50 /dev/zero; } >"$tmp/lie.stl"
bad_mesh "stl count lies" "lie.stl: as binary STL, the header announces 10000" "$tmp/lie.stl"
head -c 40 /dev/zero >"$tmp/tiny.stl"
bad_mesh "stl too short" "tiny.stl: too short for a binary STL" "$tmp/tiny.stl"
printf 'solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0\n' >"$tmp/cut.stl"
bad_mesh "stl ascii truncated" "cut.stl: line" "$tmp/cut.stl"
printf 'solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 nan\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid x\n' >"$tmp/nan.stl"
bad_mesh "stl NaN" "nan.stl: vertex 0: coordinate is NaN" "$tmp/nan.stl"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n' >"$tmp/index.obj"
bad_mesh "obj index out of range" "index.obj: face 0: vertex index 9" "$tmp/index.obj"
printf 'v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$tmp/nan.obj"
bad_mesh "obj NaN" "nan.obj: line 1: vertex coordinate is NaN" "$tmp/nan.obj"
printf 'v 0 0\nf 1 1 1\n' >"$tmp/short.obj"
bad_mesh "obj short vertex" "short.obj: line 1: 'v' needs 3 numbers" "$tmp/short.obj"
mkdir -p "$tmp/folder.mtl"
printf 'mtllib folder.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$tmp/mtldir.obj"
bad_mesh "obj mtl is a folder" "folder.mtl: is a folder, not a file" "$tmp/mtldir.obj"
ln -sf /dev/zero "$tmp/zero.mtl"
printf 'mtllib zero.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$tmp/mtlzero.obj"
bad_mesh "obj mtl is /dev/zero" "zero.mtl: not a regular file (a character device)" "$tmp/mtlzero.obj"
mkfifo "$tmp/fifo.mtl"
printf 'mtllib fifo.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$tmp/mtlfifo.obj"
bad_mesh "obj mtl is a FIFO" "fifo.mtl: not a regular file (a named pipe (FIFO))" "$tmp/mtlfifo.obj"
printf 'newmtl m\nmap_Kd tex.png\n' >"$tmp/tex.mtl"
mkdir -p "$tmp/otex" && cp "$tmp/tex.mtl" "$tmp/otex/tex.mtl" && mkfifo "$tmp/otex/tex.png"
printf 'mtllib tex.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n' >"$tmp/otex/t.obj"
bad_mesh "obj texture is a FIFO" "tex.png: not a regular file (a named pipe (FIFO))" "$tmp/otex/t.obj"
nodes=$(for i in $(seq 0 9998); do printf '{"children": [%d]},' $((i + 1)); done)
printf '{"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [%s{}]}' "$nodes" >"$tmp/deep.gltf"
bad_mesh "gltf chain 10000 deep" "deep.gltf: the node tree is more than 1000 levels deep" "$tmp/deep.gltf"
printf '{"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"children": [1]}, {"children": [0]}]}' >"$tmp/cycle.gltf"
bad_mesh "gltf cycle" "cycle.gltf: node 0 is its own ancestor" "$tmp/cycle.gltf"
printf '{"asset": {"version": "2.0"}, "scenes": [{"nodes": [5]}], "nodes": [{}]}' >"$tmp/node.gltf"
bad_mesh "gltf missing node" "node.gltf: node index 5 does not exist" "$tmp/node.gltf"
printf '{"asset": {"version": "1.0"}}' >"$tmp/v1.gltf"
bad_mesh "gltf version 1" "v1.gltf" "$tmp/v1.gltf"
printf '{"asset": ' >"$tmp/cut.gltf"
bad_mesh "gltf truncated JSON" "cut.gltf" "$tmp/cut.gltf"
# A GLB whose image buffer view runs past its 8-byte buffer.
json='{"asset":{"version":"2.0"},"buffers":[{"byteLength":8}],"bufferViews":[{"buffer":0,"byteLength":100000}],"images":[{"bufferView":0,"mimeType":"image/png"}]}'
while [ $(( ${#json} % 4 )) -ne 0 ]; do json="$json "; done
le32() { printf "\\x$(printf %02x $(($1 & 255)))\\x$(printf %02x $((($1 >> 8) & 255)))\\x$(printf %02x $((($1 >> 16) & 255)))\\x$(printf %02x $((($1 >> 24) & 255)))"; }
{ printf 'glTF'; le32 2; le32 $((12 + 8 + ${#json} + 8 + 8)); le32 ${#json}; printf 'JSON'
  printf '%s' "$json"; le32 8; printf 'BIN\0'; head -c 8 /dev/zero; } >"$tmp/short.glb"
bad_mesh "glb image past its buffer" "short.glb: image 0: its buffer view" "$tmp/short.glb"
head -c 12 "$tmp/short.glb" >"$tmp/head.glb"
bad_mesh "glb header only" "head.glb" "$tmp/head.glb"
: >"$tmp/empty.obj"
bad_mesh "empty obj" "empty.obj: file is empty" "$tmp/empty.obj"

# ---- Textures ------------------------------------------------------------------------------
texscene() {
  printf '{"textures": {"t": {"type": "image", "file": "%s"}}, "objects": [{"shape": "sphere", "radius": 1, "material": {"texture": "t"}}]}' "$1" >"$tmp/scene.json"
}
be32() { printf "\\x$(printf %02x $((($1 >> 24) & 255)))\\x$(printf %02x $((($1 >> 16) & 255)))\\x$(printf %02x $((($1 >> 8) & 255)))\\x$(printf %02x $(($1 & 255)))"; }
{ printf '\x89PNG\r\n\x1a\n'; be32 13; printf 'IHDR'; be32 30000; be32 30000; printf '\x08\x06\0\0\0'; be32 0
  head -c 260000 /dev/zero; } >"$tmp/huge.png"
texscene huge.png
bad "texture decodes to GiB" "scene.json: /textures/t/file: $tmp/huge.png: needs about" "$tmp/v.png" \
  view "$tmp/scene.json" --size 8x8 -o "$tmp/v.png"
{ printf '\0\0\x02\0\0\0\0\0\0\0\0\0\x20\x4e\x20\x4e\x18\0'; head -c 96 /dev/zero; } >"$tmp/tga.png"
texscene tga.png
bad "TGA named .png" "/textures/t/file: $tmp/tga.png: not a readable image" "$tmp/v.png" \
  view "$tmp/scene.json" --size 8x8 -o "$tmp/v.png"
cp "$tmp/tga.png" "$tmp/big.tga"
texscene big.tga
bad "TGA of 20000x20000" "big.tga: needs about" "$tmp/v.png" view "$tmp/scene.json" --size 8x8 -o "$tmp/v.png"
{ printf 'P6\n40000 40000\n255\n'; head -c 30 /dev/zero; } >"$tmp/huge.ppm"
texscene huge.ppm
bad "PNM of 40000x40000" "huge.ppm: needs about" "$tmp/v.png" view "$tmp/scene.json" --size 8x8 -o "$tmp/v.png"
printf 'not an image at all' >"$tmp/text.png"
texscene text.png
bad "text named .png" "text.png: not a readable image" "$tmp/v.png" view "$tmp/scene.json" --size 8x8 -o "$tmp/v.png"
texscene /dev/zero
bad "texture /dev/zero" "/textures/t/file: /dev/zero: not a regular file (a character device)" "$tmp/v.png" \
  view "$tmp/scene.json" --size 8x8 -o "$tmp/v.png"
texscene /dev/urandom
bad "texture /dev/urandom" "/dev/urandom: not a regular file (a character device)" "$tmp/v.png" \
  view "$tmp/scene.json" --size 8x8 -o "$tmp/v.png"
mkdir -p "$tmp/dir.png"
texscene dir.png
bad "texture folder" "dir.png: is a folder, not a file" "$tmp/v.png" view "$tmp/scene.json" --size 8x8 -o "$tmp/v.png"
mkfifo "$tmp/fifo.png"
texscene fifo.png
bad "texture FIFO" "fifo.png: not a regular file (a named pipe (FIFO))" "$tmp/v.png" \
  view "$tmp/scene.json" --size 8x8 -o "$tmp/v.png"

# ---- Layers for simulate: PFM with NaN, non-regular files ---------------------------------
check "a render to simulate" run 0 render --display "$src/displays/default.json" --spp 1 -o "$tmp/r" \
  --linear
{ printf 'PF\n1 1\n-1\n'; printf '\0\0\xc0\x7f\0\0\xc0\x7f\0\0\xc0\x7f'; } >"$tmp/nan.pfm"
bad "simulate NaN PFM layer" "nan.pfm: pixel (0, 0)" "$tmp/s.png" simulate "$tmp/r" --image "$tmp/nan.pfm" \
  --eye 0,0,600 -o "$tmp/s.png"
bad "simulate /dev/zero mask" "/dev/zero: not a regular file" "$tmp/s.png" simulate "$tmp/r" \
  --mask /dev/zero --eye 0,0,600 -o "$tmp/s.png"
bad "simulate folder as display" "is a folder, not a file" "$tmp/s.png" simulate "$tmp/r" \
  --display "$tmp/r" --eye 0,0,600 -o "$tmp/s.png"

# ---- Non-regular files for every input kind ----------------------------------------------
mkfifo "$tmp/fifo.json" "$tmp/fifo.ply" "$tmp/visual-fifo.json"
mkdir -p "$tmp/folder.json" "$tmp/folder.obj"
bad "scene /dev/zero" "/dev/zero: not a regular file (a character device)" "$tmp/v.png" view /dev/zero -o "$tmp/v.png"
bad "scene /dev/urandom" "/dev/urandom: not a regular file (a character device)" "$tmp/v.png" \
  view /dev/urandom -o "$tmp/v.png"
bad "scene FIFO" "fifo.json: not a regular file (a named pipe (FIFO))" "$tmp/v.png" view "$tmp/fifo.json" -o "$tmp/v.png"
bad "scene folder" "folder.json: is a folder, not a file" "$tmp/v.png" view "$tmp/folder.json" -o "$tmp/v.png"
bad "display /dev/zero" "/dev/zero: not a regular file (a character device)" "$tmp/rd" \
  render --display /dev/zero -o "$tmp/rd"
bad "display /dev/urandom" "/dev/urandom: not a regular file" "$tmp/rd" render --display /dev/urandom -o "$tmp/rd"
bad "display FIFO" "fifo.json: not a regular file (a named pipe (FIFO))" "$tmp/rd" \
  render --display "$tmp/fifo.json" -o "$tmp/rd"
bad "display folder" "folder.json: is a folder, not a file" "$tmp/rd" render --display "$tmp/folder.json" -o "$tmp/rd"
bad "mesh FIFO" "fifo.ply: not a regular file (a named pipe (FIFO))" "$tmp/m.png" view "$tmp/fifo.ply" -o "$tmp/m.png"
bad "mesh folder" "folder.obj: is a folder, not a file" "$tmp/m.png" view "$tmp/folder.obj" -o "$tmp/m.png"
printf '{"objects": [{"shape": "mesh", "file": "fifo.ply"}]}' >"$tmp/scene.json"
bad "scene mesh FIFO" "scene.json: /objects/0/file: $tmp/fifo.ply: not a regular file" "$tmp/v.png" \
  view "$tmp/scene.json" -o "$tmp/v.png"
printf '{"objects": [{"shape": "mesh", "file": "folder.obj"}]}' >"$tmp/scene.json"
bad "scene mesh folder" "scene.json: /objects/0/file: $tmp/folder.obj: is a folder" "$tmp/v.png" \
  view "$tmp/scene.json" -o "$tmp/v.png"
bad "visual.json /dev/zero" "/dev/zero: not a regular file" "$tmp/lr" lenticular render /dev/zero -o "$tmp/lr"
bad "visual.json FIFO" "visual-fifo.json: not a regular file (a named pipe (FIFO))" "$tmp/lr" \
  lenticular render "$tmp/visual-fifo.json" -o "$tmp/lr"
bad "visual.json folder" "folder.json: is a folder, not a file" "$tmp/lr" lenticular render "$tmp/folder.json" -o "$tmp/lr"

echo "$cases cases"
check "all 178 cases ran" test "$cases" -eq 178
cli_summary
